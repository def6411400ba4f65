#pragma once
// A small persistent pool for the solver's flat loops: the caller and (threads - 1) workers run
// one task together and the call returns when all have finished (a fork-join barrier). Workers
// spin briefly between tasks (a relaxation step issues several tasks back to back) and then
// sleep on an atomic wait, so an idle pool costs nothing. Nothing is allocated per task.
//
// Deterministic by construction for the solver's use: a task gets a fixed index range per
// worker; the solver writes results so that they do not depend on how ranges are split.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

namespace netsculpt {

class ThreadPool {
  public:
    /// threads: the total number of threads that run a task, the caller included; 0 = one per
    /// hardware thread. threads = 1 starts no worker.
    explicit ThreadPool(int threads = 0);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    /// The number of threads that run a task, the caller included (>= 1).
    int size() const { return static_cast<int>(workers_.size()) + 1; }

    /// Calls task(worker) once on each of size() threads, worker in [0, size()), the caller
    /// being worker 0, and returns when all calls have returned. task must not throw.
    template <typename Task> void run(Task& task) {
        if (workers_.empty()) {
            task(0);
            return;
        }
        dispatch(&task, [](void* context, int worker) { (*static_cast<Task*>(context))(worker); });
    }

    /// Splits [0, count) into size() contiguous ranges (worker w gets the w-th) and calls
    /// body(begin, end, worker) for each non-empty one.
    template <typename Body> void parallelFor(std::size_t count, Body&& body) {
        const std::size_t parts = static_cast<std::size_t>(size());
        auto task = [&](int worker) {
            const std::size_t w = static_cast<std::size_t>(worker);
            const std::size_t begin = count * w / parts, end = count * (w + 1) / parts;
            if (begin < end)
                body(begin, end, worker);
        };
        run(task);
    }

  private:
    using Trampoline = void (*)(void*, int);
    void dispatch(void* context, Trampoline trampoline);
    void workerLoop(int worker);

    std::vector<std::thread> workers_;
    void* context_ = nullptr;
    Trampoline trampoline_ = nullptr;
    std::atomic<std::uint64_t> generation_{0}; ///< bumped once per task; workers wait on it
    std::atomic<int> pending_{0};              ///< workers still running the current task
    std::atomic<bool> stop_{false};
};

} // namespace netsculpt
