#include "physics/Backends.h"

#include "model/Error.h"
#include "physics/fast/NewtonRelaxer.h"

#ifdef NETSCULPT_HAVE_BULLET
#include "physics/bullet/BulletRelaxer.h"
#endif

namespace netsculpt {

std::vector<std::string> relaxerNames() {
    std::vector<std::string> names{"auto", "fast", "rk4"};
#ifdef NETSCULPT_HAVE_BULLET
    names.push_back("bullet");
#endif
    return names;
}

std::unique_ptr<Relaxer> makeRelaxer(std::string_view name) {
    // "auto" is the Newton path: at a rope's real stiffness it converges in tens of iterations
    // where the paper's RK4 needs millions of steps (README, "Performance").
    if (name == "auto" || name == "fast") return std::make_unique<FastRelaxer>();
    if (name == "rk4") return std::make_unique<Rk4Relaxer>();
#ifdef NETSCULPT_HAVE_BULLET
    if (name == "bullet") return std::make_unique<BulletRelaxer>();
#else
    if (name == "bullet")
        throw UserError("backend \"bullet\" is not available: this netsculpt was built without Bullet "
                        "(configure with -DNETSCULPT_WITH_BULLET=ON and libbullet-dev installed)");
#endif
    std::string names;
    for (const auto& n : relaxerNames()) names += (names.empty() ? "" : ", ") + n;
    throw UserError("backend \"" + std::string(name) + "\" is unknown; valid backends: " + names);
}

} // namespace netsculpt
