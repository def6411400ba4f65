#include "physics/ThreadPool.h"

#include <catch2/catch.hpp>

#include <atomic>
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
