#pragma once
// The journal file (DESIGN.md "Journal"; the format and its guarantees are in
// kernel/commands/JOURNAL.md): a versioned, human-readable, append-only text file. Line 1 is the
// header "netsculpt-journal 1"; every other line is one entry,
//     <crc32 of the JSON, 8 lowercase hex digits> <JSON object>\n
// appended with write() and made durable with fdatasync() before the call that made it returns.

#include "commands/Command.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace netsculpt {

/// The journal format this netsculpt writes and reads. Newer versions are refused.
inline constexpr int kJournalFormat = 1;

struct JournalEntry {
    enum class Kind { Command, Undo, Redo };
    Kind kind = Kind::Command;
    std::uint64_t seq = 0;  ///< 1, 2, 3, ... in file order (checked when read)
    Command command;        ///< Kind::Command only
    CommandResult created;  ///< the ids the command created, checked on replay
    bool merge = false;     ///< the command joined the previous undo step (a gesture)
    int line = 0;           ///< line number in the file it was read from; 0 = not read from a file
};

/// "line 7 (set_rows)" — how messages name an entry (line omitted when not read from a file).
std::string describe(const JournalEntry& entry);

/// CRC-32 (IEEE 802.3, the one of zlib and PNG).
std::uint32_t crc32(std::string_view bytes);

/// "netsculpt-journal 1\n".
std::string journalHeader();
/// `line` without a trailing "\r": journals and snapshots are read with either line ending
/// (a file checked out with Windows line endings), and written with "\n".
inline std::string_view withoutCarriageReturn(std::string_view line) {
    return line.ends_with('\r') ? line.substr(0, line.size() - 1) : line;
}
/// The entry's JSON object, one line, no checksum ({"seq":…,"cmd":…,"args":{…},…}).
/// Throws UserError when an argument is not finite (such a command never validates anyway).
std::string entryJson(const JournalEntry& entry);
/// The entry's journal line: "<crc32 hex> <json>\n".
std::string encodeJournalLine(const JournalEntry& entry);
/// Decodes an entry's JSON (no checksum); throws UserError (without a line number).
JournalEntry decodeEntryJson(std::string_view json);

struct JournalContents {
    std::vector<JournalEntry> entries;     ///< every good entry, in order, each with its line number
    std::uintmax_t validBytes = 0;         ///< length of the header and the good entries
    std::vector<std::string> warnings;     ///< a dropped torn or garbled last entry, an empty file
};

/// Parses journal text. `name` (the file) starts every message. A torn or garbled last entry is
/// dropped with a warning; a garbled entry elsewhere, a sequence gap, an unknown command or a
/// newer format throw UserError naming the line.
JournalContents parseJournal(std::string_view text, const std::string& name);
JournalContents readJournal(const std::filesystem::path& path);

/// Writes `content` to `path` so that a crash leaves either the old file or the new one: a
/// temporary file in the same folder, fsync, rename over `path`, fsync of the folder.
void writeFileDurably(const std::filesystem::path& path, std::string_view content);
/// Writes a whole journal (header and entries, numbered as given) with writeFileDurably.
void writeJournalFile(const std::filesystem::path& path, const std::vector<JournalEntry>& entries);

/// An open journal that entries are appended to.
class Journal {
  public:
    /// Writes header + entries durably to `path` (replacing it), then opens it for appending.
    static std::unique_ptr<Journal> create(const std::filesystem::path& path,
                                           const std::vector<JournalEntry>& entries);
    /// Opens an existing journal for appending after cutting it to `validBytes` (dropping a torn
    /// tail, synced); validBytes == 0 (an empty or torn-header file) rewrites the header.
    static std::unique_ptr<Journal> reopen(const std::filesystem::path& path, std::uintmax_t validBytes);
    ~Journal();
    Journal(const Journal&) = delete;
    Journal& operator=(const Journal&) = delete;

    /// Appends one encoded line (encodeJournalLine) with write() and syncs it. On failure the
    /// file is cut back to its previous length and UserError is thrown.
    void append(std::string_view line);
    const std::filesystem::path& path() const { return path_; }
    std::uintmax_t size() const { return size_; }

  private:
    Journal(std::filesystem::path path, int fd, std::uintmax_t size);
    std::filesystem::path path_;
    int fd_ = -1;
    std::uintmax_t size_ = 0;
};

/// The Lua script equivalent to the entries (DESIGN.md "Lua API"): one call per command, with
/// handles in locals r1, p1 (in tables rail[1], piece[1] when there are too many for locals);
/// undo and redo become as many doc:undo()/doc:redo() calls as the step had Lua calls.
/// import_rails becomes one add_rail per curve (with the source in a comment), so the script
/// does not need the imported file.
std::string journalToLua(const std::vector<JournalEntry>& entries);

} // namespace netsculpt
