#pragma once
// The relaxation backends by name, for the document, the Lua binding and the CLI.

#include "physics/Relaxer.h"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace netsculpt {

/// "auto", "rk4", "fast", "bullet" — those this build has. "auto" is the fastest path that
/// converges (see makeRelaxer).
std::vector<std::string> relaxerNames();

/// A backend by name; UserError listing the valid names for an unknown one, and saying so when
/// the name is known but this build does not have it (Bullet switched off).
std::unique_ptr<Relaxer> makeRelaxer(std::string_view name);

} // namespace netsculpt
