#pragma once
// User errors: bad input from a script, a file or a gesture. The message names the value and
// what is allowed; the sculpture is left exactly as it was. Programmer errors are asserts.

#include <stdexcept>
#include <string>

namespace netsculpt {

class UserError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// Formats a double for messages with round-trip precision (shortest form that reads back).
std::string formatNumber(double value);

} // namespace netsculpt
