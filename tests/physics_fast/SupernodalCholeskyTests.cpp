// The block sparse Cholesky factorization of the Newton relaxer against Eigen's dense one.
#include "physics/ThreadPool.h"
#include "physics/fast/SupernodalCholesky.h"

#include "physics/EigenDense.h"
#include <catch2/catch.hpp>

#include <array>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace netsculpt;

namespace {

/// A random symmetric positive definite matrix of 3x3 blocks on a grid graph (rows x columns
/// nodes, a node joined to its right and lower neighbours, plus a few long links), as the
/// block values SupernodalCholesky takes and, when `withDense`, as a dense matrix.
struct Problem {
    std::size_t nodes = 0;
    std::vector<std::array<std::uint32_t, 2>> pairs;
    std::vector<double> values;
    Eigen::MatrixXd dense;
};

Problem gridProblem(int rows, int columns, unsigned seed, bool withDense = true) {
    Problem p;
    p.nodes = static_cast<std::size_t>(rows * columns);
    auto node = [columns](int r, int c) { return static_cast<std::uint32_t>(r * columns + c); };
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) {
            if (c + 1 < columns)
                p.pairs.push_back({node(r, c), node(r, c + 1)});
            if (r + 1 < rows)
                p.pairs.push_back({node(r + 1, c), node(r, c)});
        }
    p.pairs.push_back({node(0, 0), node(rows - 1, columns - 1)});
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> uniform(-1, 1);
    std::vector<Eigen::Matrix3d> pairBlocks;
    Eigen::VectorXd rowSums = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * p.nodes));
    for (const auto& [i, j] : p.pairs) {
        Eigen::Matrix3d b;
        for (int k = 0; k < 9; ++k)
            b(k / 3, k % 3) = uniform(random);
        pairBlocks.push_back(b);
        rowSums.segment<3>(3 * i) += b.cwiseAbs().rowwise().sum();
        rowSums.segment<3>(3 * j) += b.cwiseAbs().colwise().sum().transpose();
    }
    // Diagonal dominance makes it positive definite.
    for (std::size_t i = 0; i < p.nodes; ++i) {
        Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
        for (int k = 0; k < 3; ++k)
            d(k, k) = rowSums[static_cast<Eigen::Index>(3 * i) + k] + 1 + uniform(random) * 0.5;
        d(0, 1) = d(1, 0) = 0.3;
        d(1, 2) = d(2, 1) = -0.2;
        for (int k = 0; k < 9; ++k)
            p.values.push_back(d(k / 3, k % 3));
    }
    for (const Eigen::Matrix3d& b : pairBlocks)
        for (int k = 0; k < 9; ++k)
            p.values.push_back(b(k / 3, k % 3));
    if (withDense) {
        const Eigen::Index n = static_cast<Eigen::Index>(3 * p.nodes);
        p.dense = Eigen::MatrixXd::Zero(n, n);
        for (std::size_t i = 0; i < p.nodes; ++i)
            p.dense.block<3, 3>(3 * i, 3 * i) =
                Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(&p.values[9 * i]);
        for (std::size_t q = 0; q < p.pairs.size(); ++q) {
            const auto [i, j] = p.pairs[q];
            p.dense.block<3, 3>(3 * i, 3 * j) = pairBlocks[q];
            p.dense.block<3, 3>(3 * j, 3 * i) = pairBlocks[q].transpose();
        }
    }
    return p;
}

} // namespace

