#pragma once
// A wall-clock limit for `netsculpt run --max-seconds`: a script stuck inside a library call (a
// backtracking string pattern, a long relaxation) never reaches the instruction budget's hook,
// so a thread of its own ends the process when the time is up. That is safe for the files: the
// journal is synced entry by entry (a torn last entry is dropped when it is opened) and every
// other file is written whole to a temporary and renamed.

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace netsculpt::cli {

class Watchdog {
  public:
    /// After `seconds` prints `message` on stderr and exits 1. No limit (no thread) for 0 or
    /// for more than about a century.
    Watchdog(double seconds, std::string message);
    ~Watchdog(); ///< stands the watchdog down
    Watchdog(const Watchdog&) = delete;
    Watchdog& operator=(const Watchdog&) = delete;

  private:
    std::mutex mutex_;
    std::condition_variable wake_;
    bool done_ = false;
    std::thread thread_;
};

} // namespace netsculpt::cli
