// SupernodalCholesky's triangular solves with the factor: forward L y' = y, backward
// L^T x = y', one supernode at a time, in order or over the factorization's task tree with a
// pool (the same operations per entry in the same order, so the same bits).
#include "physics/fast/SupernodalCholesky.h"

#include "physics/ThreadPool.h"

#include "physics/EigenDense.h"

#include <algorithm>
#include <cassert>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace netsculpt {

namespace {

template <class T>
using ConstMatrixMap = Eigen::Map<const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>>;
template <class T> using Vector = Eigen::Matrix<T, Eigen::Dynamic, 1>;

} // namespace

void SupernodalCholesky::solve(std::span<double> b, ThreadPool* pool) const {
    assert(analysed_ && !failed_ && b.size() == dimension_);
    if (precision_ == Precision::Single)
        solveIn<float>(b, pool);
    else
        solveIn<double>(b, pool);
}

// The solve in the factor's precision T: the right-hand side permuted (and rounded to T), the
// two substitutions, the solution back in b.
template <class T> void SupernodalCholesky::solveIn(std::span<double> b, ThreadPool* pool) const {
    Vector<T> y(static_cast<Eigen::Index>(dimension_));
    for (std::size_t k = 0; k < dimension_; ++k)
        y[static_cast<Eigen::Index>(k)] = static_cast<T>(b[static_cast<std::size_t>(perm_[k])]);
    if (pool && pool->threadsNow() > 1 && taskStart_.size() > 2) {
        solveParallel<T>(y.data(), *pool);
    } else {
        const std::size_t supers = superStart_.size() - 1;
        Vector<T> scratch(static_cast<Eigen::Index>(maxRows_));
        // L y' = y
        for (std::size_t s = 0; s < supers; ++s) {
            const std::int64_t below = solveForward<T>(s, y.data(), scratch.data());
            const std::int64_t* rows =
                rows_.data() + rowStart_[s] + (superStart_[s + 1] - superStart_[s]);
            for (std::int64_t i = 0; i < below; ++i)
                y[rows[i]] -= scratch[i];
        }
        // L^T x = y'
        for (std::size_t s = supers; s-- > 0;)
            solveBackward<T>(s, y.data(), scratch.data());
    }
    for (std::size_t k = 0; k < dimension_; ++k)
        b[static_cast<std::size_t>(perm_[k])] = y[static_cast<Eigen::Index>(k)];
}

template <class T> std::vector<T>& SupernodalCholesky::belowProducts() const {
    if constexpr (std::is_same_v<T, double>)
        return belowProducts_;
    else
        return belowProductsSingle_;
}

// Supernode s's part of L y' = y, its descendants' products already taken from its entries of y:
// its diagonal block's triangle solved, and the product of its rows below with the result into
// scratch (one entry per row below, in their order). Returns how many rows are below. Column by
// column, each column of the block read once and contiguously: most supernodes are one to eight
// knots, and the per-call overheads of a library's triangular solve and matrix-vector product
// made the solve 1.3-1.4 times as slow.
template <class T>
std::int64_t SupernodalCholesky::solveForward(std::size_t s, T* yData, T* scratch) const {
    const std::int64_t cols = superStart_[s + 1] - superStart_[s];
    const std::int64_t rowCount = rowStart_[s + 1] - rowStart_[s];
    const std::int64_t below = rowCount - cols;
    ConstMatrixMap<T> l(factorValues<T>() + valueStart_[s], rowCount, cols);
    Eigen::Map<Vector<T>> part(yData + superStart_[s], cols), product(scratch, below);
    product.setZero();
    for (std::int64_t j = 0; j < cols; ++j) {
        const T value = part[j] / l(j, j);
        part[j] = value;
        part.tail(cols - j - 1) -= l.col(j).segment(j + 1, cols - j - 1) * value;
        product += l.col(j).tail(below) * value;
    }
    return below;
}

// Supernode s's part of L^T x = y': its entries of y minus its rows below times their (final)
// entries, its diagonal block's transposed triangle solved; column by column, the last first.
template <class T>
void SupernodalCholesky::solveBackward(std::size_t s, T* yData, T* scratch) const {
    const std::int64_t cols = superStart_[s + 1] - superStart_[s];
    const std::int64_t rowCount = rowStart_[s + 1] - rowStart_[s];
    const std::int64_t below = rowCount - cols;
    ConstMatrixMap<T> l(factorValues<T>() + valueStart_[s], rowCount, cols);
    Eigen::Map<Vector<T>> part(yData + superStart_[s], cols), t(scratch, below);
    const std::int64_t* rows = rows_.data() + rowStart_[s] + cols;
    for (std::int64_t i = 0; i < below; ++i)
        t[i] = yData[rows[i]];
    for (std::int64_t j = cols; j-- > 0;) {
        const T known = l.col(j).segment(j + 1, cols - j - 1).dot(part.tail(cols - j - 1)) +
                             l.col(j).tail(below).dot(t);
        part[j] = (part[j] - known) / l(j, j);
    }
}

