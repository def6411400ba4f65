#include "Interrupt.h"

#include <csignal>
#include <unistd.h>

namespace netsculpt::cli {

namespace {

std::atomic<bool> interrupted{false};
std::atomic<bool> acknowledge{true};
static_assert(std::atomic<bool>::is_always_lock_free, "read and written in a signal handler");
struct sigaction before {};

void onInterrupt(int) {
    interrupted.store(true);
    static constexpr char kMessage[] =
        "\nnetsculpt: Ctrl-C: stopping (Ctrl-C again to quit at once)\n";
    if (!acknowledge.load())
        return;
    [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
}

} // namespace

InterruptRequest::InterruptRequest(bool quiet) {
    interrupted.store(false);
    acknowledge.store(!quiet);
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
