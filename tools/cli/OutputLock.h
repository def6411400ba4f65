#pragma once
// `netsculpt run` holds its output folder for the whole run: two runs into one folder would
// append to one session journal (the entries of both interleaved, a journal that no longer
// opens) and leave each other's exports side by side. The lock is an advisory flock on the file
// OUT/.netsculpt-run.lock, which stays in the folder, empty; the system releases it when the run
// ends, however it ends (a crash, kill -9, --max-seconds), so it is never stale.

#include <filesystem>

namespace netsculpt::cli {

/// The name of the lock file in the output folder.
inline constexpr const char* kRunLockName = ".netsculpt-run.lock";

class OutputLock {
  public:
    /// Locks `folder` (which exists) or throws UserError when another process holds it, naming
    /// the folder and what to do. Where the file system has no locks (flock fails other than
    /// for a holder), the run goes on unlocked, as before.
    explicit OutputLock(const std::filesystem::path& folder);
    ~OutputLock(); ///< releases the lock; the file stays
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

  private:
    int fd_ = -1;
};

} // namespace netsculpt::cli
