#include "CholeskyBench.h"

#include "BenchScenes.h"

#include "physics/ThreadPool.h"
#include "physics/fast/SupernodalCholesky.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace netsculpt::bench {

namespace {

/// A matrix of the Newton matrix's pattern for `system` (its free knots and the bars between
/// them): each bar's axial stiffness k u u^T, plus 1 N/m on the diagonal, in the block layout
/// SupernodalCholesky::factorize takes.
struct BlockMatrix {
    std::size_t nodes = 0;
    std::vector<std::array<std::uint32_t, 2>> pairs;
    std::vector<std::array<double, 3>> coordinates;
    std::vector<double> values;
};

BlockMatrix newtonPattern(const MassSpringSystem& system) {
    BlockMatrix m;
    std::vector<std::int64_t> index(system.knotCount(), -1);
    for (std::size_t j = 0; j < system.knotCount(); ++j)
        if (!system.fixed[j]) {
            index[j] = static_cast<std::int64_t>(m.nodes++);
            const Vec3& p = system.position[j];
            m.coordinates.push_back({p.x, p.y, p.z});
        }
    std::vector<double> diagonal(9 * m.nodes, 0.0), offDiagonal;
    for (std::size_t n = 0; n < m.nodes; ++n)
        for (int i : {0, 4, 8})
            diagonal[9 * n + static_cast<std::size_t>(i)] = 1.0;
    for (std::size_t b = 0; b < system.barCount(); ++b) {
        const Vec3 d = system.position[system.barB[b]] - system.position[system.barA[b]];
        const double u[3] = {d.x / d.norm(), d.y / d.norm(), d.z / d.norm()};
        const std::int64_t ends[2] = {index[system.barA[b]], index[system.barB[b]]};
        for (std::int64_t e : ends)
            if (e >= 0)
                for (int i = 0; i < 9; ++i)
                    diagonal[9 * static_cast<std::size_t>(e) + static_cast<std::size_t>(i)] +=
                        system.kTension[b] * u[i / 3] * u[i % 3];
        if (ends[0] >= 0 && ends[1] >= 0) {
            m.pairs.push_back({static_cast<std::uint32_t>(ends[0]),
                               static_cast<std::uint32_t>(ends[1])});
            for (int i = 0; i < 9; ++i)
                offDiagonal.push_back(-system.kTension[b] * u[i / 3] * u[i % 3]);
        }
    }
    m.values = std::move(diagonal);
    m.values.insert(m.values.end(), offDiagonal.begin(), offDiagonal.end());
    return m;
}

/// Best wall seconds of `repeats` calls of `work`.
template <typename Work> double bestOf(int repeats, Work&& work) {
    double best = INFINITY;
    for (int k = 0; k < repeats; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        work();
        best = std::min(best, secondsSince(t0));
    }
    return best;
}

} // namespace

void choleskyTimes(bool quick) {
    std::printf("\n== sparse Cholesky of a tube's Newton-matrix pattern: best of %s "
                "factorizations and of 30 solves, ms\n", quick ? "3" : "10");
    for (int columns : quick ? std::vector<int>{200} : std::vector<int>{200, 1000}) {
        const MassSpringSystem tube = tubeOnCircularRail(100, columns, realisticRope());
        const BlockMatrix m = newtonPattern(tube);
        SupernodalCholesky cholesky;
        cholesky.analyse(m.nodes, m.pairs, m.coordinates);
        std::vector<double> rhs(3 * m.nodes);
        for (std::size_t i = 0; i < rhs.size(); ++i)
            rhs[i] = std::sin(0.37 * static_cast<double>(i));
        std::printf("%zu knots: factor %.1f MB, %.3g flops per factorization\n", tube.knotCount(),
                    static_cast<double>(cholesky.factorEntries()) * 8e-6, cholesky.factorFlops());
        using Precision = SupernodalCholesky::Precision;
        for (const Precision precision : {Precision::Double, Precision::Single})
            for (int threads : {1, 2}) {
                ThreadPool pool(threads);
                ThreadPool* use = threads > 1 ? &pool : nullptr;
                const double factorize = bestOf(quick ? 3 : 10, [&] {
                    if (!cholesky.factorize(m.values, 0.0, use, precision))
                        throw std::runtime_error(
                            "cholesky bench: the matrix is not positive definite");
                });
                std::vector<double> b;
                const double solve = bestOf(30, [&] {
                    b = rhs;
                    cholesky.solve(b, use);
                });
                std::printf("  %s, %d thread%s: factorization %.2f ms (%.1f GFlop/s), solve "
                            "%.2f ms\n",
                            precision == Precision::Double ? "double" : "single", threads,
                            threads > 1 ? "s" : "", factorize * 1e3,
                            cholesky.factorFlops() / factorize * 1e-9, solve * 1e3);
            }
    }
}

} // namespace netsculpt::bench
