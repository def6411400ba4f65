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

TypedOptional readOptional(const std::string& text, std::optional<double> value,
                           const char* format) {
    const std::size_t first = text.find_first_not_of(" \t");
    TypedOptional out;
    if (first == std::string::npos) {
        out.edit = value.has_value();
        return out;
    }
    const std::string typed = text.substr(first, text.find_last_not_of(" \t") + 1 - first);
    char* end = nullptr;
    const double number = std::strtod(typed.c_str(), &end);
    if (end != typed.c_str() + typed.size()) {
        out.error = "\"" + typed + "\" is not a number (leave the field blank for none)";
        return out;
    }
    // A number not finite, 0 or negative is passed on, to be refused with what is allowed.
    out.edit = !value || !std::isfinite(number) || isEdit(*value, number, format);
    out.value = number;
    return out;
}

} // namespace netsculpt::studio
