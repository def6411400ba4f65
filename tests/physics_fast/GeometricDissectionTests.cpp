// The geometric nested-dissection ordering (kernel/physics/fast/GeometricDissection.h): a valid,
// reproducible permutation whose factor costs about what METIS's does on nets.
#include "physics/fast/GeometricDissection.h"
#include "physics/fast/SupernodalCholesky.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

using namespace netsculpt;

namespace {

/// The knot graph of a net piece of rows x columns (DESIGN.md's staggered rows: knot (r, c), r
/// odd, hangs from (r-1, c) and (r-1, c+1); r even from (r-1, c-1) and (r-1, c)), closed into a
/// tube on a circle or open as a flat sheet, at its Eq. 2 start (bars 0.1 m, knots 0.1 m apart).
struct Net {
    std::size_t nodes = 0;
    std::vector<std::array<std::uint32_t, 2>> pairs;
    std::vector<std::array<double, 3>> coordinates;
    std::vector<std::int64_t> adjacencyStart;
    std::vector<std::uint32_t> adjacency;

    GeometricGraph graph() const { return {adjacencyStart, adjacency, coordinates}; }
};

Net net(int rows, int columns, bool closed) {
    Net n;
    n.nodes = static_cast<std::size_t>(rows * columns);
    auto node = [columns](int r, int c) { return static_cast<std::uint32_t>(r * columns + c); };
    const double h = std::sqrt(0.1 * 0.1 - 0.05 * 0.05);
    const double radius = 0.1 * columns / (2 * std::numbers::pi);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) {
            const double along = c + (r % 2 == 1 ? 0.5 : 0.0);
            if (closed) {
                const double angle = 2 * std::numbers::pi * along / columns;
                n.coordinates.push_back({radius * std::cos(angle), radius * std::sin(angle), -h * r});
            } else {
                n.coordinates.push_back({0.1 * along, 0.0, -h * r});
            }
            if (r == 0)
                continue;
            const int first = r % 2 == 1 ? c : c - 1;
            for (int parent : {first, first + 1}) {
                if (closed)
                    parent = (parent + columns) % columns;
                else if (parent < 0 || parent >= columns)
                    continue;
                n.pairs.push_back({node(r, c), node(r - 1, parent)});
            }
        }
    n.adjacencyStart.assign(n.nodes + 1, 0);
    for (const auto& [i, j] : n.pairs) {
        ++n.adjacencyStart[i + 1];
        ++n.adjacencyStart[j + 1];
    }
    for (std::size_t k = 0; k < n.nodes; ++k)
        n.adjacencyStart[k + 1] += n.adjacencyStart[k];
    n.adjacency.resize(2 * n.pairs.size());
    std::vector<std::int64_t> next(n.adjacencyStart.begin(), n.adjacencyStart.end() - 1);
    for (const auto& [i, j] : n.pairs) {
        n.adjacency[static_cast<std::size_t>(next[i]++)] = j;
        n.adjacency[static_cast<std::size_t>(next[j]++)] = i;
    }
    return n;
}

bool isPermutation(std::vector<std::uint32_t> order, std::size_t nodes) {
    if (order.size() != nodes)
        return false;
    std::sort(order.begin(), order.end());
    for (std::size_t k = 0; k < nodes; ++k)
        if (order[k] != k)
            return false;
    return true;
}

/// Flops of one factorization with the geometric ordering over those with METIS's.
double flopRatio(const Net& n) {
    SupernodalCholesky geometric, metis;
    geometric.analyse(n.nodes, n.pairs, n.coordinates);
    metis.analyse(n.nodes, n.pairs);
    REQUIRE(geometric.ordering() == SupernodalCholesky::Ordering::Geometric);
    REQUIRE(metis.ordering() == SupernodalCholesky::Ordering::Metis);
    INFO("geometric " << geometric.factorFlops() << " flops, METIS " << metis.factorFlops());
    return geometric.factorFlops() / metis.factorFlops();
}

} // namespace

TEST_CASE("geometric dissection: a permutation, the same on every run", "[fast]") {
    for (bool closed : {true, false}) {
        const Net n = net(40, 70, closed);
        const std::vector<std::uint32_t> order = geometricNestedDissection(n.graph());
        CHECK(isPermutation(order, n.nodes));
        CHECK(geometricNestedDissection(n.graph()) == order);
    }
    const Net tiny = net(2, 3, false); // no split: one leaf
    CHECK(isPermutation(geometricNestedDissection(tiny.graph()), tiny.nodes));
}

TEST_CASE("geometric dissection: the factor costs no more than METIS's on nets", "[fast]") {
    // Measured: 0.93 on both of these; 0.96 on the benchmark's 100 x 200 tube, 0.99 on its
    // 100 x 1000 one, 0.95 on its slack sheet (without the gap search 1.06, 1.09, 1.08).
    const double tube = flopRatio(net(60, 120, true));
    const double sheet = flopRatio(net(60, 120, false));
    INFO("tube " << tube << ", sheet " << sheet);
    CHECK(tube < 1.0);
    CHECK(sheet < 1.0);
}

TEST_CASE("geometric dissection refuses positions that do not separate the net", "[fast]") {
    Net n = net(60, 60, true);
    // Positions unrelated to the net (knots scattered at random): a median split cuts about
    // half of the bars, a separator of hundreds of knots.
    std::mt19937 random(3);
    std::uniform_real_distribution<double> uniform(0, 1);
    for (auto& p : n.coordinates)
        p = {uniform(random), uniform(random), uniform(random)};
    CHECK(geometricNestedDissection(n.graph()).empty());
    SupernodalCholesky cholesky;
    cholesky.analyse(n.nodes, n.pairs, n.coordinates);
    CHECK(cholesky.ordering() == SupernodalCholesky::Ordering::Metis);

    Net broken = net(60, 60, true);
    broken.coordinates[100][2] = std::nan("");
    CHECK(geometricNestedDissection(broken.graph()).empty());
}
