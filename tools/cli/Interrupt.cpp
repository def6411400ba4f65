#include "Interrupt.h"

#include <csignal>
#include <unistd.h>

namespace netsculpt::cli {

namespace {

constexpr char kAcknowledgement[] =
    "\nnetsculpt: Ctrl-C: stopping (Ctrl-C again to quit at once)\n";

std::atomic<bool> interrupted{false};
/// Where the handler's line starts in kAcknowledgement: 0 on a terminal (the "\n" ends a progress
/// line first), 1 elsewhere (a log would get an empty line), -1 for no line (--quiet). Set before
/// the handler is installed: isatty is not async-signal-safe.
std::atomic<int> acknowledgementStart{-1};
static_assert(std::atomic<bool>::is_always_lock_free, "read and written in a signal handler");
static_assert(std::atomic<int>::is_always_lock_free, "read in a signal handler");
struct sigaction before {};

void onInterrupt(int) {
    interrupted.store(true);
    const int start = acknowledgementStart.load();
    if (start < 0)
        return;
    [[maybe_unused]] const ssize_t written =
        write(STDERR_FILENO, kAcknowledgement + start, sizeof kAcknowledgement - 1 - start);
}

} // namespace

InterruptRequest::InterruptRequest(bool quiet) {
    interrupted.store(false);
    acknowledgementStart.store(quiet ? -1 : isatty(STDERR_FILENO) != 0 ? 0 : 1);
    sigaction(SIGINT, nullptr, &before);
    if (before.sa_handler == SIG_IGN) // started in the background: Ctrl-C is not for it
        return;
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND | SA_RESTART; // the second Ctrl-C takes the default action
    sigaction(SIGINT, &action, &before);
}

InterruptRequest::~InterruptRequest() {
    sigaction(SIGINT, &before, nullptr);
}

const std::atomic<bool>* InterruptRequest::flag() const {
    return &interrupted;
}

} // namespace netsculpt::cli
