#pragma once
// "Run a Lua script" in the studio, behind a small interface: the script's commands go through
// the studio's document (so they are journaled and undoable like gestures). The Lua binding
// (scripting/) provides the implementation; until it is wired in, makeScriptRunner() returns null
// and the studio says that scripts are not available in this build.

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

/// The runner of this build, or null when the studio was built without the Lua binding.
std::unique_ptr<ScriptRunner> makeScriptRunner();

} // namespace netsculpt::studio
