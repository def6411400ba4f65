#include "scripting/LuaSupport.h"

#include "model/Error.h"
#include "scripting/Handles.h"
#include "scripting/Limits.h"

#include <cmath>
#include <new>

namespace netsculpt::lua {

namespace {

bool startsWith(const std::string& text, const std::string& prefix) {
    return text.compare(0, prefix.size(), prefix) == 0;
}

std::string quoted(std::string_view text) {
    constexpr std::size_t kMax = 60;
    std::string out = "\"";
    out += text.size() > kMax ? std::string(text.substr(0, kMax)) + "..." : std::string(text);
    return out + "\"";
}

} // namespace

std::string currentErrorMessage(const char* name) {
    const std::string prefix = std::string(name) + ":";
    try {
        throw;
    } catch (const ArgumentError& e) {
        return e.what();
    } catch (const UserError& e) {
        const std::string message = e.what();
        return startsWith(message, prefix) ? message : prefix + " " + message;
    } catch (const std::bad_alloc&) {
        return prefix + " out of memory";
    } catch (const std::exception& e) {
        return prefix + " internal error: " + e.what();
    } catch (...) {
        return prefix + " internal error (unknown exception)";
    }
}

void Call::fail(const std::string& message) const {
    throw ArgumentError(std::string(name) + ": " + message);
}

void Call::bad(const char* arg, int index, const std::string& expected) const {
    fail(std::string("argument '") + arg + "' must be " + expected + ", got " + describe(L, index));
}

std::string describe(lua_State* L, int index) {
    switch (lua_type(L, index)) {
    case LUA_TNONE:
    case LUA_TNIL:
        return "nil";
    case LUA_TBOOLEAN:
        return lua_toboolean(L, index) ? "true" : "false";
    case LUA_TNUMBER:
        if (lua_isinteger(L, index))
            return std::to_string(lua_tointeger(L, index));
        return formatNumber(lua_tonumber(L, index));
    case LUA_TSTRING: {
        std::size_t size = 0;
        const char* text = lua_tolstring(L, index, &size);
        return quoted(std::string_view(text, size));
    }
    case LUA_TTABLE:
        return "a table";
    case LUA_TFUNCTION:
        return "a function";
    case LUA_TUSERDATA: {
        const std::string handle = describeHandle(L, index);
        return handle.empty() ? "a userdata" : handle;
    }
    default:
        return std::string("a ") + lua_typename(L, lua_type(L, index));
    }
}

namespace {

/// Stops Lua's collector while it lives. A collection step, which any allocation may take, runs
/// the script's __gc finalizers, that is Lua code: inside a body, one that edited the document
/// freed what the body was reading (doc:knots of a piece that a finalizer's set_rows rebuilt).
/// Inside a finalizer the collector takes no steps anyway (lua_gc then returns -1).
class CollectorPause {
  public:
    explicit CollectorPause(lua_State* L) : L_(L), wasRunning_(lua_gc(L, LUA_GCISRUNNING) == 1) {
        if (wasRunning_)
            lua_gc(L_, LUA_GCSTOP);
    }
    ~CollectorPause() {
        if (wasRunning_)
            lua_gc(L_, LUA_GCRESTART);
    }
    CollectorPause(const CollectorPause&) = delete;
    CollectorPause& operator=(const CollectorPause&) = delete;

