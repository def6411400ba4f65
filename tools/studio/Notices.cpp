#include "Notices.h"

#include <cmath>
#include <cstdio>

namespace netsculpt::studio {

Notice exportNotice(const std::string& path, bool relaxed, double previewScale) {
    const std::string done = "exported " + path;
    if (relaxed)
        return {done, false};
    const std::string refine = "; Refine, then export again for the net maker and the installer";
    if (previewScale > 0 && previewScale < 1) {
        // At the material's stiffness a preview's stretch reads as forces 1/scale too large.
        char text[160];
        std::snprintf(text, sizeof text,
                      ": not the relaxed shape but the preview's at x%.2g stiffness, so its "
                      "forces (tensions, rail loads) read about %.0f times too large",
                      previewScale, std::round(1 / previewScale));
        return {done + text + refine, true};
    }
    return {done + ": not the relaxed shape, so its forces (tensions, rail loads) are not final" +
                refine,
            true};
}

Notice openNotice(const std::string& done, const std::vector<std::string>& warnings) {
    Notice notice{done, !warnings.empty()};
    for (std::size_t i = 0; i < warnings.size(); ++i)
        notice.text += (i == 0 ? ", but " : "; ") + warnings[i];
    return notice;
}

} // namespace netsculpt::studio
