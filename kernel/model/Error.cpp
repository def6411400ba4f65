#include "model/Error.h"

#include <charconv>

namespace netsculpt {

std::string formatNumber(double value) {
    char buffer[32];
    auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

} // namespace netsculpt
