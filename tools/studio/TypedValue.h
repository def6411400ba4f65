#pragma once
// Numbers typed into the inspector's fields. A field shows its value with a short format
// ("%.4g": a bar of 0.23456 m reads 0.2346), and Enter reads the field's text back: without
// typing anything that text is the rounded value, which is not an edit.

#include <optional>
#include <string>

namespace netsculpt::studio {

/// Whether `typed`, read from a field that shows `value` with the printf `format`, is an edit: a
/// finite number other than both the value and the value as the field shows it.
bool isEdit(double value, double typed, const char* format);

/// Enter in the field of an optional number (a breaking load), which shows `value` with the
/// printf `format`, or nothing when there is none.
struct TypedOptional {
    bool edit = false;           ///< the field's text asks for another value than it showed
    std::optional<double> value; ///< what it asks for: empty = none (the field was cleared)
    std::string error;           ///< not blank and not a number: why nothing is done
};
/// Blank text is none; a number is that number, whatever it is (the command that takes it says
/// what is allowed); anything else is an error.
TypedOptional readOptional(const std::string& text, std::optional<double> value,
                           const char* format);

} // namespace netsculpt::studio
