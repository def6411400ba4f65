// DXF bytes to UTF-8 text (DxfText.h): the byte-order mark, CR line ends, and the code pages
// of drawings older than AutoCAD 2007 ($DWGCODEPAGE ANSI_1252, ISO 8859-1).

#include "io/DxfText.h"

#include "io/IoText.h"
#include "model/Error.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace netsculpt::io {

namespace {

/// Windows-1252 at 0x80..0x9F (where it differs from ISO 8859-1); 0 = unassigned, read as the
/// C1 control of that number as Windows does.
constexpr std::array<char32_t, 32> kCp1252High{
    0x20AC, 0,      0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
    0x2039, 0x0152, 0,      0x017D, 0,      0,      0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
    0x2013, 0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0,      0x017E, 0x0178};

void appendUtf8(std::string& out, char32_t c) {
    if (c < 0x80) {
        out += char(c);
    } else if (c < 0x800) {
        out += char(0xC0 | (c >> 6));
        out += char(0x80 | (c & 0x3F));
    } else {
        out += char(0xE0 | (c >> 12));
        out += char(0x80 | ((c >> 6) & 0x3F));
        out += char(0x80 | (c & 0x3F));
    }
}

/// The offset of the first byte that does not belong to a well-formed UTF-8 sequence, or npos.
std::size_t firstInvalidUtf8(std::string_view s) {
    std::size_t i = 0;
    while (i < s.size()) {
        const auto b = std::uint8_t(s[i]);
        const std::size_t length = b < 0x80           ? 1
                                   : (b >> 5) == 0x6  ? 2
                                   : (b >> 4) == 0xE  ? 3
                                   : (b >> 3) == 0x1E ? 4
                                                      : 0;
        if (length == 0 || i + length > s.size())
            return i;
        char32_t c = length == 1 ? b : b & (0x7F >> length);
        for (std::size_t k = 1; k < length; ++k) {
            const auto next = std::uint8_t(s[i + k]);
            if ((next >> 6) != 0x2)
                return i;
            c = (c << 6) | (next & 0x3F);
        }
        const char32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
        if (c < least[length] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF))
            return i;
        i += length;
    }
    return std::string_view::npos;
}

std::size_t lineOf(const std::string& text, std::size_t offset) {
    return 1 + std::size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(offset), '\n'));
}

/// The value of header variable `name` ("$ACADVER"): the line two below it, before the first
/// ENDSEC. Empty when absent.
std::string headerValue(const std::vector<std::string_view>& lines, std::string_view name) {
    for (std::size_t i = 0; i + 2 < lines.size() && trim(lines[i]) != "ENDSEC"; ++i)
        if (trim(lines[i]) == name)
            return std::string(trim(lines[i + 2]));
    return {};
}

std::vector<std::string_view> splitLines(const std::string& text) {
    std::vector<std::string_view> lines;
    for (std::size_t start = 0; start < text.size();) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos)
            end = text.size();
        lines.emplace_back(text.data() + start, end - start);
        start = end + 1;
    }
    return lines;
}

std::string upper(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::toupper(c)); });
    return s;
}

std::string decodeSingleByte(const std::string& bytes, bool windows) {
    std::string out;
    out.reserve(bytes.size() + bytes.size() / 8);
    for (const char ch : bytes) {
        const auto b = std::uint8_t(ch);
        const char32_t mapped = windows && b >= 0x80 && b < 0xA0 ? kCp1252High[b - 0x80] : 0;
        appendUtf8(out, mapped != 0 ? mapped : char32_t(b));
    }
    return out;
}

} // namespace

std::string decodeDxfText(const std::string& file, std::string bytes) {
    if (bytes.starts_with("\xEF\xBB\xBF"))
        bytes.erase(0, 3);
    if (bytes.starts_with("AutoCAD Binary DXF") || bytes.find('\0') != std::string::npos)
        return bytes;
    if (bytes.find('\n') == std::string::npos && bytes.find('\r') != std::string::npos)
        std::replace(bytes.begin(), bytes.end(), '\r', '\n');
    const std::size_t bad = firstInvalidUtf8(bytes);
    if (bad == std::string::npos)
        return bytes;
    const auto lines = splitLines(bytes);
    const std::string version = headerValue(lines, "$ACADVER");
    const std::string page = headerValue(lines, "$DWGCODEPAGE");
    const std::string where = file + ": line " + std::to_string(lineOf(bytes, bad)) +
                              ": the byte " + io::quoted(bytes.substr(bad, 1)) +
                              " is not UTF-8 text";
    if (version >= "AC1021")
        throw UserError(where + ", which a drawing of AutoCAD 2007 or later ($ACADVER " + version +
                        ") must hold; the file is damaged or was written with another encoding");
    const std::string key = upper(page);
    if (key.empty() || key == "ANSI_1252")
        return decodeSingleByte(bytes, true);
    if (key == "ISO8859-1" || key == "ISO_8859-1" || key == "ISO 8859-1" || key == "ANSI_28591")
        return decodeSingleByte(bytes, false);
    throw UserError(where + ", and the drawing's code page is " + io::quoted(page) +
                    " ($DWGCODEPAGE); netsculpt reads text in ANSI_1252 and ISO8859-1 (or "
                    "UTF-8): save the drawing as DXF 2007 or later, which is UTF-8");
}

} // namespace netsculpt::io
