// luaopen_netsculpt: the module table that require "netsculpt" returns, in the CLI (preloaded)
// and in a stock lua5.4 (netsculpt.so on LUA_CPATH).

#include "scripting/Handles.h"
#include "scripting/Wrap.h"

#ifndef NETSCULPT_VERSION
#define NETSCULPT_VERSION "unknown"
#endif

extern "C" __attribute__((visibility("default"))) int luaopen_netsculpt(lua_State* L) {
    using namespace netsculpt::lua;
    registerHandleTypes(L);
    lua_newtable(L);
    addModuleDocumentFunctions(L);
    addModuleRailFunctions(L);
    addModuleRelaxFunctions(L);
    addModuleIoFunctions(L);
    lua_pushliteral(L, NETSCULPT_VERSION);
    lua_setfield(L, -2, "version");
    return 1;
}
