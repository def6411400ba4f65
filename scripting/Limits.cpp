#include "scripting/Limits.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace netsculpt::lua {

void* limitedAlloc(void* ud, void* ptr, std::size_t osize, std::size_t nsize) noexcept {
    auto* limit = static_cast<MemoryLimit*>(ud);
    const std::size_t old = ptr != nullptr ? osize : 0; // osize is a type tag when ptr is null
    if (nsize == 0) {
        std::free(ptr);
        limit->used -= old;
        return nullptr;
    }
    const bool grows = nsize > old;
    if (grows && limit->limit != 0 && limit->exempt == 0 &&
        limit->used - old + nsize > limit->limit)
        return nullptr; // Lua collects garbage, retries, then raises a memory error
    void* block = std::realloc(ptr, nsize);
    if (block == nullptr)
        return nullptr;
    limit->used = limit->used - old + nsize;
    if (limit->used > limit->peak)
        limit->peak = limit->used;
    return block;
}

MemoryLimit* memoryLimit(lua_State* L) {
    void* ud = nullptr;
    return lua_getallocf(L, &ud) == &limitedAlloc ? static_cast<MemoryLimit*>(ud) : nullptr;
}

BindingExemption::BindingExemption(lua_State* L) : limit_(memoryLimit(L)) {
    if (limit_ != nullptr)
        ++limit_->exempt;
}

BindingExemption::~BindingExemption() {
    if (limit_ != nullptr)
        --limit_->exempt;
}

std::string instructionBudgetText(std::uint64_t budget) {
    int exponent = 0;
    std::uint64_t rest = budget;
    while (rest >= 10 && rest % 10 == 0)
        rest /= 10, ++exponent;
    if (rest == 1 && exponent >= 3)
        return "10^" + std::to_string(exponent);
    return std::to_string(budget);
}

std::string memoryLimitText(std::size_t bytes) {
    constexpr std::size_t kMiB = std::size_t(1) << 20;
    if (bytes >= kMiB && bytes % kMiB == 0)
        return std::to_string(bytes / kMiB) + " MiB";
    return std::to_string(bytes) + " bytes";
}

std::string memoryExceededMessage(std::size_t limit) {
    return "script exceeded " + memoryLimitText(limit) + " of memory";
}

std::string instructionsExceededMessage(std::uint64_t budget) {
    return "script exceeded its budget of " + instructionBudgetText(budget) + " instructions";
}

const char* interruptedMessage() {
    return "script interrupted (Ctrl-C)";
}

bool interruptRequested(const ScriptContext& context) {
    return context.interrupt != nullptr && context.interrupt->load();
}