TEST_CASE("supernodal Cholesky solves like a dense one", "[fast]") {
    for (auto [rows, columns] : {std::pair{3, 4}, std::pair{30, 40}, std::pair{60, 60}}) {
        const Problem p = gridProblem(rows, columns, 7);
        SupernodalCholesky cholesky;
        cholesky.analyse(p.nodes, p.pairs);
        REQUIRE(cholesky.factorize(p.values, 0.0));
        Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.dense.rows(), -1, 2);
        std::vector<double> x(b.data(), b.data() + b.size());
        cholesky.solve(x);
        const Eigen::Map<Eigen::VectorXd> solution(x.data(), b.size());
        const double error = (p.dense * solution - b).cwiseAbs().maxCoeff();
        INFO(rows << " x " << columns << " nodes: residual " << error);
        CHECK(error < 1e-10);
        CHECK(cholesky.factorEntries() > 0);

        // A shift is added to every diagonal entry.
        REQUIRE(cholesky.factorize(p.values, 2.0));
        std::vector<double> y(b.data(), b.data() + b.size());
        cholesky.solve(y);
        const Eigen::Map<Eigen::VectorXd> shifted(y.data(), b.size());
        const Eigen::MatrixXd a = p.dense + 2.0 * Eigen::MatrixXd::Identity(b.size(), b.size());
        CHECK((a * shifted - b).cwiseAbs().maxCoeff() < 1e-10);
    }
}

TEST_CASE("supernodal Cholesky: the same bits with 1 and 2 threads", "[fast]") {
    const Problem p = gridProblem(60, 60, 11);
    SupernodalCholesky one, two;
    one.analyse(p.nodes, p.pairs);
    two.analyse(p.nodes, p.pairs);
    ThreadPool pool(2);
    REQUIRE(one.factorize(p.values, 0.0));
    REQUIRE(two.factorize(p.values, 0.0, &pool));
    std::vector<double> x(3 * p.nodes, 1.0), y = x;
    one.solve(x);
    two.solve(y, &pool);
    CHECK(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0);
}

TEST_CASE("supernodal Cholesky: the same bits whatever cache sizes the processor reports",
          "[fast]") {
    // Eigen blocks its products by the cache sizes it reads from the processor, and the hosts of
    // this machine kind differ (48 KiB L1 data and 1 MiB L2, or 32 KiB and 512 KiB): the
    // factorization fixes them, so these two processors' sizes give the same factor.
    const Problem p = gridProblem(150, 150, 11, false);
    const std::array<std::array<std::ptrdiff_t, 3>, 2> reported{
        {{48 << 10, 1 << 20, 512 << 20}, {16 << 10, 256 << 10, 4 << 20}}};
    std::vector<std::vector<double>> solutions;
    for (const auto& [l1, l2, l3] : reported) {
        Eigen::setCpuCacheSizes(l1, l2, l3);
        SupernodalCholesky cholesky;
        cholesky.analyse(p.nodes, p.pairs);
        REQUIRE(cholesky.factorize(p.values, 0.0));
        std::vector<double> x(3 * p.nodes, 1.0);
        cholesky.solve(x);
        solutions.push_back(x);
    }
    CHECK(std::memcmp(solutions[0].data(), solutions[1].data(),
                      solutions[0].size() * sizeof(double)) == 0);
}

TEST_CASE("supernodal Cholesky with a geometric ordering: solves like a dense one, same bits on 2 threads",
          "[fast]") {
    const Problem p = gridProblem(50, 60, 5);
    std::vector<std::array<double, 3>> coordinates;
    for (int r = 0; r < 50; ++r)
        for (int c = 0; c < 60; ++c)
            coordinates.push_back({0.1 * c, 0.0, -0.1 * r});
    SupernodalCholesky one, two;
    one.analyse(p.nodes, p.pairs, coordinates);
    two.analyse(p.nodes, p.pairs, coordinates);
    CHECK(one.ordering() == SupernodalCholesky::Ordering::Geometric);
    ThreadPool pool(2);
    REQUIRE(one.factorize(p.values, 0.0));
    REQUIRE(two.factorize(p.values, 0.0, &pool));
    Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.dense.rows(), -1, 2);
    std::vector<double> x(b.data(), b.data() + b.size()), y = x;
    one.solve(x);
    two.solve(y, &pool);
    const Eigen::Map<Eigen::VectorXd> solution(x.data(), b.size());
    CHECK((p.dense * solution - b).cwiseAbs().maxCoeff() < 1e-10);
    CHECK(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0);
}

