#pragma once
// Helpers shared by the readers and writers of kernel/io: round-trip number formatting,
// strict number parsing, message-safe quoting, and atomic file writes. Internal to kernel/io.

#include "geometry/Vec3.h"

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace netsculpt::io {

/// Appends `value` in the shortest form that reads back to the same double (std::to_chars).
void appendNumber(std::string& out, double value);
/// Appends "x<sep>y<sep>z" with appendNumber.
void appendVec(std::string& out, const Vec3& v, char separator);
/// The parts one after the other. (GCC 12 warns falsely, -Wrestrict, on "x" + std::string&&.)
std::string concat(std::initializer_list<std::string_view> parts);
/// The items separated by ", " ("" for none).
std::string listed(const std::vector<std::string>& items);
/// Appends the integers separated by `separator` (and nothing before the first).
void appendIntegers(std::string& out, std::initializer_list<long long> values,
                    char separator = ' ');
/// The shortest round-trip text of `value`.
std::string numberText(double value);

/// Parses a whole field as a double (surrounding blanks allowed, a leading '+' allowed).
/// Empty when the text is not a number; NaN and infinities parse (callers check isfinite).
std::optional<double> parseDouble(std::string_view text);
/// Why parseDouble refused `text`: "is out of range (...)" for a number beyond what a double
/// holds (1e400, 1e-400), else "is not a number".
std::string numberRefusal(std::string_view text);
/// Parses a whole field as an integer (surrounding blanks allowed).
std::optional<long long> parseInteger(std::string_view text);

std::string_view trim(std::string_view text);
/// `text` cut to `limit` characters with control and non-ASCII bytes shown as \xNN, in quotes:
/// safe to put into an error message whatever the file held.
std::string quoted(std::string_view text, std::size_t limit = 40);
/// The extension without the dot, in lower case ("" when none).
std::string lowerExtension(const std::filesystem::path& path);
/// "file.dxf" as it should appear at the start of messages (the path as given).
std::string displayName(const std::filesystem::path& path);

/// Reads a whole file; UserError naming the file when it cannot be read.
std::string readWholeFile(const std::filesystem::path& path);
/// Writes `bytes` to a temporary file beside `path`, flushes and syncs it, then renames it over
/// `path`. On any failure the temporary file is removed, `path` is untouched and UserError says
/// why (with the OS's reason).
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

} // namespace netsculpt::io
