#pragma once
// What a run leaves in its output folder from before it. A run replaces the files it writes
// (each whole, by rename) and leaves every other one as it was, so after a script that stopped
// half way, or one that no longer exports a file, the folder holds files of an earlier run
// next to this run's journal: `netsculpt run` names them.

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace netsculpt::cli {

/// The regular files under a folder (relative paths), each with what changes when it is
/// written again: its inode (a file replaced by rename is a new one) and its modification time.
class FolderFiles {
  public:
    /// Lists `folder` now; a folder with more than `limit` files is listed in part.
    explicit FolderFiles(const std::filesystem::path& folder, std::size_t limit = 100'000);
    /// The files listed then that are still there, unwritten since, by relative path.
    [[nodiscard]] std::vector<std::string> unchanged() const;

  private:
    struct Stamp {
        unsigned long long inode = 0;
        long long seconds = 0, nanoseconds = 0;
        bool operator==(const Stamp&) const = default;
    };
    static bool stamp(const std::filesystem::path& file, Stamp& out);

    std::filesystem::path folder_;
    std::map<std::string, Stamp> files_;
};

/// "3 files in out/x are from before this run, which did not write them: a.csv, b.png,
/// c.netj" (at most `shown` names, then "and N more"); empty when there are none.
std::string leftoverNote(const std::filesystem::path& folder, const std::vector<std::string>& files,
                         std::size_t shown = 8);

} // namespace netsculpt::cli