TEST_CASE("supernodal Cholesky refuses a matrix that is not positive definite", "[fast]") {
    Problem p = gridProblem(10, 10, 3);
    SupernodalCholesky cholesky;
    cholesky.analyse(p.nodes, p.pairs);
    p.values[9 * 50 + 4] = -1; // a negative diagonal entry
    CHECK_FALSE(cholesky.factorize(p.values, 0.0));
    p.values[9 * 50 + 4] = std::nan("");
    CHECK_FALSE(cholesky.factorize(p.values, 0.0));
    p.values[9 * 50 + 4] = -1;
    CHECK(cholesky.factorize(p.values, 1e3)); // a large enough shift makes it definite
}

TEST_CASE("supernodal Cholesky: shared supernodes give the same bits on 1 and 2 threads",
          "[fast]") {
    // Grids whose top separators are wide enough to be shared, of several widths (so that the
    // column and row ranges fall at different places of the products' register blocks), in
    // both precisions (their register blocks differ).
    using Precision = SupernodalCholesky::Precision;
    for (auto [rows, columns] :
         {std::pair{40, 70}, std::pair{45, 45}, std::pair{37, 53}, std::pair{80, 33}}) {
        const Problem p = gridProblem(rows, columns, 13);
        SupernodalCholesky one, two;
        one.analyse(p.nodes, p.pairs);
        two.analyse(p.nodes, p.pairs);
        REQUIRE(two.sharedSupernodes() > 0);
        ThreadPool pool(2);
        for (const Precision precision : {Precision::Double, Precision::Single})
            for (int repeat = 0; repeat < 3; ++repeat) {
                INFO(rows << " x " << columns << " nodes, single "
                          << (precision == Precision::Single) << ", shift " << 0.5 * repeat);
                REQUIRE(one.factorize(p.values, 0.5 * repeat, nullptr, precision));
                REQUIRE(two.factorize(p.values, 0.5 * repeat, &pool, precision));
                Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.dense.rows(), -1, 2);
                std::vector<double> x(b.data(), b.data() + b.size()), y = x;
                one.solve(x);
                two.solve(y, &pool);
                CHECK(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0);
                if (repeat == 0 && precision == Precision::Double) {
                    const Eigen::Map<Eigen::VectorXd> solution(x.data(), b.size());
                    CHECK((p.dense * solution - b).cwiseAbs().maxCoeff() < 1e-10);
                }
            }
    }
}

TEST_CASE("supernodal Cholesky in single precision: a solution off by about the condition number "
          "times float's rounding, and doubles again after it",
          "[fast]") {
    using Precision = SupernodalCholesky::Precision;
    const Problem p = gridProblem(20, 25, 17);
    SupernodalCholesky cholesky;
    cholesky.analyse(p.nodes, p.pairs);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.dense.rows(), -1, 2);
    const Eigen::VectorXd exact = p.dense.llt().solve(b);
    const Eigen::VectorXd eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(p.dense, Eigen::EigenvaluesOnly)
            .eigenvalues();
    const double condition = eigenvalues.maxCoeff() / eigenvalues.minCoeff();
    auto relativeError = [&](Precision precision) {
        REQUIRE(cholesky.factorize(p.values, 0.0, nullptr, precision));
        std::vector<double> x(b.data(), b.data() + b.size());
        cholesky.solve(x);
        const Eigen::Map<Eigen::VectorXd> solution(x.data(), b.size());
        return (solution - exact).norm() / exact.norm();
    };
    const double single = relativeError(Precision::Single);
    const double twice = relativeError(Precision::Double);
    const double epsilon = std::numeric_limits<float>::epsilon();
    INFO("condition " << condition << ", single " << single << ", double " << twice);
    CHECK(single < condition * epsilon);
    CHECK(single > 1e-3 * epsilon); // the arithmetic was single: doubles are 1e9 times finer
    CHECK(twice < 1e-13);

    // Not positive definite in single precision either.
    Problem bad = gridProblem(10, 10, 3);
    SupernodalCholesky small;
    small.analyse(bad.nodes, bad.pairs);
    bad.values[9 * 50 + 4] = -1;
    CHECK_FALSE(small.factorize(bad.values, 0.0, nullptr, Precision::Single));
    CHECK(small.factorize(bad.values, 1e3, nullptr, Precision::Single));
}
