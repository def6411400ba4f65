#include "scripting/ScriptHost.h"

#include "scripting/Limits.h"
#include "scripting/Sandbox.h"

#include <memory>
#include <system_error>

extern "C" int luaopen_netsculpt(lua_State* L);

namespace netsculpt::lua {

namespace fs = std::filesystem;

namespace {

struct CloseState {
    void operator()(lua_State* L) const { lua_close(L); }
};

const char* const kTracebackMarker = "\nstack traceback:\n";

/// The message handler: the error as a string, followed by the traceback.
int messageHandler(lua_State* L) {
    if (lua_type(L, 1) != LUA_TSTRING) {
        if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING)
            lua_replace(L, 1);
        else
            lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1)),
                lua_replace(L, 1);
    }
    luaL_traceback(L, L, lua_tostring(L, 1), 1);
    return 1;
}

void setScriptArguments(lua_State* L, const std::string& script,
                        const std::vector<std::string>& args) {
    lua_createtable(L, int(args.size()), 1);
    lua_pushstring(L, script.c_str());
    lua_rawseti(L, -2, 0);
    for (std::size_t i = 0; i < args.size(); ++i) {
        lua_pushstring(L, args[i].c_str());
        lua_rawseti(L, -2, lua_Integer(i + 1));
    }
    lua_setglobal(L, "arg");
}

/// Calls the loaded chunk with the arguments as its `...`, as the stock `lua` interpreter does
/// (`local rows = ...`); they are the global `arg` too.
int callScript(lua_State* L, const std::vector<std::string>& args) {
    if (args.size() > 100'000 || !lua_checkstack(L, int(args.size()) + 1)) {
        lua_pushfstring(L, "too many script arguments: %d (at most 100000)", int(args.size()));
        return LUA_ERRRUN;
    }
    for (const std::string& a : args)
        lua_pushlstring(L, a.data(), a.size());
    return lua_pcall(L, int(args.size()), 0, 1);
}

/// Without the sandbox `require` still looks first where a sandboxed script's does (its folder,
/// the output folder, the --lib folders), so that --unsafe loses no module a script found
/// before. A folder whose name holds ';' or '?' cannot be written into package.path: left out.
void prependModuleFolders(lua_State* L, const ScriptContext& ctx) {
    std::string path;
    for (const fs::path& folder : readableFolders(ctx)) {
        const std::string name = folder.string();
        if (name.find_first_of(";?") == std::string::npos)
            path += (folder / "?.lua").string() + ";" + (folder / "?" / "init.lua").string() + ";";
    }
    lua_getglobal(L, "package");
    lua_getfield(L, -1, "path");
    if (const char* current = lua_tostring(L, -1))
        path += current;
    lua_pop(L, 1);
    lua_pushlstring(L, path.data(), path.size());
    lua_setfield(L, -2, "path");
    lua_pop(L, 1);
}

/// Opens the libraries and netsculpt, the sandbox and the limits (with no memory limit yet).
void prepareState(lua_State* L, ScriptContext& ctx, const std::string& script,
                  const ScriptOptions& options) {
    installContext(L, &ctx);
    luaL_openlibs(L);
    lua_getglobal(L, "package");
    lua_getfield(L, -1, "preload");
    lua_pushcfunction(L, luaopen_netsculpt);
    lua_setfield(L, -2, "netsculpt");
    lua_pop(L, 2);
    if (ctx.sandboxed)
        installSandbox(L);
    else
        prependModuleFolders(L, ctx);
    installLimits(L, ctx);
    setScriptArguments(L, script, options.args);
}

ScriptContext makeContext(const fs::path& scriptDir, const std::string& journalStem,
                          const ScriptOptions& options) {
    ScriptContext ctx;
    std::error_code error;
    ctx.sandboxed = !options.unsafe;
    ctx.scriptDir = fs::weakly_canonical(fs::absolute(scriptDir), error);
    ctx.outputDir = fs::weakly_canonical(fs::absolute(options.outputDir), error);
    for (const fs::path& folder : options.libraryDirs)
        ctx.libraryDirs.push_back(fs::weakly_canonical(fs::absolute(folder), error));
    ctx.journalStem = options.journal ? journalStem : std::string();
    ctx.backendOverride = options.backend;
    ctx.relaxProgress = options.relaxProgress;
    ctx.relaxFinished = options.relaxFinished;
    ctx.maxInstructions = options.maxInstructions;
    ctx.maxMemory = options.maxMemory;
    ctx.interrupt = options.interrupt;
    return ctx;
}

/// Splits "message\nstack traceback:\n..." into the result.
void setError(ScriptResult& result, const std::string& text) {
    result.ok = false;
    const auto at = text.rfind(kTracebackMarker);
    result.error = at == std::string::npos ? text : text.substr(0, at);
    result.traceback = at == std::string::npos ? std::string() : text.substr(at + 1);
}

ScriptResult run(const std::string& chunkName, const fs::path& scriptDir,
                 const std::string& journalStem, const ScriptOptions& options,
                 const std::function<int(lua_State*)>& load) {
    ScriptResult result;
    ScriptContext ctx = makeContext(scriptDir, journalStem, options);
    MemoryLimit memory; // declared before the state: it outlives lua_close
    const std::unique_ptr<lua_State, CloseState> state(lua_newstate(limitedAlloc, &memory));
    lua_State* L = state.get();
    if (L == nullptr) {
        result.ok = false;
        result.error = "cannot create a Lua state (out of memory)";
        return result;
    }
    prepareState(L, ctx, chunkName, options);
    memory.limit = options.maxMemory;
    lua_pushcfunction(L, messageHandler);
    int status = load(L);
    if (status == LUA_OK)
        status = callScript(L, options.args);
    if (status != LUA_OK) {
        if (status == LUA_ERRMEM && ctx.maxMemory != 0)
            ctx.stop = Stop::Memory;
        const char* message = lua_tostring(L, -1);
        setError(result, message != nullptr ? message : "(error object is not a string)");
        if (ctx.stop == Stop::Memory)
            result.error = memoryExceededMessage(ctx.maxMemory);
        const std::string budget = instructionsExceededMessage(ctx.maxInstructions);
        if (ctx.stop == Stop::Instructions && result.error.find(budget) == std::string::npos)
            result.error = budget;
    }
    if (interruptRequested(ctx)) { // also when the script ended before the hook's next turn
        ctx.stop = Stop::Interrupted;
        if (status == LUA_OK || result.error.find(interruptedMessage()) == std::string::npos)
            setError(result, interruptedMessage());
    }
    result.stop = ctx.stop;
    result.journals = ctx.journals;
    result.instructions = ctx.instructions;
    memory.limit = 0; // closing the state must not fail
    result.peakMemory = memory.peak;
    return result;
}

} // namespace

ScriptResult runScriptFile(const fs::path& script, const ScriptOptions& options) {
    const std::string name = script.string();
    const fs::path folder = fs::absolute(script).parent_path();
    const char* mode = options.unsafe ? "bt" : "t";
    return run(name, folder, script.stem().string(), options,
               [&](lua_State* L) { return luaL_loadfilex(L, name.c_str(), mode); });
}

ScriptResult runScriptString(std::string_view source, const std::string& chunkName,
                             const fs::path& scriptDir, const ScriptOptions& options) {
    return run(chunkName, scriptDir, options.journalStem, options, [&](lua_State* L) {
        return luaL_loadbufferx(L, source.data(), source.size(), ("=" + chunkName).c_str(), "t");
    });
}

} // namespace netsculpt::lua
