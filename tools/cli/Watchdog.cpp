#include "Watchdog.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace netsculpt::cli {

namespace {
constexpr double kLongest = 3.2e9; // s, about a century
} // namespace

Watchdog::Watchdog(double seconds, std::string message) {
    if (!(seconds > 0) || seconds > kLongest) // past a century the wait would overflow: none
        return;
    thread_ = std::thread([this, seconds, message = std::move(message)] {
        std::unique_lock lock(mutex_);
        if (wake_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return done_; }))
            return;
        std::fflush(stdout); // what the script printed so far
        std::fprintf(stderr, "netsculpt: error: %s\n", message.c_str());
        std::fflush(stderr);
        std::_Exit(1);
    });
}

Watchdog::~Watchdog() {
    if (!thread_.joinable())
        return;
    {
        std::lock_guard lock(mutex_);
        done_ = true;
    }
    wake_.notify_one();
    thread_.join();
}

} // namespace netsculpt::cli
