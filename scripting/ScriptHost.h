#pragma once
// Runs a Lua script that builds sculptures: a fresh Lua state with the standard libraries,
// netsculpt preloaded (require "netsculpt"), the sandbox (unless unsafe) and the limits. The
// script's errors, including a limit being hit, come back as a ScriptResult; the host goes on.

#include "physics/Relaxer.h"
#include "scripting/Context.h"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace netsculpt::lua {

struct ScriptOptions {
    /// Where doc:save / doc:export write (relative paths) and where journals go. Must exist.
    std::filesystem::path outputDir = ".";
    /// Lift the sandbox (Sandbox.h). The limits stay.
    bool unsafe = false;
    /// Folders of shared Lua modules (a studio's helpers): `require` finds modules there and the
    /// script may read in them, after its own folder and the output folder. Each must exist.
    std::vector<std::filesystem::path> libraryDirs;
    std::size_t maxMemory = std::size_t(512) << 20; ///< bytes the Lua state may hold; 0 = no limit
    std::uint64_t maxInstructions = 1'000'000'000;  ///< VM instructions; 0 = no budget
    /// Relax every doc:relax with this backend, overriding the script's choice. Empty = the
    /// script's.
    std::string backend;
    /// Journal the documents the script makes to outputDir/<stem>.netj (runFile: the script's
    /// file name without extension). Empty for runString = no journal.
    bool journal = true;
    std::string journalStem;
    /// The script's command-line arguments: the global `arg` (arg[0] = the script, arg[1..])
    /// and the main chunk's `...`, as the stock `lua` interpreter gives them.
    std::vector<std::string> args;
    /// Called during every doc:relax. Empty = none.
    std::function<void(const RelaxProgress&)> relaxProgress;
    /// Called when a doc:relax returns. Empty = none.
    std::function<void(const Document&, const RelaxResult&)> relaxFinished;
    /// When it reads true (the CLI's Ctrl-C) the script stops as at a limit, with "script
    /// interrupted (Ctrl-C)"; a doc:relax under way stops at its next step first, its shape the
    /// one reached. Null = none. Must outlive the run.
    const std::atomic<bool>* interrupt = nullptr;
};

struct ScriptResult {
    bool ok = true;
    /// The error, one line first ("default.lua:12: attach_to_rail: argument 'rows' ..."); for a
    /// limit: "script exceeded 512 MiB of memory" / "script exceeded its budget of 10^9
    /// instructions" / "script interrupted (Ctrl-C)", with the place when known.
    std::string error;
    std::string traceback;  ///< the Lua stack at the error, when there was one
    Stop stop = Stop::None; ///< which limit stopped the script
    std::vector<std::filesystem::path> journals;
    std::uint64_t instructions = 0; ///< counted to the hook's interval (1000)
    std::size_t peakMemory = 0;     ///< bytes
};

/// Runs the script file (its folder is the script folder of the sandbox).
ScriptResult runScriptFile(const std::filesystem::path& script, const ScriptOptions& options);
/// Runs Lua source; `chunkName` names it in messages; `scriptDir` is where it may read.
ScriptResult runScriptString(std::string_view source, const std::string& chunkName,
                             const std::filesystem::path& scriptDir, const ScriptOptions& options);

} // namespace netsculpt::lua
