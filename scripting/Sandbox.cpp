#include "scripting/Sandbox.h"

#include "model/Error.h"
#include "scripting/LuaSupport.h"

#include <algorithm>
#include <cctype>
#include <system_error>

namespace netsculpt::lua {

namespace fs = std::filesystem;

namespace {

const char* const kUnsafeHint = "run with --unsafe to lift the sandbox";

fs::path canonicalOrSelf(const fs::path& path) {
    std::error_code error;
    fs::path result = fs::weakly_canonical(path, error);
    return error ? path.lexically_normal() : result;
}

/// `path` is `folder` or lies below it (both canonical).
bool isInside(const fs::path& path, const fs::path& folder) {
    auto p = path.begin();
    for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
        if (f->empty())
            continue; // a trailing separator
        if (p == path.end() || *p != *f)
            return false;
    }
    return true;
}

std::string quotedPath(const fs::path& path) {
    return "\"" + path.string() + "\"";
}

} // namespace

/// A file name is text without NUL: the system would cut "x.nets\0y" to "x.nets" silently.
void checkFileName(const std::string& text, const char* call) {
    if (text.empty())
        throw UserError(std::string(call) + ": the file name is empty");
    const std::size_t nul = text.find('\0');
    if (nul != std::string::npos)
        throw UserError(std::string(call) + ": the file name \"" + text.substr(0, nul) +
                        "\\0" + text.substr(nul + 1) + "\" holds a NUL character (byte " +
                        std::to_string(nul + 1) + "); a file name is text without NUL");
}

