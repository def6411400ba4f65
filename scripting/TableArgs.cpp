// TableArgs: the keyword-argument tables of calls like doc:attach_to_rail{rail = r, rows = 3}.

#include "scripting/LuaSupport.h"

#include <cmath>

namespace netsculpt::lua {

namespace {

std::string allowedKeys(std::initializer_list<const char*> allowed) {
    std::string out;
    for (const char* key : allowed)
        out += (out.empty() ? "" : ", ") + std::string(key);
    return out;
}

} // namespace

TableArgs::TableArgs(const Call& call, int index, std::initializer_list<const char*> allowed)
    : call_(call), index_(lua_absindex(call.L, index)) {
    lua_State* L = call.L;
    if (lua_type(L, index_) != LUA_TTABLE) {
        if (index_ == 1) // a module function, ns.circle{...}
            call.fail(std::string("call it as ns.") + call.name + "{" + allowedKeys(allowed) +
                      "}, got " + describe(L, index_));
        if (lua_type(L, 1) == LUA_TTABLE) // a method called with a dot: the table is self
            call.fail(std::string("call it as doc:") + call.name +
                      "{...} (with a colon and a table of arguments)");
        call.fail(std::string("expected a table of arguments {") + allowedKeys(allowed) +
                  "}, got " + describe(L, index_));
    }
    lua_pushnil(L);
    while (lua_next(L, index_) != 0) {
        lua_pop(L, 1); // the value; keep the key for lua_next
        bool known = false;
        if (lua_type(L, -1) == LUA_TSTRING)
            for (const char* key : allowed)
                known = known || std::string_view(lua_tostring(L, -1)) == key;
        if (!known) {
            const std::string key = describe(L, -1);
            lua_pop(L, 1);
            call.fail("unknown argument " + key + "; allowed: " + allowedKeys(allowed));
        }
    }
}

bool TableArgs::has(const char* key) const {
    const bool present = lua_type(call_.L, push(key)) != LUA_TNIL;
    pop();
    return present;
}

int TableArgs::push(const char* key) const {
    lua_pushstring(call_.L, key);
    lua_rawget(call_.L, index_);
    return lua_gettop(call_.L);
}

void TableArgs::missing(const char* key, const std::string& expected) const {
    call_.fail(std::string("argument '") + key + "' is missing; expected " + expected);
}

std::int64_t TableArgs::whole(const char* key, std::optional<std::int64_t> fallback,
                              std::int64_t min, std::int64_t max) const {
    const int at = push(key);
    if (lua_isnil(call_.L, at)) {
        pop();
        if (!fallback)
            missing(key, "a whole number");
        return *fallback;
    }
    const std::int64_t value = checkWhole(call_, at, key, min, max);
    pop();
    return value;
}

double TableArgs::finite(const char* key, std::optional<double> fallback) const {
    const int at = push(key);
    if (lua_isnil(call_.L, at)) {
        pop();
        if (!fallback)
            missing(key, "a number");
        return *fallback;
    }
    const double value = checkFinite(call_, at, key);
    pop();
    return value;
}

double TableArgs::positive(const char* key, std::optional<double> fallback) const {
    const int at = push(key);
    if (lua_isnil(call_.L, at)) {
        pop();
        if (!fallback)
            missing(key, "a number > 0");
        return *fallback;
    }
    const double value = lua_tonumber(call_.L, at);
    if (lua_type(call_.L, at) != LUA_TNUMBER || !(value > 0) || !std::isfinite(value))
        call_.bad(key, at, "a finite number > 0");
    pop();
    return value;
}

bool TableArgs::boolean(const char* key, bool fallback) const {
    const int at = push(key);
    const int type = lua_type(call_.L, at);
    if (type != LUA_TNIL && type != LUA_TBOOLEAN)
        call_.bad(key, at, "true or false");
    const bool value = type == LUA_TNIL ? fallback : lua_toboolean(call_.L, at) != 0;
    pop();
    return value;
}

std::string TableArgs::string(const char* key, std::optional<std::string> fallback) const {
    const int at = push(key);
    if (lua_isnil(call_.L, at)) {
        pop();
        if (!fallback)
            missing(key, "a string");
        return *fallback;
    }
    std::string value = checkString(call_, at, key);
    pop();
    return value;
}

std::string TableArgs::choice(const char* key, const std::vector<std::string>& allowed,
                              std::optional<std::string> fallback) const {
    const int at = push(key);
    if (lua_isnil(call_.L, at)) {
        pop();
        if (!fallback)
            missing(key, "one of " + listOf(allowed));
        return *fallback;
    }
    std::string value = checkChoice(call_, at, key, allowed);
    pop();
    return value;
}

Vec3 TableArgs::vec3(const char* key) const {
    const int at = push(key);
    if (lua_isnil(call_.L, at))
        missing(key, "a point {x, y, z}");
    const Vec3 value = checkVec3(call_, at, key);
    pop();
    return value;
}

std::vector<Vec3> TableArgs::points(const char* key) const {
    lua_State* L = call_.L;
    const int at = push(key);
    if (lua_type(L, at) != LUA_TTABLE) {
        if (lua_isnil(L, at))
            missing(key, "a list of points {{x, y, z}, ...}");
        call_.bad(key, at, "a list of points {{x, y, z}, ...}");
    }
    std::vector<Vec3> points;
    const lua_Integer n = lua_Integer(lua_rawlen(L, at));
    points.reserve(std::size_t(n));
    for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L, at, i);
        const std::string name = std::string(key) + "[" + std::to_string(i) + "]";
        points.push_back(checkVec3(call_, -1, name.c_str()));
        lua_pop(L, 1);
    }
    pop();
    return points;
}

std::vector<double> TableArgs::numbers(const char* key) const {
    lua_State* L = call_.L;
    const int at = push(key);
    if (lua_type(L, at) != LUA_TTABLE)
        call_.bad(key, at, "a list of numbers");
    std::vector<double> values;
    const lua_Integer n = lua_Integer(lua_rawlen(L, at));
    for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L, at, i);
        const std::string name = std::string(key) + "[" + std::to_string(i) + "]";
        values.push_back(checkFinite(call_, -1, name.c_str()));
        lua_pop(L, 1);
    }
    pop();
    return values;
}

std::vector<std::string> TableArgs::strings(const char* key) const {
    lua_State* L = call_.L;
    const int at = push(key);
    const lua_Integer n = lua_type(L, at) == LUA_TTABLE ? lua_Integer(lua_rawlen(L, at)) : 0;
    if (n == 0)
        call_.bad(key, at, "a non-empty list of strings {\"a\", \"b\", ...}");
    std::vector<std::string> values;
    for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L, at, i);
        const std::string name = std::string(key) + "[" + std::to_string(i) + "]";
        values.push_back(checkString(call_, -1, name.c_str()));
        lua_pop(L, 1);
    }
    pop();
    return values;
}

} // namespace netsculpt::lua
