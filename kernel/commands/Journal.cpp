#include "commands/Journal.h"

#include "commands/JsonCodec.h"
#include "commands/TemporaryFiles.h"
#include "model/Error.h"

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <unistd.h>

namespace netsculpt {

namespace {

using codec::Json;

constexpr std::string_view kMagic = "netsculpt-journal";

std::string systemError(const std::string& what, const std::filesystem::path& path, int error) {
    return "cannot " + what + " " + path.string() + ": " + std::strerror(error);
}

int syncFd(int fd) {
#ifdef __linux__
    return ::fdatasync(fd);
#else
    return ::fsync(fd);
#endif
}

void syncFolderOf(const std::filesystem::path& path) {
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return; // best effort: some file systems do not let a folder be opened
    (void)::fsync(fd);
    ::close(fd);
}

/// A short, printable excerpt of a line for messages.
std::string excerpt(std::string_view line) {
    std::string out;
    for (char c : line.substr(0, 60)) out += (c >= 32 && c < 127) ? c : '?';
    if (line.size() > 60) out += "...";
    return "\"" + out + "\"";
}

std::string hex8(std::uint32_t v) {
    char buffer[9];
    std::snprintf(buffer, sizeof buffer, "%08x", v);
    return buffer;
}

bool parseHex8(std::string_view text, std::uint32_t& out) {
    if (text.size() != 8) return false;
    out = 0;
    for (char c : text) {
        int d;
        if (c >= '0' && c <= '9') d = c - '0';
        else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
        else return false;
        out = (out << 4) | std::uint32_t(d);
    }
    return true;
}

/// Checks the framing and checksum of an entry line (without its newline); returns the JSON text
/// or throws UserError describing what is wrong (the caller adds the line number).
std::string_view checkedJson(std::string_view line) {
    if (line.size() < 10 || line[8] != ' ')
        throw UserError("not an entry (expected \"<8 hex digits> <JSON>\"): " + excerpt(line));
    std::uint32_t stored = 0;
    if (!parseHex8(line.substr(0, 8), stored))
        throw UserError("not an entry (expected \"<8 hex digits> <JSON>\"): " + excerpt(line));
    const std::string_view json = line.substr(9);
    const std::uint32_t actual = crc32(json);
    if (stored != actual)
        throw UserError("bad checksum (the line says " + hex8(stored) + ", its text gives " + hex8(actual) + "): " +
                        excerpt(line));
    return json;
}

} // namespace

std::string describe(const JournalEntry& entry) {
    std::string what = entry.kind == JournalEntry::Kind::Undo   ? "undo"
                       : entry.kind == JournalEntry::Kind::Redo ? "redo"
                                                                : commandName(entry.command);
    if (entry.line > 0) return "line " + std::to_string(entry.line) + " (" + what + ")";
    return "entry " + std::to_string(entry.seq) + " (" + what + ")";
}

std::uint32_t crc32(std::string_view bytes) {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xffffffffu;
    for (unsigned char b : bytes) c = table[(c ^ b) & 0xffu] ^ (c >> 8);
    return c ^ 0xffffffffu;
}

std::string journalHeader() { return std::string(kMagic) + " " + std::to_string(kJournalFormat) + "\n"; }

std::string entryJson(const JournalEntry& entry) {
    const Json j = codec::entryObject(entry);
    // ensure_ascii: a line is plain ASCII whatever the names hold. Text that is not UTF-8 is
    // refused rather than replaced, which would make the replay differ from the original.
    try {
        return j.dump(-1, ' ', true);
    } catch (const Json::type_error&) {
        throw UserError(commandName(entry.command) + ": names and paths must be valid UTF-8 text");
    }
}

std::string encodeJournalLine(const JournalEntry& entry) {
    const std::string json = entryJson(entry);
    return hex8(crc32(json)) + " " + json + "\n";
}

JournalEntry decodeEntryJson(std::string_view text) {
    return codec::decodeEntryObject(codec::parseJson(text));
}

namespace {

/// What a garbled last line held: one entry, or the text of several when a line end between
/// them was damaged (each entry has one "seq").
std::string garbledLastLine(std::string_view body) {
    std::size_t entries = 0;
    for (std::size_t at = body.find("\"seq\":"); at != std::string_view::npos;
         at = body.find("\"seq\":", at + 1))
        ++entries;
    if (entries <= 1)
        return "a garbled last entry";
    return "a garbled last line holding the text of " + std::to_string(entries) +
           " entries (a damaged line end joined them; all " + std::to_string(entries) +
           " are lost)";
}

} // namespace

JournalContents parseJournal(std::string_view text, const std::string& name) {
    JournalContents out;
    // A line may end in "\r\n" (a journal checked out with Windows line endings): the "\r" is
    // not part of the line.
    // ---- header ----
    const std::size_t headerEnd = text.find('\n');
    if (headerEnd == std::string_view::npos) {
        const std::string header = journalHeader();
        if (text.empty() || std::string_view(header).substr(0, text.size()) == text) {
            out.warnings.push_back(name + (text.empty() ? " is empty" : " has a torn header line") +
                                   "; it is started afresh");
            return out;
        }
        throw UserError(name + " is not a netsculpt journal (its first line is " + excerpt(text) + ")");
    }
    const std::string_view header = withoutCarriageReturn(text.substr(0, headerEnd));
    const std::string prefix = std::string(kMagic) + " ";
    if (header.substr(0, prefix.size()) != prefix)
        throw UserError(name + " is not a netsculpt journal (its first line is " + excerpt(header) +
                        ", expected \"" + std::string(kMagic) + " " + std::to_string(kJournalFormat) + "\")");
    const std::string_view versionText = header.substr(prefix.size());
    int version = 0;
    const bool digits = !versionText.empty() && versionText.size() < 9 &&
                        versionText.find_first_not_of("0123456789") == std::string_view::npos;
    if (digits) version = std::stoi(std::string(versionText));
    if (!digits || version < 1)
        throw UserError(name + " line 1: bad journal format version " + excerpt(versionText));
    if (version > kJournalFormat)
        throw UserError(name + ": journal format " + std::to_string(version) + " is newer than this netsculpt (reads " +
                        std::to_string(kJournalFormat) + ")");
    out.validBytes = headerEnd + 1;

    // ---- entries ----
    std::size_t pos = headerEnd + 1;
    int line = 1;
    while (pos < text.size()) {
        ++line;
        const std::size_t end = text.find('\n', pos);
        const bool torn = end == std::string_view::npos;
        const std::string_view body =
            withoutCarriageReturn(text.substr(pos, torn ? std::string_view::npos : end - pos));
        const bool last = torn || end + 1 == text.size();
        const std::string where = name + " line " + std::to_string(line);
        if (torn) {
            out.warnings.push_back(where + ": dropped a torn last entry (no end of line, so it was never "
                                           "acknowledged): " + excerpt(body));
            break;
        }
        // Damage a crash can cause (a bad checksum, broken JSON) is forgiven in the last entry
        // only; an entry that is intact but wrong (unknown command, bad argument) never is.
        Json object;
        try {
            object = codec::parseJson(checkedJson(body));
        } catch (const UserError& e) {
            if (last) {
                out.warnings.push_back(where + ": dropped " + garbledLastLine(body) + " (" +
                                       e.what() + ")");
                break;
            }
            throw UserError(where + ": " + e.what() + "; the journal is damaged before its last entry");
        }
        JournalEntry entry;
        try {
            entry = codec::decodeEntryObject(object);
        } catch (const UserError& e) {
            throw UserError(where + ": " + e.what());
        }
        entry.line = line;
        const std::uint64_t expected = out.entries.size() + 1;
        if (entry.seq != expected)
            throw UserError(name + " " + describe(entry) + ": sequence number " + std::to_string(entry.seq) +
                            ", expected " + std::to_string(expected) + " (an entry is missing or repeated)");
        out.entries.push_back(std::move(entry));
        pos = end + 1;
        out.validBytes = pos;
    }
    return out;
}

JournalContents readJournal(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw UserError(systemError("open the journal", path, errno));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) throw UserError(systemError("read the journal", path, errno));
    return parseJournal(buffer.str(), path.string());
}

