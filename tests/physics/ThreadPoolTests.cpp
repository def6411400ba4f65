#include "physics/ThreadPool.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

using namespace netsculpt;

TEST_CASE("parallelFor runs every chunk once, covering the range in index order", "[threadpool]") {
    for (int threads : {1, 2, 3}) {
        ThreadPool pool(threads);
        REQUIRE(pool.size() == threads);
        const int rounds = threads <= 2 ? 500 : 20; // 3 threads may exceed the cores
        for (std::size_t count : {0u, 1u, 2u, 7u, 1000u}) {
            const std::size_t chunks = pool.chunkCount(count);
            CHECK(chunks <= count);
            CHECK((threads == 1 ? chunks == std::min<std::size_t>(count, 1)
                                : chunks >= std::min<std::size_t>(count, 2)));
            for (int round = 0; round < rounds; ++round) {
                std::vector<int> hits(count, 0);
                std::vector<std::size_t> begins(chunks, 0), ends(chunks, 0);
                std::atomic<int> calls{0};
                pool.parallelFor(count, [&](std::size_t begin, std::size_t end, std::size_t chunk) {
                    ++calls;
                    begins[chunk] = begin;
                    ends[chunk] = end;
                    for (std::size_t i = begin; i < end; ++i)
                        ++hits[i];
                });
                REQUIRE(calls.load() == static_cast<int>(chunks));
                for (int h : hits)
                    REQUIRE(h == 1);
                for (std::size_t c = 0; c < chunks; ++c) {
                    REQUIRE(begins[c] < ends[c]);
                    REQUIRE(begins[c] == (c == 0 ? 0 : ends[c - 1]));
                }
            }
        }
    }
}

TEST_CASE("A default pool has one thread per hardware thread", "[threadpool]") {
    ThreadPool pool;
    CHECK(pool.size() == static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
}

TEST_CASE("A pool that shares cores runs a task on its fair share of them, in the same chunks",
          "[threadpool]") {
    SharedCores cores(4);
    ThreadPool pool(4);
    pool.share(&cores);
    const std::size_t count = 1000, chunks = pool.chunkCount(count);
    const auto runOn = [&] { // the number of threads that ran chunks of one task
        std::vector<std::thread::id> ranBy(chunks);
        pool.parallelFor(count, [&](std::size_t, std::size_t, std::size_t chunk) {
            ranBy[chunk] = std::this_thread::get_id();
            std::this_thread::sleep_for(std::chrono::milliseconds(2)); // time for all to join
        });
        std::sort(ranBy.begin(), ranBy.end());
        return std::unique(ranBy.begin(), ranBy.end()) - ranBy.begin();
    };
    cores.enter();
    cores.enter();
    cores.enter();
    CHECK(pool.threadsNow() == 1); // three runs on four threads: one each
    CHECK(runOn() == 1);
    cores.leave();
    CHECK(pool.threadsNow() == 2);
    CHECK(runOn() <= 2);
    cores.leave();
    CHECK(pool.threadsNow() == 4); // the last run left takes the threads the others freed
    CHECK(runOn() <= 4);
    CHECK(pool.chunkCount(count) == chunks);
    pool.share(nullptr);
    CHECK(pool.threadsNow() == 4);
}
