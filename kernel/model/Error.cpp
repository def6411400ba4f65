#include "model/Error.h"

#include <charconv>
#include <cmath>

namespace netsculpt {

std::string formatNumber(double value) {
    if (std::isnan(value)) return "nan"; // whatever its sign bit: "-nan" reads as a number
    char buffer[32];
    auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

} // namespace netsculpt