void writeFileDurably(const std::filesystem::path& path, std::string_view content) {
    removeStaleTemporaries(path);
    const std::filesystem::path temp = temporaryBeside(path);
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw UserError(systemError("create", temp, errno));
    std::size_t done = 0;
    while (done < content.size()) {
        const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int error = errno;
            ::close(fd);
            ::unlink(temp.c_str());
            throw UserError(systemError("write", temp, error));
        }
        done += std::size_t(n);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        const int error = errno;
        ::unlink(temp.c_str());
        throw UserError(systemError("write", temp, error));
    }
    if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        ::unlink(temp.c_str());
        throw UserError(systemError("replace", path, error));
    }
    syncFolderOf(path);
}

void writeJournalFile(const std::filesystem::path& path, const std::vector<JournalEntry>& entries) {
    std::string content = journalHeader();
    for (const JournalEntry& e : entries) content += encodeJournalLine(e);
    writeFileDurably(path, content);
}

// ---- Journal ----

Journal::Journal(std::filesystem::path path, int fd, std::uintmax_t size)
    : path_(std::move(path)), fd_(fd), size_(size) {}

Journal::~Journal() {
    if (fd_ >= 0) ::close(fd_);
}

std::unique_ptr<Journal> Journal::create(const std::filesystem::path& path, const std::vector<JournalEntry>& entries) {
    writeJournalFile(path, entries);
    const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd < 0) throw UserError(systemError("open the journal", path, errno));
    const off_t size = ::lseek(fd, 0, SEEK_END);
    return std::unique_ptr<Journal>(new Journal(path, fd, std::uintmax_t(size)));
}

std::unique_ptr<Journal> Journal::reopen(const std::filesystem::path& path, std::uintmax_t validBytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd < 0) throw UserError(systemError("open the journal", path, errno));
    std::unique_ptr<Journal> journal(new Journal(path, fd, validBytes));
    const off_t size = ::lseek(fd, 0, SEEK_END);
    if (size < 0 || std::uintmax_t(size) != validBytes) {
        if (::ftruncate(fd, off_t(validBytes)) != 0 || syncFd(fd) != 0)
            throw UserError(systemError("cut the torn tail off the journal", path, errno));
    }
    if (validBytes == 0) journal->append(journalHeader());
    return journal;
}

void Journal::append(std::string_view line) {
    std::size_t done = 0;
    int error = 0;
    while (done < line.size()) {
        const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            error = errno;
            break;
        }
        done += std::size_t(n);
    }
    if (error == 0 && syncFd(fd_) != 0) error = errno;
    if (error != 0) {
        // Leave the file as it was, so that the next entry does not follow a partial line.
        if (::ftruncate(fd_, off_t(size_)) == 0) (void)syncFd(fd_);
        throw UserError(systemError("write to the journal", path_, error) + "; the change was not made");
    }
    size_ += line.size();
}

} // namespace netsculpt