FileArgument checkFileArgument(const Call& call, int index) {
    FileArgument argument{checkString(call, index, "path"), {}};
    checkFileName(argument.given, call.name);
    argument.extension = fs::path(argument.given).extension().string();
    if (!argument.extension.empty())
        argument.extension.erase(0, 1);
    std::transform(argument.extension.begin(), argument.extension.end(), argument.extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return argument;
}

std::vector<fs::path> readableFolders(const ScriptContext& context) {
    std::vector<fs::path> folders = {context.scriptDir, context.outputDir};
    folders.insert(folders.end(), context.libraryDirs.begin(), context.libraryDirs.end());
    return folders;
}

fs::path resolveReadPath(const ScriptContext& context, const std::string& text, const char* call) {
    checkFileName(text, call);
    const fs::path given(text);
    fs::path full = given.is_absolute() ? given : context.scriptDir / given;
    std::error_code error;
    if (!given.is_absolute() && !fs::exists(full, error) &&
        fs::exists(context.outputDir / given, error))
        full = context.outputDir / given; // what the script saved there itself, say
    if (!context.sandboxed)
        return full;
    const fs::path resolved = canonicalOrSelf(full);
    for (const fs::path& folder : readableFolders(context))
        if (isInside(resolved, canonicalOrSelf(folder)))
            return resolved;
    throw UserError(std::string(call) + ": reading \"" + text +
                    "\" is not allowed: a script reads files only in its own folder (" +
                    context.scriptDir.string() + "), in the output folder (" +
                    context.outputDir.string() + ") and in the folders given with --lib; " +
                    kUnsafeHint);
}

fs::path resolveWritePath(const ScriptContext& context, const std::string& text, const char* call) {
    checkFileName(text, call);
    const fs::path given(text);
    if (given.is_absolute() && context.sandboxed)
        throw UserError(std::string(call) + ": " + quotedPath(given) +
                        " is an absolute path; a script writes only inside the output folder (" +
                        context.outputDir.string() + "): give a path relative to it, or " +
                        kUnsafeHint);
    const fs::path full =
        given.is_absolute() ? given : (context.outputDir / given).lexically_normal();
    if (context.sandboxed) {
        const fs::path out = canonicalOrSelf(context.outputDir);
        const fs::path resolved = canonicalOrSelf(full);
        if (resolved == out || !isInside(resolved, out))
            throw UserError(std::string(call) + ": " + quotedPath(given) +
                            " is outside the output folder (" + context.outputDir.string() +
                            "); a script writes only inside it; " + kUnsafeHint);
    }
    if (full.has_parent_path()) {
        std::error_code error;
        fs::create_directories(full.parent_path(), error);
        if (error)
            throw UserError(std::string(call) + ": cannot create the folder " +
                            quotedPath(full.parent_path()) + ": " + error.message());
    }
    return full;
}

namespace {

// ---- refused functions ---------------------------------------------------------------------

/// A refused function; its name is upvalue 1. Only C data in this frame (luaL_error longjmps).
int refuse(lua_State* L) {
    return luaL_error(L, "%s: not allowed in a script (scripts run sandboxed; %s)",
                      lua_tostring(L, lua_upvalueindex(1)), kUnsafeHint);
}

void refuseField(lua_State* L, const char* table, const char* field) {
    if (lua_getglobal(L, table) != LUA_TTABLE) {
        lua_pop(L, 1);
        return;
    }
    lua_pushfstring(L, "%s.%s", table, field);
    lua_pushcclosure(L, refuse, 1);
    lua_setfield(L, -2, field);
    lua_pop(L, 1);
}

// ---- checked library functions -------------------------------------------------------------
// A check body runs under invoke(): it validates the arguments and rewrites them in place
// (resolved paths, text-only modes). The original function (upvalue 2) is then called with
// them outside every C++ frame, because it may raise Lua errors or run Lua code.

void replacePathArgument(const Call& call, int index, bool write) {
    const std::string given = checkString(call, index, "filename");
    const ScriptContext& ctx = context(call.L);
    const fs::path path =
        write ? resolveWritePath(ctx, given, call.name) : resolveReadPath(ctx, given, call.name);
    lua_pushstring(call.L, path.c_str());
    lua_replace(call.L, index);
}

int checkOpen(Call& call) {
    if (lua_gettop(call.L) >= 2 && !lua_isnil(call.L, 2)) {
        const std::string mode = checkString(call, 2, "mode");
        if (mode != "r" && mode != "rb")
            call.fail("writing files is not allowed in a script (mode \"" + mode +
                      "\"): write through doc:save, doc:export or doc:write_report into the output "
                      "folder, or " +
                      kUnsafeHint);
    }
    replacePathArgument(call, 1, false);
    return 0;
}

int checkOptionalRead(Call& call) {
    if (lua_type(call.L, 1) == LUA_TSTRING)
        replacePathArgument(call, 1, false);
    return 0;
}

int checkOutput(Call& call) {
    if (lua_type(call.L, 1) == LUA_TSTRING)
        call.fail("writing files is not allowed in a script: write through doc:save, doc:export or "
                  "doc:write_report into the output folder, or " +
                  std::string(kUnsafeHint));
    return 0;
}

/// Forces mode "t" at argument `modeIndex` (refusing "b").
void textOnly(const Call& call, int modeIndex) {
    lua_State* L = call.L;
    if (lua_gettop(L) >= modeIndex && !lua_isnil(L, modeIndex)) {
        const std::string mode = checkString(call, modeIndex, "mode");
        if (mode.find('t') == std::string::npos)
            call.fail("binary chunks are not allowed in a script (mode \"" + mode + "\")");
    }
    if (lua_gettop(L) < modeIndex)
        lua_settop(L, modeIndex);
    lua_pushliteral(L, "t");
    lua_replace(L, modeIndex);
}

int checkLoad(Call& call) {
    textOnly(call, 3);
    return 0;
}

int checkLoadfile(Call& call) {
    if (!lua_isnoneornil(call.L, 1))
        replacePathArgument(call, 1, false);
    textOnly(call, 2);
    return 0;
}

template <Body Check> int checkedOriginal(lua_State* L) {
    invoke(L, lua_tostring(L, lua_upvalueindex(1)), Check);
    lua_pushvalue(L, lua_upvalueindex(2));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
}

void replaceField(lua_State* L, const char* table, const char* field, lua_CFunction wrapper) {
    const bool global = table == nullptr;
    if (global)
        lua_pushglobaltable(L);
    else
        lua_getglobal(L, table);
    lua_pushstring(L, global ? field : (std::string(table) + "." + field).c_str());
    lua_getfield(L, -2, field);
    lua_pushcclosure(L, wrapper, 2);
    lua_setfield(L, -2, field);
    lua_pop(L, 1);
}

// ---- dofile and require -------------------------------------------------------------------

/// Loads the file at argument 1 as text into a function at the top of the stack.
int loadFileArgument(Call& call) {
    replacePathArgument(call, 1, false);
    const char* path = lua_tostring(call.L, 1);
    if (luaL_loadfilex(call.L, path, "t") != LUA_OK) {
        const std::string message = lua_tostring(call.L, -1);
        call.fail(message);
    }
    return 1;
}

int sandboxedDofile(lua_State* L) {
    lua_settop(L, 1);
    invoke(L, "dofile", loadFileArgument);
    lua_call(L, 0, LUA_MULTRET);
    return lua_gettop(L) - 1;
}

/// package.searchers[2] in the sandbox: Lua modules from the script's and the output folder.
int searchModule(Call& call) {
    lua_State* L = call.L;
    const std::string name = checkString(call, 1, "name");
    std::string relative = name;
    std::replace(relative.begin(), relative.end(), '.', '/');
    const ScriptContext& ctx = context(L);
    std::string tried;
    for (const fs::path& folder : readableFolders(ctx))
        for (const std::string& file : {relative + ".lua", relative + "/init.lua"}) {
            const fs::path path = folder / file;
            std::error_code error;
            if (!isInside(canonicalOrSelf(path), canonicalOrSelf(folder)) ||
                !fs::is_regular_file(path, error)) {
                tried += (tried.empty() ? "no file '" : "\n\tno file '") + path.string() + "'";
                continue;
            }
            if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK)
                call.fail("error loading module '" + name + "' from file '" + path.string() +
                          "':\n\t" + lua_tostring(L, -1));
            lua_pushstring(L, path.c_str());
            return 2;
        }
    tried += "\n\t(a script loads Lua modules from its own folder, the output folder and the "
             "folders given with --lib (module names use dots: require \"lib.helpers\"); C "
             "modules other than netsculpt are not allowed; " +
             std::string(kUnsafeHint) + ")";
    lua_pushstring(L, tried.c_str());
    return 1;
}

void installSearchers(lua_State* L) {
    lua_getglobal(L, "package");
    lua_pushliteral(L, "");
    lua_setfield(L, -2, "path");
    lua_pushliteral(L, "");
    lua_setfield(L, -2, "cpath");
    lua_getfield(L, -1, "searchers");
    lua_createtable(L, 2, 0);
    lua_rawgeti(L, -2, 1); // the preload searcher (netsculpt is preloaded)
    lua_rawseti(L, -2, 1);
    lua_pushliteral(L, "require");
    lua_pushcclosure(L, entry<searchModule>, 1);
    lua_rawseti(L, -2, 2);
    lua_setfield(L, -3, "searchers");
    lua_pop(L, 2);
}

void restrictDebug(lua_State* L) {
    static const char* const kRefused[] = {
        "debug",      "gethook",      "getlocal",  "getmetatable", "getregistry",
        "getupvalue", "getuservalue", "sethook",   "setlocal",     "setmetatable",
        "setupvalue", "setuservalue", "upvalueid", "upvaluejoin",  "setcstacklimit"};
    for (const char* field : kRefused)
        refuseField(L, "debug", field);
}

} // namespace

void installSandbox(lua_State* L) {
    for (const char* field : {"execute", "exit", "remove", "rename", "tmpname", "setlocale"})
        refuseField(L, "os", field);
    for (const char* field : {"popen", "tmpfile"})
        refuseField(L, "io", field);
    for (const char* field : {"loadlib", "searchpath"})
        refuseField(L, "package", field);
    restrictDebug(L);
    replaceField(L, "io", "open", checkedOriginal<checkOpen>);
    replaceField(L, "io", "lines", checkedOriginal<checkOptionalRead>);
    replaceField(L, "io", "input", checkedOriginal<checkOptionalRead>);
    replaceField(L, "io", "output", checkedOriginal<checkOutput>);
    replaceField(L, nullptr, "load", checkedOriginal<checkLoad>);
    replaceField(L, nullptr, "loadfile", checkedOriginal<checkLoadfile>);
    lua_pushcfunction(L, sandboxedDofile);
    lua_setglobal(L, "dofile");
    installSearchers(L);
}

} // namespace netsculpt::lua
