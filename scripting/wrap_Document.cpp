// The document: ns.new, ns.open; doc:undo, redo, save, save_snapshot, set_gravity, rename,
// hash, rails, pieces, can_undo, can_redo.

#include "model/Error.h"
#include "scripting/Context.h"
#include "scripting/DocumentFiles.h"
#include "scripting/Handles.h"
#include "scripting/Sandbox.h"
#include "scripting/Wrap.h"

#include <cstdint>
#include <cstdio>
#include <string>

namespace netsculpt::lua {

namespace {

/// Journals a document the script made when the host asks for it (the CLI's `run`).
void journalIfAsked(lua_State* L, Document& doc) {
    ScriptContext& ctx = context(L);
    const std::filesystem::path path = nextJournalPath(ctx);
    if (path.empty())
        return;
    doc.attachJournal(path);
    ctx.journals.push_back(path);
}

int w_new(Call& call) {
    Document doc;
    journalIfAsked(call.L, doc);
    pushDocument(call.L, std::move(doc));
    return 1;
}

/// ns.open(path) -> doc, warnings: a journal (replayed) or a snapshot.
int w_open(Call& call) {
    const std::string given = checkString(call, 1, "path");
    const auto path = resolveReadPath(context(call.L), given, call.name);
    std::vector<std::string> warnings;
    Document doc = openReadOnly(path, &warnings);
    journalIfAsked(call.L, doc);
    pushDocument(call.L, std::move(doc));
    lua_createtable(call.L, int(warnings.size()), 0);
    for (std::size_t i = 0; i < warnings.size(); ++i) {
        lua_pushstring(call.L, warnings[i].c_str());
        lua_rawseti(call.L, -2, lua_Integer(i + 1));
    }
    return 2;
}

/// doc:undo(steps) and doc:redo(steps), one step when not given: all the steps or, when fewer
/// can be taken, none.
int undoOrRedo(Call& call, bool undo) {
    Document& doc = checkDocument(call);
    const std::size_t available = undo ? doc.undoableSteps() : doc.redoableSteps();
    const std::int64_t steps =
        lua_isnoneornil(call.L, 2) ? 1 : checkWhole(call, 2, "steps", 1, INT32_MAX);
    if (available > 0 && std::size_t(steps) > available)
        call.bad("steps", 2,
                 "at most " + std::to_string(available) + ", the steps that can be " +
                     (undo ? "undone" : "redone"));
    for (std::int64_t i = 0; i < steps; ++i)
        undo ? doc.undo() : doc.redo(); // with none available: "nothing to undo"
    return 0;
}

int w_undo(Call& call) { return undoOrRedo(call, true); }
int w_redo(Call& call) { return undoOrRedo(call, false); }

int w_can_undo(Call& call) {
    lua_pushboolean(call.L, checkDocument(call).canUndo());
    return 1;
}

int w_can_redo(Call& call) {
    lua_pushboolean(call.L, checkDocument(call).canRedo());
    return 1;
}

/// The path argument of doc:save or doc:save_snapshot, refused unless it ends in `extension`
/// (any case): a journal and a snapshot are opened by their content, but named by their kind.
std::string checkSavePath(const Call& call, const char* extension, const char* what) {
    const auto [given, ext] = checkFileArgument(call, 2);
    if (ext != extension)
        call.fail(std::string("argument 'path' must end in .") + extension + " (" + what +
                  "), got \"" + given + "\"");
    return given;
}

/// doc:save(path): the compacted journal, into the output folder. Returns the path written.
int w_save(Call& call) {
    Document& doc = checkDocument(call);
    const std::string given =
        checkSavePath(call, "netj", "a journal; doc:save_snapshot writes a .nets snapshot");
    const auto path = resolveWritePath(context(call.L), given, call.name);
    doc.save(path);
    lua_pushstring(call.L, path.c_str());
    return 1;
}

/// doc:save_snapshot(path): the model and the current (relaxed) positions in one file.
int w_save_snapshot(Call& call) {
    Document& doc = checkDocument(call);
    const std::string given = checkSavePath(
        call, "nets", "a snapshot of the model and its shape; doc:save writes a .netj journal");
    const auto path = resolveWritePath(context(call.L), given, call.name);
    doc.saveSnapshot(path);
    lua_pushstring(call.L, path.c_str());
    return 1;
}

/// doc:set_gravity{x, y, z} (or {x=, y=, z=}, or three numbers).
int w_set_gravity(Call& call) {
    Document& doc = checkDocument(call);
    Vec3 g;
    if (lua_type(call.L, 2) == LUA_TNUMBER)
        g = {checkFinite(call, 2, "x"), checkFinite(call, 3, "y"), checkFinite(call, 4, "z")};
    else
        g = checkVec3(call, 2, "gravity");
    doc.execute(SetGravityCommand{g});
    return 0;
}

/// doc:rename{piece = p, name = "..."} or doc:rename{rail = r, name = "..."}.
int w_rename(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"piece", "rail", "name"});
    const std::string name = args.string("name", std::nullopt);
    if (args.has("piece") == args.has("rail"))
        call.fail("give piece or rail (one of them)");
    if (args.has("piece"))
        doc.execute(RenamePieceCommand{pieceArg(args, "piece"), name});
    else
        doc.execute(RenameRailCommand{railArg(args, "rail"), name});
    return 0;
}

/// doc:hash() -> 16 hex digits: equal hashes = the same sculpture.
int w_hash(Call& call) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx",
                  static_cast<unsigned long long>(checkDocument(call).hash()));
    lua_pushstring(call.L, text);
    return 1;
}

int w_rails(Call& call) {
    const Sculpture& s = checkDocument(call).sculpture();
    lua_createtable(call.L, int(s.rails.size()), 0);
    lua_Integer i = 0;
    for (const auto& [id, rail] : s.rails) {
        pushRail(call.L, 1, id);
        lua_rawseti(call.L, -2, ++i);
    }
    return 1;
}

int w_pieces(Call& call) {
    const Sculpture& s = checkDocument(call).sculpture();
    lua_createtable(call.L, int(s.pieces.size()), 0);
    lua_Integer i = 0;
    for (const auto& [id, piece] : s.pieces) {
        pushPiece(call.L, 1, id);
        lua_rawseti(call.L, -2, ++i);
    }
    return 1;
}

} // namespace

void addModuleDocumentFunctions(lua_State* L) {
    setFunctions(L, {{"new", entry<w_new>, 0}, {"open", entry<w_open>, 1}});
}

void addDocumentMethods(lua_State* L) {
    setMethods(L, {{"undo", entry<w_undo>, 1},
                     {"redo", entry<w_redo>, 1},
                     {"can_undo", entry<w_can_undo>, 0},
                     {"can_redo", entry<w_can_redo>, 0},
                     {"save", entry<w_save>, 1},
                     {"save_snapshot", entry<w_save_snapshot>, 1},
                     {"set_gravity", entry<w_set_gravity>, 3},
                     {"rename", entry<w_rename>, kKeywordTable},
                     {"hash", entry<w_hash>, 0},
                     {"rails", entry<w_rails>, 0},
                     {"pieces", entry<w_pieces>, 0}});
    addRailMethods(L);
    addPieceMethods(L);
    addQueryMethods(L);
    addRelaxMethods(L);
    addIoMethods(L);
}

} // namespace netsculpt::lua
