#include "TypedValue.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace netsculpt::studio {

bool isEdit(double value, double typed, const char* format) {
    if (!std::isfinite(typed) || typed == value)
        return false;
    char shown[64];
    std::snprintf(shown, sizeof shown, format, value);
    return typed != std::strtod(shown, nullptr);
}

} // namespace netsculpt::studio
