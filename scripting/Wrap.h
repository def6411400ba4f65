#pragma once
// The wrap_*.cpp files, one per kernel area. Each add* function sets its functions into the
// table at the top of the stack (the document's methods, a handle's methods or the module).

#include <lua.hpp>

namespace netsculpt::lua {

// wrap_Document.cpp: ns.new, ns.open; undo, redo, save, set_gravity, hash, rename, rails, pieces
void addModuleDocumentFunctions(lua_State* L);
void addDocumentMethods(lua_State* L); // calls the add*Methods below too
// wrap_Rails.cpp: add_rail, import_rails, remove_rail; ns.circle
void addRailMethods(lua_State* L);
void addModuleRailFunctions(lua_State* L);
// wrap_Pieces.cpp: attach_to_rail, attach_to_piece, split, set_*, connect_to_rail, ...
void addPieceMethods(lua_State* L);
// wrap_Queries.cpp: piece_info, rail_info, knots; p:info(), p:knots(), r:info()
void addQueryMethods(lua_State* L);
void addPieceHandleMethods(lua_State* L);
void addRailHandleMethods(lua_State* L);
// wrap_Relax.cpp: relax, last_relax; ns.backends()
void addRelaxMethods(lua_State* L);
void addModuleRelaxFunctions(lua_State* L);
// wrap_Io.cpp: export, report, write_report; ns.export_formats(), ns.output_dir(), ns.script_dir()
void addIoMethods(lua_State* L);
void addModuleIoFunctions(lua_State* L);

} // namespace netsculpt::lua
