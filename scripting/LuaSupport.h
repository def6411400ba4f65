#pragma once
// Argument checking and error plumbing shared by the wrap_*.cpp files (LÖVE's habit: each bound
// function checks its arguments, calls one kernel function, pushes results, returns the count).
//
// A bound function's body takes a Call and may throw: ArgumentError for a bad argument (the
// message is already complete), UserError from the kernel (prefixed with the call's name when it
// does not start with it). invoke() catches them and raises the Lua error only after the C++
// frames are gone (lua_error longjmps; raising inside a handler would skip destructors). The
// message starts with the script's file:line (luaL_where level 1).
//
// Bodies read their arguments with raw access (no metamethods run, so no Lua code runs and no
// Lua error can longjmp through C++ frames); allocation inside a body is exempt from the
// script's memory limit for the same reason (Limits.h).

#include "geometry/Vec3.h"

#include <lua.hpp>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace netsculpt::lua {

/// A bad argument; what() is the whole message ("attach_to_rail: argument 'rows' must be ...").
class ArgumentError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// One call of a bound function: the Lua state and the call's name, for messages.
struct Call {
    lua_State* L;
    const char* name;

    /// Throws ArgumentError("<name>: <message>").
    [[noreturn]] void fail(const std::string& message) const;
    /// Throws "<name>: argument '<arg>' must be <expected>, got <value at index>".
    [[noreturn]] void bad(const char* arg, int index, const std::string& expected) const;
};

/// How a value reads in a message: -3, 0.5, "abc", true, nil, a table, piece 3.
std::string describe(lua_State* L, int index);

/// The message of the exception being handled, named after the call (for catch blocks).
std::string currentErrorMessage(const char* name);

/// The body of a bound function: returns the number of results it pushed.
using Body = int (*)(Call&);
/// Runs `body` with the exception-to-Lua-error conversion described above.
int invoke(lua_State* L, const char* name, Body body);

template <Body F> int entry(lua_State* L) {
    return invoke(L, lua_tostring(L, lua_upvalueindex(1)), F);
}

struct Function {
    const char* name;
    lua_CFunction function; ///< entry<body>, which reads its name from upvalue 1
    int arguments;          ///< the most arguments it takes (a method's self not counted)
};
/// Function::arguments of a function that takes one table of keyword arguments
/// (doc:set_rows{piece = p, rows = 3}): called with several values of which the first is no
/// table (doc:set_rows(p, 3)), it is the body that says it expects a table.
inline constexpr int kKeywordTable = -1;
/// Sets table[name] = function for each entry, a closure with the name, the argument limit and
/// whether it is a method as upvalues; the table is at the top of the stack. A call with more
/// arguments than the limit is refused, naming the extra ones: an argument in the wrong place
/// is an error, not ignored (doc:undo(3) is not doc:undo()). Trailing nils are not counted.
void setFunctions(lua_State* L, std::initializer_list<Function> functions); ///< ns.f(...)
void setMethods(lua_State* L, std::initializer_list<Function> methods);     ///< obj:f(...)

// ---- reading values (raw access; throw ArgumentError) -------------------------------------

/// A number that is a whole number in [min, max] (3 and 3.0 both count).
std::int64_t checkWhole(const Call& call, int index, const char* arg, std::int64_t min,
                        std::int64_t max);
/// A finite number.
double checkFinite(const Call& call, int index, const char* arg);
/// A string.
std::string checkString(const Call& call, int index, const char* arg);
/// A string from `allowed`; a bad one lists the allowed values.
std::string checkChoice(const Call& call, int index, const char* arg,
                        const std::vector<std::string>& allowed);
/// A point {x, y, z} (or {x=, y=, z=}) of finite numbers.
Vec3 checkVec3(const Call& call, int index, const char* arg);
/// Three finite numbers {a, b, c} or {n0=a, n1=b, n2=c} for names n: a colour {r, g, b}, ...
Vec3 checkTriple(const Call& call, int index, const char* arg, const char* const (&names)[3],
                 const char* expected);

/// "a, b or c" for messages.
std::string listOf(const std::vector<std::string>& names);

/// The keyword arguments of a call like doc:attach_to_rail{rail = r, rows = 3}: a table at
/// `index` whose keys must all be in `allowed` (a misspelt key is an error, not ignored).
class TableArgs {
  public:
    TableArgs(const Call& call, int index, std::initializer_list<const char*> allowed);

    const Call& call() const { return call_; }
    bool has(const char* key) const;
    /// Pushes the value of `key` (nil when absent) and returns its stack index; pop() removes it.
    int push(const char* key) const;
    void pop() const { lua_pop(call_.L, 1); }
    [[noreturn]] void missing(const char* key, const std::string& expected) const;

    std::int64_t whole(const char* key, std::optional<std::int64_t> fallback, std::int64_t min,
                       std::int64_t max) const;
    double finite(const char* key, std::optional<double> fallback) const;
    /// A finite number > 0 (lengths, stiffness, tolerances).
    double positive(const char* key, std::optional<double> fallback) const;
    bool boolean(const char* key, bool fallback) const;
    std::string string(const char* key, std::optional<std::string> fallback) const;
    std::string choice(const char* key, const std::vector<std::string>& allowed,
                       std::optional<std::string> fallback) const;
    Vec3 vec3(const char* key) const;
    /// A list of points {{x,y,z}, ...}.
    std::vector<Vec3> points(const char* key) const;
    /// A list of finite numbers.
    std::vector<double> numbers(const char* key) const;
    /// A non-empty list of strings.
    std::vector<std::string> strings(const char* key) const;

  private:
    const Call& call_;
    int index_;
};

// ---- pushing values -----------------------------------------------------------------------

void pushVec3(lua_State* L, const Vec3& v);
/// t[key] = value for the table at the top of the stack.
void setNumber(lua_State* L, const char* key, double value);
void setInteger(lua_State* L, const char* key, std::int64_t value);
void setBoolean(lua_State* L, const char* key, bool value);
void setString(lua_State* L, const char* key, const std::string& value);

} // namespace netsculpt::lua
