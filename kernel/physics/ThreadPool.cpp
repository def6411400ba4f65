#include "physics/ThreadPool.h"

#include <algorithm>
#include <cassert>
#include <cstdint>

namespace netsculpt {

namespace {

// About 10..50 microseconds of polling: longer than the gap between the tasks of one
// relaxation step, far shorter than a scheduler time slice.
constexpr int kSpinIterations = 20000;

inline void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

} // namespace

ThreadPool::ThreadPool(int threads) {
    assert(threads >= 0);
    if (threads == 0)
        threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    workers_.reserve(static_cast<std::size_t>(threads - 1));
    for (int worker = 1; worker < threads; ++worker)
        workers_.emplace_back([this, worker] { workerLoop(worker); });
}

ThreadPool::~ThreadPool() {
    stop_.store(true, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
    generation_.notify_all();
    for (std::thread& worker : workers_)
        worker.join();
}

void ThreadPool::dispatch(void* context, Trampoline trampoline) {
    context_ = context;
    trampoline_ = trampoline;
    pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release); // publishes context_ and trampoline_
    generation_.notify_all();

    trampoline(context, 0);

    for (int spin = 0; spin < kSpinIterations; ++spin) {
        if (pending_.load(std::memory_order_acquire) == 0)
            return;
        cpuRelax();
    }
    for (int left = pending_.load(std::memory_order_acquire); left != 0;
         left = pending_.load(std::memory_order_acquire))
        pending_.wait(left, std::memory_order_acquire);
}

void ThreadPool::workerLoop(int worker) {
    std::uint64_t seen = 0;
    for (;;) {
        std::uint64_t now = generation_.load(std::memory_order_acquire);
        for (int spin = 0; now == seen && spin < kSpinIterations; ++spin) {
            cpuRelax();
            now = generation_.load(std::memory_order_acquire);
        }
        while (now == seen) {
            generation_.wait(seen, std::memory_order_acquire);
            now = generation_.load(std::memory_order_acquire);
        }
        seen = now;
        if (stop_.load(std::memory_order_relaxed))
            return;
        trampoline_(context_, worker);
        if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1)
            pending_.notify_one();
    }
}

} // namespace netsculpt
