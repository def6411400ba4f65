#pragma once
// Ctrl-C during long work. While an InterruptRequest lives, the first Ctrl-C (SIGINT) asks the
// work to stop: a relaxation stops at its next step and `relax` saves the shape reached; a
// script stops between two instructions (or its doc:relax at its next step), its journal
// keeping the commands run so far. A second Ctrl-C ends the process at once, as Ctrl-C does
// outside such work (short commands, reading and writing files).

#include <atomic>
#include <stdexcept>

namespace netsculpt::cli {

/// 128 + SIGINT: what a shell reports for a command ended by Ctrl-C.
constexpr int kExitInterrupted = 130;

/// Work stopped by Ctrl-C before it wrote anything: main() reports "netsculpt: interrupted:
/// <what>" and exits with kExitInterrupted.
class Interrupted : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class InterruptRequest {
  public:
    /// Catches SIGINT; one at a time. The first Ctrl-C is acknowledged by a line on stderr (after
    /// a "\n" that ends the progress line when stderr is a terminal); `quiet`: no line.
    explicit InterruptRequest(bool quiet = false);
    ~InterruptRequest(); ///< gives SIGINT back its action from before
    InterruptRequest(const InterruptRequest&) = delete;
    InterruptRequest& operator=(const InterruptRequest&) = delete;

    /// Reads true once Ctrl-C was pressed while this request lived (RelaxOptions::cancel).
    const std::atomic<bool>* flag() const;
    bool requested() const { return flag()->load(); }
};

} // namespace netsculpt::cli
