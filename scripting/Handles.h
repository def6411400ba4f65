#pragma once
// The Lua values that stand for kernel objects.
//
// A document is a full userdata holding a Document (metatable "netsculpt.Document"; __gc runs
// its destructor). Its user value is a table of two weak-valued caches, so the same id always
// gives the same handle userdata while it is referenced (handles work as table keys).
//
// A piece or rail handle is a full userdata {id} (metatables "netsculpt.Piece" and
// "netsculpt.Rail") whose user value is its document, which it keeps alive. Handles print as
// "piece 3" / "rail 1", compare equal by id, and are checked for liveness on every use: a
// removed one raises "piece 7 was removed". A handle also holds the id's Document::birth: when
// the call that made its piece is undone and another piece gets the id, the old handle stays
// dead ("no longer exists") instead of naming the new piece, and the two are not equal.

#include "commands/Document.h"
#include "scripting/LuaSupport.h"

#include <string>

namespace netsculpt::lua {

inline constexpr const char* kDocumentType = "netsculpt.Document";
inline constexpr const char* kPieceType = "netsculpt.Piece";
inline constexpr const char* kRailType = "netsculpt.Rail";

/// Pushes a new document userdata owning `doc`.
Document& pushDocument(lua_State* L, Document&& doc);
/// The document at `index` (the `doc` of doc:call{...}); a clear error for doc.call{...}.
Document& checkDocument(const Call& call, int index = 1);

/// Pushes the handle of `id` in the document at `docIndex` (the cached one if it exists).
void pushPiece(lua_State* L, int docIndex, PieceId id);
void pushRail(lua_State* L, int docIndex, RailId id);

/// The piece handle at `index`: of the document at `docIndex`, and alive.
PieceId checkPiece(const Call& call, int index, const char* arg, int docIndex = 1);
RailId checkRail(const Call& call, int index, const char* arg, int docIndex = 1);
/// Same for the value of a keyword argument.
PieceId pieceArg(const TableArgs& args, const char* key, int docIndex = 1);
RailId railArg(const TableArgs& args, const char* key, int docIndex = 1);

/// For a handle method (p:info()): the handle's id, checked alive, and its document pushed on
/// the stack; returns the document's stack index.
int handleDocument(const Call& call, PieceId& id);
int handleDocument(const Call& call, RailId& id);

/// "piece 3" / "rail 1" for a handle at `index`, "sculpture" for a document, "" otherwise.
std::string describeHandle(lua_State* L, int index);

/// Creates the metatables (once per state).
void registerHandleTypes(lua_State* L);

} // namespace netsculpt::lua
