#include "physics/Backends.h"

#include "model/Error.h"

namespace netsculpt {

std::vector<std::string> relaxerNames() { return {"auto", "rk4"}; }

std::unique_ptr<Relaxer> makeRelaxer(std::string_view name) {
    if (name == "rk4" || name == "auto") return std::make_unique<Rk4Relaxer>();
    if (name == "bullet")
        throw UserError("backend \"bullet\" is not available: this netsculpt was built without Bullet "
                        "(configure with -DNETSCULPT_WITH_BULLET=ON and libbullet-dev installed)");
    std::string names;
    for (const auto& n : relaxerNames()) names += (names.empty() ? "" : ", ") + n;
    throw UserError("backend \"" + std::string(name) + "\" is unknown; valid backends: " + names);
}

} // namespace netsculpt
