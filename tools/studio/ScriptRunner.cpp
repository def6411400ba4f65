#include "ScriptRunner.h"

namespace netsculpt::studio {

// The Lua binding's "run a script on this document" entry point is not wired in yet; see
// ScriptRunner.h. Replace this with a runner that calls it.
std::unique_ptr<ScriptRunner> makeScriptRunner() { return nullptr; }

} // namespace netsculpt::studio