  private:
    lua_State* L_;
    bool wasRunning_;
};

/// Whether the value at (absolute) `index` is the netsculpt module itself: `ns:new()` passes it.
bool isModuleTable(lua_State* L, int index) {
    lua_getfield(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
    lua_getfield(L, -1, "netsculpt");
    const bool same = lua_istable(L, index) && lua_rawequal(L, index, -1);
    lua_pop(L, 2);
    return same;
}

/// Refuses a call with more arguments than its closure's limit (setClosures' upvalues 2 and 3;
/// a closure without them takes any).
void checkArgumentCount(const Call& call) {
    lua_State* L = call.L;
    if (lua_type(L, lua_upvalueindex(2)) != LUA_TNUMBER)
        return;
    const int arguments = int(lua_tointeger(L, lua_upvalueindex(2)));
    const int limit = arguments == kKeywordTable ? 1 : arguments;
    const int first = lua_toboolean(L, lua_upvalueindex(3)) ? 2 : 1; // after a method's self
    int last = lua_gettop(L);
    while (last >= first && lua_isnil(L, last))
        --last;
    const int given = last - first + 1;
    if (given <= limit || (arguments == kKeywordTable && !lua_istable(L, first)))
        return;
    if (first == 1 && isModuleTable(L, 1))
        call.fail(std::string("call it as ns.") + call.name + "(...) (with a dot): ns:" +
                  call.name + "(...) passes the module itself as a first argument");
    std::string extra;
    for (int i = first + limit; i <= last; ++i)
        extra += (extra.empty() ? "" : ", ") + describe(L, i);
    const std::string takes = limit == 0   ? "takes no arguments"
                              : limit == 1 ? "takes at most 1 argument"
                                           : "takes at most " + std::to_string(limit) +
                                                 " arguments";
    call.fail(takes + ", got " + std::to_string(given) + " (the extra: " + extra + ")");
}

} // namespace

int invoke(lua_State* L, const char* name, Body body) {
    int results = 0;
    bool failed = false;
    {
        const BindingExemption exemption(L); // no Lua error (memory) while C++ frames are live
        const CollectorPause pause(L);       // and no Lua code: no finalizer re-enters the kernel
        std::string message;
        try {
            Call call{L, name};
            checkArgumentCount(call);
            results = body(call);
        } catch (...) {
            message = currentErrorMessage(name);
            failed = true;
        }
        if (failed) {
            luaL_where(L, 1); // the script's file:line
            lua_pushlstring(L, message.data(), message.size());
            lua_concat(L, 2);
        }
    }
    if (failed) return lua_error(L); // every C++ object of this call is gone: lua_error longjmps
    return results;
}

namespace {

void setClosures(lua_State* L, std::initializer_list<Function> functions, bool methods) {
    for (const Function& f : functions) {
        lua_pushstring(L, f.name);
        lua_pushinteger(L, f.arguments);
        lua_pushboolean(L, methods);
        lua_pushcclosure(L, f.function, 3);
        lua_setfield(L, -2, f.name);
    }
}

} // namespace

void setFunctions(lua_State* L, std::initializer_list<Function> functions) {
    setClosures(L, functions, false);
}

void setMethods(lua_State* L, std::initializer_list<Function> methods) {
    setClosures(L, methods, true);
}

std::int64_t checkWhole(const Call& call, int index, const char* arg, std::int64_t min,
                        std::int64_t max) {
    const bool anyMin = min == INT32_MIN || min == INT64_MIN,
               anyMax = max == INT32_MAX || max == INT64_MAX;
    const std::string range = anyMin && anyMax ? ""
                              : anyMax         ? " >= " + std::to_string(min)
                              : anyMin
                                  ? " <= " + std::to_string(max)
                                  : " from " + std::to_string(min) + " to " + std::to_string(max);
    const std::string expected = "a whole number" + range;
    if (lua_type(call.L, index) != LUA_TNUMBER)
        call.bad(arg, index, expected);
    std::int64_t value = 0;
    if (lua_isinteger(call.L, index)) {
        value = lua_tointeger(call.L, index);
    } else {
        const double d = lua_tonumber(call.L, index);
        if (!(d == std::floor(d)) || !(std::fabs(d) < 9e15))
            call.bad(arg, index, expected);
        value = std::int64_t(d);
    }
    if (value < min || value > max)
        call.bad(arg, index, expected);
    return value;
}

double checkFinite(const Call& call, int index, const char* arg) {
    if (lua_type(call.L, index) != LUA_TNUMBER || !std::isfinite(lua_tonumber(call.L, index)))
        call.bad(arg, index, "a finite number");
    return lua_tonumber(call.L, index);
}

std::string checkString(const Call& call, int index, const char* arg) {
    if (lua_type(call.L, index) != LUA_TSTRING)
        call.bad(arg, index, "a string");
    std::size_t size = 0;
    const char* text = lua_tolstring(call.L, index, &size);
    return std::string(text, size);
}

std::string listOf(const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0)
            out += i + 1 == names.size() ? " or " : ", ";
        out += "\"" + names[i] + "\"";
    }
    return out;
}

std::string checkChoice(const Call& call, int index, const char* arg,
                        const std::vector<std::string>& allowed) {
    const std::string expected = "one of " + listOf(allowed);
    if (lua_type(call.L, index) != LUA_TSTRING)
        call.bad(arg, index, expected);
    const std::string value = lua_tostring(call.L, index);
    for (const std::string& a : allowed)
        if (a == value)
            return value;
    call.bad(arg, index, expected);
}

Vec3 checkVec3(const Call& call, int index, const char* arg) {
    static const char* const kNames[3] = {"x", "y", "z"};
    return checkTriple(call, index, arg, kNames, "a point {x, y, z} of three finite numbers");
}

Vec3 checkTriple(const Call& call, int index, const char* arg, const char* const (&kNames)[3],
                 const char* expected) {
    lua_State* L = call.L;
    index = lua_absindex(L, index);
    if (lua_type(L, index) != LUA_TTABLE)
        call.bad(arg, index, expected);
    const std::size_t length = lua_rawlen(L, index);
    const bool named = length == 0;
    if (!named && length != 3)
        call.fail(std::string("argument '") + arg + "' must be " + expected + ", got a table of " +
                  std::to_string(length) + " values");
    double xyz[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i) {
        if (named)
            lua_pushstring(L, kNames[i]), lua_rawget(L, index);
        else
            lua_rawgeti(L, index, i + 1);
        const bool ok = lua_type(L, -1) == LUA_TNUMBER && std::isfinite(lua_tonumber(L, -1));
        xyz[i] = lua_tonumber(L, -1);
        if (!ok) {
            const std::string got = describe(L, -1);
            lua_pop(L, 1);
            call.fail(std::string("argument '") + arg + "' must be " + expected + ", got " + got +
                      " as " + kNames[i]);
        }
        lua_pop(L, 1);
    }
    return {xyz[0], xyz[1], xyz[2]};
}

void pushVec3(lua_State* L, const Vec3& v) {
    lua_createtable(L, 3, 0);
    lua_pushnumber(L, v.x);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, v.y);
    lua_rawseti(L, -2, 2);
    lua_pushnumber(L, v.z);
    lua_rawseti(L, -2, 3);
}

void setNumber(lua_State* L, const char* key, double value) {
    lua_pushnumber(L, value);
    lua_setfield(L, -2, key);
}

void setInteger(lua_State* L, const char* key, std::int64_t value) {
    lua_pushinteger(L, value);
    lua_setfield(L, -2, key);
}

void setBoolean(lua_State* L, const char* key, bool value) {
    lua_pushboolean(L, value);
    lua_setfield(L, -2, key);
}

void setString(lua_State* L, const char* key, const std::string& value) {
    lua_pushlstring(L, value.data(), value.size());
    lua_setfield(L, -2, key);
}

} // namespace netsculpt::lua
