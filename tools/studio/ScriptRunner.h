#pragma once
// "Run a Lua script" in the studio: the script runs in the sandbox of scripting/ScriptHost.h, and
// its commands are replayed through the studio's document (so they are journaled and undoable
// like gestures). A script builds a new sculpture, so the document must be new.

#include "commands/Document.h"

#include <filesystem>
#include <memory>
#include <string>

namespace netsculpt::studio {

class ScriptRunner {
  public:
    virtual ~ScriptRunner() = default;
    /// Runs `script` against `doc`. Throws UserError with the script's message (file:line: ...).
    virtual void run(Document& doc, const std::filesystem::path& script) = 0;
};

/// The runner of this build (null would mean a studio without the Lua binding).
std::unique_ptr<ScriptRunner> makeScriptRunner();

} // namespace netsculpt::studio
