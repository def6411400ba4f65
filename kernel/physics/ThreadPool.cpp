#include "physics/ThreadPool.h"

#include <algorithm>
#include <cassert>

namespace netsculpt {

namespace {

// Polls before sleeping: longer than the gap between the tasks of one relaxation step (a few
// microseconds), far shorter than a scheduler time slice.
constexpr int kSpinIterations = 4000;
// Chunks per thread: small enough pieces for the caller to take over a late worker's share.
constexpr std::size_t kChunksPerThread = 4;

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
        workers_.emplace_back([this, worker] { workerLoop(worker - 1); });
}

ThreadPool::~ThreadPool() {
    stop_.store(true, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
    generation_.notify_all();
    for (std::thread& worker : workers_)
        worker.join();
}

std::size_t ThreadPool::chunkCount(std::size_t count) const {
    const std::size_t wanted =
        workers_.empty() ? 1 : kChunksPerThread * static_cast<std::size_t>(size());
    return std::min(count, wanted);
}

void ThreadPool::dispatch(void* context, std::size_t chunks, int helpers, Trampoline trampoline) {
    const std::uint32_t generation = generation_.load(std::memory_order_relaxed) + 1;
    helpers_.store(helpers, std::memory_order_relaxed);
    context_.store(context, std::memory_order_relaxed);
    trampoline_.store(trampoline, std::memory_order_relaxed);
    chunks_.store(static_cast<std::uint32_t>(chunks), std::memory_order_relaxed);
    done_.store(0, std::memory_order_relaxed);
    ticket_.store(std::uint64_t{generation} << 32, std::memory_order_release);
    generation_.store(generation, std::memory_order_release);
    generation_.notify_all();

    claimChunks(generation);

    const auto all = static_cast<std::uint32_t>(chunks);
    for (int spin = 0; spin < kSpinIterations; ++spin) {
        if (done_.load(std::memory_order_acquire) == all)
            return;
        cpuRelax();
    }
    for (std::uint32_t done = done_.load(std::memory_order_acquire); done != all;
         done = done_.load(std::memory_order_acquire))
        done_.wait(done, std::memory_order_acquire);
}

void ThreadPool::claimChunks(std::uint32_t generation) {
    for (;;) {
        std::uint64_t ticket = ticket_.load(std::memory_order_acquire);
        if (static_cast<std::uint32_t>(ticket >> 32) != generation)
            return;
        const std::uint32_t chunk = static_cast<std::uint32_t>(ticket);
        const std::uint32_t chunks = chunks_.load(std::memory_order_relaxed);
        void* context = context_.load(std::memory_order_relaxed);
        Trampoline trampoline = trampoline_.load(std::memory_order_relaxed);
        if (chunk >= chunks)
            return;
        // Success proves the task (and the values just read) is still this generation's: the
        // next task is published only after all of this one's chunks are claimed and done.
        if (!ticket_.compare_exchange_weak(ticket, ticket + 1, std::memory_order_acq_rel))
            continue;
        trampoline(context, chunk);
        if (done_.fetch_add(1, std::memory_order_acq_rel) + 1 == chunks)
            done_.notify_one();
    }
}

void ThreadPool::workerLoop(int index) {
    std::uint32_t seen = 0;
    for (;;) {
        std::uint32_t now = generation_.load(std::memory_order_acquire);
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
        if (index < helpers_.load(std::memory_order_relaxed)) // (published with generation_)
            claimChunks(now);
    }
}

std::unique_ptr<ThreadPool> relaxationPool(int threads, std::size_t bars) {
    constexpr std::size_t kAutoBarsPerThread = 4096;
    if (threads == 0) {
        const std::size_t hardware = std::max(1u, std::thread::hardware_concurrency());
        threads = static_cast<int>(std::clamp<std::size_t>(bars / kAutoBarsPerThread, 1, hardware));
    }
    return threads > 1 ? std::make_unique<ThreadPool>(threads) : nullptr;
}

} // namespace netsculpt