namespace {

constexpr std::uint64_t kHookInterval = 1000;

/// Instructions between two calls of the hook: the budget's interval, or the plain one when
/// only an interrupt is watched.
std::uint64_t hookInterval(std::uint64_t budget) {
    return budget != 0 && budget < kHookInterval ? budget : kHookInterval;
}

std::string stopMessage(const ScriptContext& ctx) {
    switch (ctx.stop) {
    case Stop::Memory:
        return memoryExceededMessage(ctx.maxMemory);
    case Stop::Interrupted:
        return interruptedMessage();
    default:
        return instructionsExceededMessage(ctx.maxInstructions);
    }
}

/// Pushes the message of the limit that stopped the script. The push is exempt from the memory
/// limit (it must not fail when memory is what ran out), and no C++ object is alive during it.
void pushStopMessage(lua_State* L, const ScriptContext& ctx) {
    char message[128];
    std::snprintf(message, sizeof message, "%s", stopMessage(ctx).c_str());
    MemoryLimit* limit = memoryLimit(L);
    if (limit != nullptr)
        ++limit->exempt;
    lua_pushstring(L, message);
    if (limit != nullptr)
        --limit->exempt;
}

void countHook(lua_State* L, lua_Debug*) {
    ScriptContext& ctx = context(L);
    ctx.instructions += hookInterval(ctx.maxInstructions);
    if (ctx.stop == Stop::None && ctx.maxInstructions != 0 &&
        ctx.instructions > ctx.maxInstructions)
        ctx.stop = Stop::Instructions;
    if (ctx.stop == Stop::None && interruptRequested(ctx))
        ctx.stop = Stop::Interrupted;
    if (ctx.stop == Stop::None)
        return;
    luaL_where(L, 0); // the Lua function being run (a hook has no frame of its own)
    pushStopMessage(L, ctx);
    lua_concat(L, 2);
    lua_error(L); // no C++ object lives in this frame
}

/// After a protected call failed with the error at `errorIndex`: if a limit was hit, re-raise.
void letLimitsThrough(lua_State* L, int status, int errorIndex) {
    ScriptContext& ctx = context(L);
    const bool memory = status == LUA_ERRMEM ||
                        (lua_type(L, errorIndex) == LUA_TSTRING &&
                         std::strcmp(lua_tostring(L, errorIndex), "not enough memory") == 0);
    if (memory && ctx.maxMemory != 0 && ctx.stop == Stop::None)
        ctx.stop = Stop::Memory;
    if (ctx.stop == Stop::None)
        return;
    // Re-raise the limit's own message: a message handler may have replaced the error object.
    const char* error =
        lua_type(L, errorIndex) == LUA_TSTRING ? lua_tostring(L, errorIndex) : nullptr;
    const bool isLimitMessage = error != nullptr && (std::strstr(error, "script exceeded") ||
                                                     std::strstr(error, interruptedMessage()));
    if (isLimitMessage)
        lua_pushvalue(L, errorIndex);
    else
        pushStopMessage(L, ctx);
    lua_error(L);
}

// pcall and xpcall as in lbaselib.c, with letLimitsThrough.
int finishProtectedCall(lua_State* L, int status, lua_KContext extra) {
    if (status != LUA_OK && status != LUA_YIELD) {
        letLimitsThrough(L, status, -1);
        lua_pushboolean(L, 0);
        lua_pushvalue(L, -2);
        return 2;
    }
    return lua_gettop(L) - int(extra);
}

int checkedPcall(lua_State* L) {
    luaL_checkany(L, 1);
    lua_pushboolean(L, 1);
    lua_insert(L, 1);
    const int status = lua_pcallk(L, lua_gettop(L) - 2, LUA_MULTRET, 0, 0, finishProtectedCall);
    return finishProtectedCall(L, status, 0);
}

int checkedXpcall(lua_State* L) {
    const int n = lua_gettop(L);
    luaL_checktype(L, 2, LUA_TFUNCTION);
    lua_pushboolean(L, 1);
    lua_pushvalue(L, 1);
    lua_rotate(L, 3, 2);
    const int status = lua_pcallk(L, n - 2, LUA_MULTRET, 2, 2, finishProtectedCall);
    return finishProtectedCall(L, status, 2);
}

/// coroutine.resume (the original is upvalue 1): an error that is a limit's goes on up.
int checkedResume(lua_State* L) {
    const int n = lua_gettop(L);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, n, LUA_MULTRET);
    if (lua_gettop(L) >= 2 && !lua_toboolean(L, 1))
        letLimitsThrough(L, LUA_ERRRUN, 2);
    return lua_gettop(L);
}

/// setmetatable (the original is upvalue 1), refusing a metatable with a __gc field while there
/// is an instruction budget: Lua runs finalizers with its hooks off, so the budget could not
/// stop one (a finalizer with an endless loop hung the run, or the closing of the state, for
/// ever). Any value of __gc is refused, not only a function: Lua marks an object for
/// finalization when its metatable has the field at setmetatable, whatever its value, and a
/// function put there afterwards is then called.
int checkedSetmetatable(lua_State* L) {
    const std::uint64_t budget = context(L).maxInstructions;
    if (budget != 0 && lua_type(L, 2) == LUA_TTABLE) {
        lua_pushliteral(L, "__gc");
        const bool finalizer = lua_rawget(L, 2) != LUA_TNIL;
        lua_pop(L, 1);
        if (finalizer) {
            // luaL_error does not return: no std::string may be alive when it is called.
            char text[32];
            std::snprintf(text, sizeof text, "%s", instructionBudgetText(budget).c_str());
            return luaL_error(L,
                              "setmetatable: a metatable with a __gc field is not allowed while "
                              "the script has an instruction budget (%s): Lua runs finalizers "
                              "with its hooks off, so the budget could not stop one; "
                              "--max-instructions 0 lifts the budget",
                              text);
        }
    }
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
}

} // namespace

void installLimits(lua_State* L, ScriptContext& context) {
    if (context.maxInstructions != 0 || context.interrupt != nullptr)
        lua_sethook(L, countHook, LUA_MASKCOUNT, int(hookInterval(context.maxInstructions)));
    lua_pushcfunction(L, checkedPcall);
    lua_setglobal(L, "pcall");
    lua_pushcfunction(L, checkedXpcall);
    lua_setglobal(L, "xpcall");
    lua_getglobal(L, "setmetatable");
    lua_pushcclosure(L, checkedSetmetatable, 1);
    lua_setglobal(L, "setmetatable");
    if (lua_getglobal(L, "coroutine") == LUA_TTABLE) {
        lua_getfield(L, -1, "resume");
        lua_pushcclosure(L, checkedResume, 1);
        lua_setfield(L, -2, "resume");
    }
    lua_pop(L, 1);
}

} // namespace netsculpt::lua
