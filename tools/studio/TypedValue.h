#pragma once
// Numbers typed into the inspector's fields. A field shows its value with a short format
// ("%.4g": a bar of 0.23456 m reads 0.2346), and Enter reads the field's text back: without
// typing anything that text is the rounded value, which is not an edit.

namespace netsculpt::studio {

/// Whether `typed`, read from a field that shows `value` with the printf `format`, is an edit: a
/// finite number other than both the value and the value as the field shows it.
bool isEdit(double value, double typed, const char* format);

} // namespace netsculpt::studio