// The same operations as solve() without a pool, per entry in the same order: the forward
// substitution pulls, into a supernode's entries, the products of the descendants whose rows are
// among its columns in increasing descendant order (the order in which the sequential solve
// pushes them there); the backward one reads only its ancestors' finished entries. Tasks run
// as in the factorization, forward children first, backward parents first.
template <class T>
void SupernodalCholesky::solveParallel(T* y, ThreadPool& pool) const {
    const std::size_t supers = superStart_.size() - 1;
    const std::size_t tasks = taskStart_.size() - 1;
    const auto threads = static_cast<std::size_t>(pool.threadsNow());
    std::vector<T>& products = belowProducts<T>();
    if (products.size() != static_cast<std::size_t>(belowStart_[supers]))
        products.resize(static_cast<std::size_t>(belowStart_[supers]));
    std::vector<Vector<T>> scratch(threads, Vector<T>(static_cast<Eigen::Index>(maxRows_)));

    auto forward = [&](std::size_t s, Vector<T>& t) {
        for (std::int64_t u = updateStart_[s]; u < updateStart_[s + 1]; ++u) {
            const Update& update = updates_[static_cast<std::size_t>(u)];
            const std::size_t d = update.source;
            const std::int64_t* sourceRows = rows_.data() + rowStart_[d];
            const T* product =
                products.data() + belowStart_[d] - (superStart_[d + 1] - superStart_[d]);
            for (std::uint32_t i = update.begin; i < update.end; ++i)
                y[sourceRows[i]] -= product[i];
        }
        const std::int64_t below = solveForward<T>(s, y, t.data());
        std::copy(t.data(), t.data() + below, products.data() + belowStart_[s]);
    };
    auto backward = [&](std::size_t s, Vector<T>& t) {
        solveBackward<T>(s, y, t.data());
    };

    // Backward, a task is ready when its parent task is done.
    std::vector<std::uint32_t> childStart(tasks + 1, 0), children(tasks);
    for (std::size_t t = 0; t < tasks; ++t)
        if (taskParent_[t] != kNone)
            ++childStart[taskParent_[t] + 1];
    for (std::size_t t = 0; t < tasks; ++t)
        childStart[t + 1] += childStart[t];
    {
        std::vector<std::uint32_t> next(childStart.begin(), childStart.end() - 1);
        for (std::size_t t = 0; t < tasks; ++t)
            if (taskParent_[t] != kNone)
                children[next[taskParent_[t]]++] = static_cast<std::uint32_t>(t);
    }

    for (const bool isForward : {true, false}) {
        std::vector<std::uint32_t> waits =
            isForward ? taskWaits_ : std::vector<std::uint32_t>(tasks, 0);
        std::vector<std::uint32_t> ready;
        for (std::size_t t = 0; t < tasks; ++t)
            if (isForward ? waits[t] == 0 : taskParent_[t] == kNone)
                ready.push_back(static_cast<std::uint32_t>(t));
        std::mutex mutex;
        std::size_t remaining = tasks;
        auto loop = [&](Vector<T>& t) {
            for (;;) {
                std::uint32_t task = kNone;
                {
                    std::lock_guard<std::mutex> lock(mutex);
                    if (remaining == 0)
                        return;
                    if (!ready.empty()) {
                        task = ready.back();
                        ready.pop_back();
                    }
                }
                if (task == kNone) {
                    std::this_thread::yield();
                    continue;
                }
                if (isForward)
                    for (std::uint32_t k = taskStart_[task]; k < taskStart_[task + 1]; ++k)
                        forward(taskSupers_[k], t);
                else
                    for (std::uint32_t k = taskStart_[task + 1]; k-- > taskStart_[task];)
                        backward(taskSupers_[k], t);
                std::lock_guard<std::mutex> lock(mutex);
                --remaining;
                if (isForward) {
                    const std::uint32_t up = taskParent_[task];
                    if (up != kNone && --waits[up] == 0)
                        ready.push_back(up);
                } else {
                    for (std::uint32_t c = childStart[task]; c < childStart[task + 1]; ++c)
                        ready.push_back(children[c]);
                }
            }
        };
        pool.parallelFor(threads, [&](std::size_t begin, std::size_t end, std::size_t) {
            for (std::size_t w = begin; w < end; ++w)
                loop(scratch[w]);
        });
    }
}

} // namespace netsculpt
