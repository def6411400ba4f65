#pragma once
// Files written whole: into a temporary name beside the target, synced, then renamed over it
// (Journal.cpp, io/IoText.cpp). A writer killed in between leaves its temporary behind; the next
// write of the same file removes the temporaries of writers that are gone.

#include <filesystem>

namespace netsculpt {

/// `path.tmp-<pid>-<n>`: a name beside `path` no other writer uses at the same time.
std::filesystem::path temporaryBeside(const std::filesystem::path& path);

/// Removes the files beside `path` named exactly `path.tmp-<pid>-<n>` (or `path.tmp-<pid>`,
/// as older writers named them) that this user's process <pid>, no longer running, left at
/// least ten minutes ago. Never throws: a temporary it cannot remove stays.
void removeStaleTemporaries(const std::filesystem::path& path);

} // namespace netsculpt
