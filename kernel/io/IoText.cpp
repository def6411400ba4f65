#include "io/IoText.h"

#include "commands/TemporaryFiles.h"
#include "model/Error.h"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <unistd.h>

namespace netsculpt::io {

void appendNumber(std::string& out, double value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, result.ptr);
}

void appendVec(std::string& out, const Vec3& v, char separator) {
    appendNumber(out, v.x);
    out += separator;
    appendNumber(out, v.y);
    out += separator;
    appendNumber(out, v.z);
}

std::string listed(const std::vector<std::string>& items) {
    std::string text;
    for (const auto& item : items)
        text += (text.empty() ? "" : ", ") + item;
    return text;
}

std::string concat(std::initializer_list<std::string_view> parts) {
    std::size_t size = 0;
    for (auto part : parts)
        size += part.size();
    std::string out;
    out.reserve(size);
    for (auto part : parts)
        out += part;
    return out;
}

void appendIntegers(std::string& out, std::initializer_list<long long> values, char separator) {
    bool first = true;
    for (long long value : values) {
        if (!first)
            out += separator;
        first = false;
        char buffer[24];
        const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
        out.append(buffer, result.ptr);
    }
}

std::string numberText(double value) {
    std::string text;
    appendNumber(text, value);
    return text;
}

std::string_view trim(std::string_view text) {
    const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
    while (!text.empty() && blank(text.front()))
        text.remove_prefix(1);
    while (!text.empty() && blank(text.back()))
        text.remove_suffix(1);
    return text;
}

std::optional<double> parseDouble(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+')
        text.remove_prefix(1);
    if (text.empty())
        return std::nullopt;
    double value = 0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    if (result.ec != std::errc() || result.ptr != text.data() + text.size())
        return std::nullopt;
    return value;
}

std::string numberRefusal(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+')
        text.remove_prefix(1);
    double value = 0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    if (result.ec != std::errc::result_out_of_range || result.ptr != text.data() + text.size())
        return "is not a number";
    const std::size_t e = text.find_last_of("eE");
    const bool tiny = e != std::string_view::npos && e + 1 < text.size() && text[e + 1] == '-';
    return tiny ? "is out of range: too near to 0 for a double (below about 2.2e-308; write 0)"
                : "is out of range: too large for a double (beyond about 1.8e308)";
}

std::optional<long long> parseInteger(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+')
        text.remove_prefix(1);
    if (text.empty())
        return std::nullopt;
    long long value = 0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    if (result.ec != std::errc() || result.ptr != text.data() + text.size())
        return std::nullopt;
    return value;
}

std::string quoted(std::string_view text, std::size_t limit) {
    std::string out = "'";
    std::size_t shown = 0;
    for (unsigned char c : text) {
        if (shown == limit) {
            out += "...";
            break;
        }
        if (c >= 0x20 && c < 0x7f && c != '\'') {
            out += char(c);
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02X", c);
            out += hex;
        }
        ++shown;
    }
    return out + "'";
}

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    if (!ext.empty() && ext.front() == '.')
        ext.erase(0, 1);
    for (char& c : ext)
        if (c >= 'A' && c <= 'Z')
            c = char(c - 'A' + 'a');
    return ext;
}

std::string displayName(const std::filesystem::path& path) {
    return path.string();
}

std::string readWholeFile(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw UserError(displayName(path) + ": is a folder, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw UserError(displayName(path) + ": cannot open the file (" + std::strerror(errno) +
                        ")");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad())
        throw UserError(displayName(path) + ": error while reading the file");
    return std::move(buffer).str();
}

namespace {

std::string osReason() {
    return std::strerror(errno);
}


} // namespace

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
    const std::string name = displayName(path);
    removeStaleTemporaries(path);
    const std::filesystem::path tmp = temporaryBeside(path);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
        throw UserError(name + ": cannot create the file (" + osReason() + ")");
    std::size_t written = 0;
    while (written < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            const std::string reason = osReason();
            ::close(fd);
            ::unlink(tmp.c_str());
            throw UserError(name + ": write failed (" + reason + ")");
        }
        written += std::size_t(n);
    }
    const bool synced = ::fsync(fd) == 0;
    std::string reason = synced ? std::string() : osReason();
    const bool closed = ::close(fd) == 0;
    if (synced && !closed)
        reason = osReason();
    if (!synced || !closed) {
        ::unlink(tmp.c_str());
        throw UserError(name + ": write failed (" + reason + ")");
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string reason = osReason();
        ::unlink(tmp.c_str());
        throw UserError(name + ": cannot replace the file (" + reason + ")");
    }
}

} // namespace netsculpt::io
