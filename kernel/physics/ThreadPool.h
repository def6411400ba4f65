#pragma once
// A small persistent pool for the solver's flat loops (fork-join). parallelFor splits an index
// range into fixed chunks; the caller and the workers claim chunks until none is left, and the
// call returns when every chunk is done. A worker that the OS has not scheduled yet simply
// claims nothing, so a busy machine slows a task down to the caller's pace, never to a
// scheduler time slice. Workers spin briefly between tasks (a relaxation step issues several
// back to back) and then sleep on an atomic wait. Nothing is allocated per task.
//
// Determinism: the chunks depend only on the count and size(), never on who runs them; a body
// that writes per-index results (and per-chunk partial results) gives the same bits on any
// schedule.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace netsculpt {

/// The machine's threads shared by runs going on at the same time (the independent parts of a net
/// relaxed together, each on a thread of its own): a pool that shares them (ThreadPool::share)
/// hands a task to no more threads than a fair share of the machine's, the caller included, so
/// that the runs do not crowd each other's cores, and the last runs left take the threads the
/// others have freed. Results do not depend on how many threads ran a task.
class SharedCores {
  public:
    explicit SharedCores(int threads) : threads_(threads) {}
    void enter() { running_.fetch_add(1, std::memory_order_relaxed); }
    void leave() { running_.fetch_sub(1, std::memory_order_relaxed); }
    /// The threads a run may use now: the machine's over the runs going on (at least one).
    int threadsEach() const {
        const int running = std::max(1, running_.load(std::memory_order_relaxed));
        return std::max(1, threads_ / running);
    }

  private:
    std::atomic<int> running_{0};
    int threads_;
};

class ThreadPool {
  public:
    /// threads: the total number of threads that run a task, the caller included; 0 = one per
    /// hardware thread. threads = 1 starts no worker and runs everything on the caller.
    explicit ThreadPool(int threads = 0);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    /// The number of threads that run a task, the caller included (>= 1).
    int size() const { return static_cast<int>(workers_.size()) + 1; }

    /// The number of chunks parallelFor splits a range of count indices into (<= count).
    std::size_t chunkCount(std::size_t count) const;

    /// From now on each task runs on at most `cores`' share of threads (null: all of the pool's);
    /// the chunks stay the same.
    void share(const SharedCores* cores) { shared_ = cores; }
    /// The threads the next task would run on, the caller included: what a kernel that chooses
    /// its way by the thread count (sequential or by tasks) asks, rather than size().
    int threadsNow() const { return shared_ ? std::min(size(), shared_->threadsEach()) : size(); }

    /// Calls body(begin, end, chunk) for the chunks of [0, count): contiguous ranges, chunk in
    /// [0, chunkCount(count)) in index order, each on some thread of the pool, and returns when
    /// all are done. body must not throw.
    template <typename Body> void parallelFor(std::size_t count, Body&& body) {
        const std::size_t chunks = chunkCount(count);
        const int threads = threadsNow();
        if (chunks <= 1 || threads <= 1) {
            for (std::size_t chunk = 0; chunk < chunks; ++chunk)
                body(count * chunk / chunks, count * (chunk + 1) / chunks, chunk);
            return;
        }
        auto runChunk = [&body, count, chunks](std::size_t chunk) {
            body(count * chunk / chunks, count * (chunk + 1) / chunks, chunk);
        };
        dispatch(&runChunk, chunks, threads - 1, [](void* context, std::size_t chunk) {
            (*static_cast<decltype(runChunk)*>(context))(chunk);
        });
    }

  private:
    using Trampoline = void (*)(void*, std::size_t);
    /// The task to the caller and the first `helpers` workers.
    void dispatch(void* context, std::size_t chunks, int helpers, Trampoline trampoline);
    void claimChunks(std::uint32_t generation);
    void workerLoop(int index);

    std::vector<std::thread> workers_;
    // The current task, published by the release store of ticket_/generation_.
    std::atomic<void*> context_{nullptr};
    std::atomic<Trampoline> trampoline_{nullptr};
    std::atomic<std::uint32_t> chunks_{0};
    /// (generation << 32) | next unclaimed chunk: a claim is a compare-exchange, so a late
    /// worker can never take a chunk of a later task by mistake.
    std::atomic<std::uint64_t> ticket_{0};
    std::atomic<std::uint32_t> generation_{0}; ///< bumped once per task; idle workers wait on it
    std::atomic<std::uint32_t> done_{0};       ///< chunks of the current task finished
    std::atomic<bool> stop_{false};
    std::atomic<int> helpers_{0}; ///< workers [0, helpers_) take part in the current task
    const SharedCores* shared_ = nullptr;
};

/// The pool of a relaxation over `bars` bars: `threads` (> 0) as asked, or for 0 one thread per
/// 4096 bars up to the hardware's threads (below that the barriers cost more than the work they
/// share); null when that comes to one thread.
std::unique_ptr<ThreadPool> relaxationPool(int threads, std::size_t bars);

} // namespace netsculpt
