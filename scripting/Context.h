#pragma once
// What a Lua state running netsculpt scripts knows about its surroundings: where files may be
// read and written, whether the sandbox is on, how documents are journaled, how relaxation
// reports progress, and the limits' bookkeeping. The host (ScriptHost) owns it and stores a
// pointer in the registry; a stock lua5.4 that does require "netsculpt" gets a default one
// (no sandbox, output folder = the current directory, no journal, no limits).

#include "commands/Document.h"
#include "physics/Relaxer.h"

#include <lua.hpp>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace netsculpt::lua {

/// Why a script was stopped by the host.
enum class Stop { None, Memory, Instructions, Interrupted };

struct ScriptContext {
    bool sandboxed = false;          ///< the sandbox rules of Sandbox.h apply
    std::filesystem::path scriptDir; ///< absolute; relative reads resolve here
    std::filesystem::path outputDir; ///< absolute; relative writes resolve here
    std::vector<std::filesystem::path> libraryDirs; ///< absolute; modules and reads only

    /// Documents made by ns.new / ns.open are journaled to outputDir/<journalStem>.netj (the
    /// second one to <journalStem>.2.netj, ...). Empty = not journaled.
    std::string journalStem;
    int documentsMade = 0;
    std::vector<std::filesystem::path> journals; ///< the journals written so far

    /// Every doc:relax uses this backend when set (the CLI's --backend), whatever the script says.
    std::string backendOverride;
    /// Called during every doc:relax (the CLI's progress line). Empty = none.
    std::function<void(const RelaxProgress&)> relaxProgress;
    /// Called when a doc:relax returns (the CLI clears its progress line). Empty = none.
    std::function<void(const Document&, const RelaxResult&)> relaxFinished;

    // ---- limits (Limits.h) ----
    std::uint64_t maxInstructions = 0; ///< 0 = no budget
    std::uint64_t instructions = 0;    ///< counted in steps of the hook's interval
    std::size_t maxMemory = 0;         ///< bytes; 0 = no limit (only used for messages here)
    Stop stop = Stop::None;            ///< set once a limit is hit; the script cannot continue
    /// The host's request to stop (the CLI's Ctrl-C): read between instructions and polled by
    /// every doc:relax, which stops at its next step. Null = none.
    const std::atomic<bool>* interrupt = nullptr;
};

/// The state's context, created (default one) on first use when the host did not install one.
ScriptContext& context(lua_State* L);
/// Installs a host-owned context (before the script runs).
void installContext(lua_State* L, ScriptContext* context);

/// The journal path for the next document made in this state, or empty.
std::filesystem::path nextJournalPath(ScriptContext& context);

} // namespace netsculpt::lua
