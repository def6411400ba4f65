#include "scripting/Context.h"

#include <new>
#include <system_error>

namespace netsculpt::lua {

namespace {

const char kContextKey = 'c'; // its address is the registry key

int defaultContextGc(lua_State* L) {
    static_cast<ScriptContext*>(lua_touserdata(L, 1))->~ScriptContext();
    return 0;
}

/// The folder of the script a stock interpreter runs (its global arg[0], when that names a
/// file), else the current directory.
std::filesystem::path stockScriptFolder(lua_State* L) {
    std::error_code error;
    const std::filesystem::path current = std::filesystem::current_path(error);
    std::filesystem::path script;
    const int top = lua_gettop(L);
    if (lua_getglobal(L, "arg") == LUA_TTABLE && lua_rawgeti(L, -1, 0) == LUA_TSTRING)
        script = lua_tostring(L, -1);
    lua_settop(L, top);
    if (script.empty() || !std::filesystem::is_regular_file(script, error))
        return current;
    return std::filesystem::absolute(script, error).parent_path();
}

ScriptContext* makeDefaultContext(lua_State* L) {
    std::error_code error;
    const std::filesystem::path scriptFolder = stockScriptFolder(L);
    void* memory = lua_newuserdatauv(L, sizeof(ScriptContext), 0);
    auto* context = new (memory) ScriptContext{};
    context->scriptDir = scriptFolder;
    context->outputDir = std::filesystem::current_path(error);
    lua_createtable(L, 0, 1);
    lua_pushcfunction(L, defaultContextGc);
    lua_setfield(L, -2, "__gc");
    lua_setmetatable(L, -2);
    lua_rawsetp(L, LUA_REGISTRYINDEX, &kContextKey); // keeps the userdata alive with the state
    return context;
}

} // namespace

ScriptContext& context(lua_State* L) {
    lua_rawgetp(L, LUA_REGISTRYINDEX, &kContextKey);
    auto* found = static_cast<ScriptContext*>(lua_touserdata(L, -1));
    lua_pop(L, 1);
    return found != nullptr ? *found : *makeDefaultContext(L);
}

void installContext(lua_State* L, ScriptContext* context) {
    lua_pushlightuserdata(L, context);
    lua_rawsetp(L, LUA_REGISTRYINDEX, &kContextKey);
}

std::filesystem::path nextJournalPath(ScriptContext& context) {
    if (context.journalStem.empty())
        return {};
    const int n = ++context.documentsMade;
    std::string name = context.journalStem;
    if (n > 1)
        name.append(".").append(std::to_string(n));
    return context.outputDir / name.append(".netj");
}

} // namespace netsculpt::lua
