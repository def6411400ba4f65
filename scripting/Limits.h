#pragma once
// Limits that stop runaway scripts (scripts are shared between studios) while the host
// survives and reports:
// - memory: the state is created with limitedAlloc, which refuses to grow the state beyond the
//   limit; Lua turns that into a memory error, reported as "script exceeded 512 MiB of memory".
//   Allocations made while a bound function runs are exempt (BindingExemption): a Lua error
//   there would longjmp through C++ frames. They are bounded by the kernel's own limits, and
//   the next allocation the script makes fails if the total is then over the limit.
// - instructions: a count hook adds up the VM instructions the script executes and raises
//   "script exceeded its budget of 10^9 instructions" when they pass the budget. Time spent
//   inside one C function (a backtracking pattern in string.find, a long relaxation) is not
//   counted: the hook runs between instructions, and nothing here limits wall time.
// - an interrupt (the CLI's Ctrl-C, ScriptContext::interrupt): the same hook reads it and raises
//   "script interrupted (Ctrl-C)"; a doc:relax polls it itself.
// Once a limit is hit the script cannot continue: pcall, xpcall and coroutine.resume re-raise
// the error instead of returning it, and the hook raises it again at every turn.

#include "scripting/Context.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace netsculpt::lua {

/// The allocator's bookkeeping (its user data).
struct MemoryLimit {
    std::size_t limit = 0; ///< bytes; 0 = none
    std::size_t used = 0;  ///< bytes the state holds now
    std::size_t peak = 0;
    int exempt = 0; ///< > 0 while a bound function runs
};

/// A lua_Alloc that enforces MemoryLimit (ud).
void* limitedAlloc(void* ud, void* ptr, std::size_t osize, std::size_t nsize) noexcept;

/// The state's MemoryLimit when it was created with limitedAlloc, else null.
MemoryLimit* memoryLimit(lua_State* L);

/// Exempts allocations from the limit while it lives (invoke() holds one around each body).
class BindingExemption {
  public:
    explicit BindingExemption(lua_State* L);
    ~BindingExemption();
    BindingExemption(const BindingExemption&) = delete;
    BindingExemption& operator=(const BindingExemption&) = delete;

  private:
    MemoryLimit* limit_;
};

/// Installs the instruction hook (context.maxInstructions and context.interrupt; none when
/// neither) and replaces pcall, xpcall and coroutine.resume with versions that let a limit's
/// error through.
void installLimits(lua_State* L, ScriptContext& context);

/// "10^9" for powers of ten from 10^3, else the number: how messages show the budget.
std::string instructionBudgetText(std::uint64_t budget);
/// "512 MiB" (or bytes when below 1 MiB).
std::string memoryLimitText(std::size_t bytes);

/// The messages a stopped script reports.
std::string memoryExceededMessage(std::size_t limit);
std::string instructionsExceededMessage(std::uint64_t budget);
/// "script interrupted (Ctrl-C)": the host asked the script to stop (ScriptContext::interrupt).
const char* interruptedMessage();
/// Whether the host asked the script to stop.
bool interruptRequested(const ScriptContext& context);

} // namespace netsculpt::lua
