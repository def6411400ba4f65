#include "physics/fast/SupernodalCholesky.h"

#include "physics/ThreadPool.h"
#include "physics/fast/GeometricDissection.h"

#include "physics/EigenDense.h"
#include <cholmod.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <type_traits>

namespace netsculpt {

namespace {

template <class T> using Dense = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
template <class T> using MatrixMap = Eigen::Map<Dense<T>>;
template <class T> using ConstMatrixMap = Eigen::Map<const Dense<T>>;
template <class T> using StridedRef = Eigen::Ref<Dense<T>, 0, Eigen::OuterStride<>>;

// Marks a fill entry whose input block lands transposed in the factor.
constexpr std::uint32_t kTransposed = std::uint32_t(1) << 31;
// Above this many nodes the ordering is nested dissection (METIS), below it AMD.
constexpr std::size_t kMetisNodes = 2000;
// CHOLMOD's relaxed amalgamation, in nodes (3 columns each): supernodes of up to kRelaxNodes[0]
// nodes always merge; up to [1] and [2] while the share of explicit zeros stays under
// kRelaxZeros[0] and [1]; any while under [2].
constexpr std::size_t kRelaxNodes[3] = {1, 5, 16};
constexpr double kRelaxZeros[3] = {0.8, 0.1, 0.05};
// A shared supernode's rows below the diagonal block are solved in ranges of at least this many
// (see SupernodalSchedule.cpp for which supernodes are shared).
constexpr std::int64_t kSharedRows = 96;
// Eigen's register blocks for products of T: a GEMM computes each output column inside a group
// of kRegisterColumns (the last ones of a product one at a time) and each output row inside a
// group of kRegisterRows<T> (the last ones in smaller groups). Splitting a product or a triangular
// solve at multiples of these (from its first column or row) leaves every entry's operations
// as they are in the whole.
constexpr std::int64_t kRegisterColumns = Eigen::internal::gebp_traits<double, double>::nr;
static_assert(Eigen::internal::gebp_traits<float, float>::nr == kRegisterColumns,
              "the shared supernodes' column ranges serve both precisions");
template <class T>
constexpr std::int64_t kRegisterRows = Eigen::internal::gebp_traits<T, T>::mr;
// Eigen computes a product coefficient by coefficient (other operations) when its rows, columns
// and depth sum to less than this (EIGEN_GEMM_TO_COEFFBASED_THRESHOLD).
constexpr std::int64_t kCoefficientProduct = 20;
static_assert(kSharedRows % kRegisterRows<double> == 0 && kSharedRows % kRegisterRows<float> == 0,
              "row ranges must start at register blocks");

// Eigen blocks its products and triangular solves by the cache sizes it reads from the
// processor, and the blocks set the order of each entry's sums: one build took other steps on two
// processors of this machine kind (48 KiB L1 data and 1 MiB L2 against 32 KiB and 512 KiB; the
// slack 100x200 sheet 230 against 191 iterations, docs/performance.md). Fixed sizes make a
// build's factorizations the same bits on every processor; these are the AVX2 hosts'.
constexpr std::ptrdiff_t kBlockingL1 = std::ptrdiff_t(32) << 10;
constexpr std::ptrdiff_t kBlockingL2 = std::ptrdiff_t(512) << 10;
constexpr std::ptrdiff_t kBlockingL3 = std::ptrdiff_t(16) << 20;

/// Eigen's cache sizes set to the fixed ones when the processor (or anyone since) left others.
/// Under a lock: the first factorizations of parts relaxed at once may come here together, and
/// the write then happens before any of them runs a product; after it, the sizes are only read.
void fixProductBlocking() {
    static std::mutex mutex;
    const std::lock_guard<std::mutex> lock(mutex);
    if (Eigen::l1CacheSize() != kBlockingL1 || Eigen::l2CacheSize() != kBlockingL2 ||
        Eigen::l3CacheSize() != kBlockingL3)
        Eigen::setCpuCacheSizes(kBlockingL1, kBlockingL2, kBlockingL3);
}

/// CHOLMOD's workspace for the duration of an analysis.
class CholmodCommon {
  public:
    CholmodCommon() {
        cholmod_l_start(&common_);
        common_.print = 0;
        common_.error_handler = nullptr;
    }
    ~CholmodCommon() { cholmod_l_finish(&common_); }
    CholmodCommon(const CholmodCommon&) = delete;
    CholmodCommon& operator=(const CholmodCommon&) = delete;
    cholmod_common* get() { return &common_; }

  private:
    cholmod_common common_;
};

[[noreturn]] void cholmodFailed(const char* what, const cholmod_common* common) {
    std::string message = "sparse Cholesky analysis: ";
    message += what;
    message += " failed (CHOLMOD status ";
    message += std::to_string(common->status);
    message += ")";
    throw std::runtime_error(message);
}

} // namespace

/// The threads of one factorization's schedule, for sharing a supernode: its owner publishes
/// a job (a count of ranges and what to do with one), any idle thread joins and claims ranges,
/// and the owner returns when all are done. One job at a time; an owner that finds the slot
/// taken runs its ranges alone. Who runs a range never changes what it computes.
struct SupernodalCholesky::Team {
    using Body = std::function<void(std::size_t, Worker&)>;
    std::mutex& mutex; ///< the schedule's; guards body and count
    const Body* body = nullptr;
    std::size_t count = 0;
    std::atomic<std::size_t> next{0}, done{0};
    std::atomic<int> active{0}; ///< threads that joined the current job and may still claim

    explicit Team(std::mutex& m) : mutex(m) {}

    void claim(const Body& job, std::size_t jobCount, Worker& worker) {
        for (;;) {
            const std::size_t range = next.fetch_add(1, std::memory_order_relaxed);
            if (range >= jobCount)
                return;
            job(range, worker);
            done.fetch_add(1, std::memory_order_release);
        }
    }

    void run(std::size_t jobCount, const Body& job, Worker& worker) {
        {
            std::lock_guard<std::mutex> lock(mutex);
            if (!body) {
                body = &job;
                count = jobCount;
                next.store(0, std::memory_order_relaxed);
                done.store(0, std::memory_order_relaxed);
            } else {
                for (std::size_t range = 0; range < jobCount; ++range)
                    job(range, worker);
                return;
            }
        }
        claim(job, jobCount, worker);
        while (done.load(std::memory_order_acquire) < jobCount)
            std::this_thread::yield();
        {
            std::lock_guard<std::mutex> lock(mutex);
            body = nullptr;
        }
        while (active.load(std::memory_order_acquire) > 0)
            std::this_thread::yield();
    }

    /// Called with the mutex held: joins the current job, if any (then call help() unlocked).
    const Body* join(std::size_t& jobCount) {
        if (body) {
            active.fetch_add(1, std::memory_order_relaxed);
            jobCount = count;
        }
        return body;
    }
    void help(const Body& job, std::size_t jobCount, Worker& worker) {
        claim(job, jobCount, worker);
        active.fetch_sub(1, std::memory_order_release);
    }
};

void SupernodalCholesky::analyse(std::size_t nodes,
                                 std::span<const std::array<std::uint32_t, 2>> pairs,
                                 std::span<const std::array<double, 3>> coordinates) {
    analysed_ = false;
    nodes_ = nodes;
    pairs_ = pairs.size();
    dimension_ = 3 * nodes;

    // The node graph, both directions, each list sorted.
    std::vector<std::int64_t> adjacencyStart(nodes + 1, 0);
    for (const auto& [i, j] : pairs) {
        assert(i < nodes && j < nodes && i != j);
        ++adjacencyStart[i + 1];
        ++adjacencyStart[j + 1];
    }
    for (std::size_t k = 0; k < nodes; ++k)
        adjacencyStart[k + 1] += adjacencyStart[k];
    std::vector<std::uint32_t> adjacency(static_cast<std::size_t>(adjacencyStart[nodes]));
    {
        std::vector<std::int64_t> next(adjacencyStart.begin(), adjacencyStart.end() - 1);
        for (const auto& [i, j] : pairs) {
            adjacency[static_cast<std::size_t>(next[i]++)] = j;
            adjacency[static_cast<std::size_t>(next[j]++)] = i;
        }
    }
    for (std::size_t k = 0; k < nodes; ++k)
        std::sort(adjacency.begin() + adjacencyStart[k], adjacency.begin() + adjacencyStart[k + 1]);

    // The node pattern (upper triangle), ordered and analysed by CHOLMOD: nested dissection for
    // large graphs (geometric when positions are given and separate the graph well, else
    // METIS), AMD for small ones (as good there, and METIS's start-up would dominate),
    // postordered, supernodal. The scalar structure is that of the nodes with every node
    // expanded to its three coordinates.
    std::vector<std::int64_t> start(nodes + 1, 0), index;
    index.reserve(nodes + pairs.size());
    for (std::size_t j = 0; j < nodes; ++j) {
        for (std::int64_t e = adjacencyStart[j]; e < adjacencyStart[j + 1]; ++e)
            if (adjacency[static_cast<std::size_t>(e)] < j)
                index.push_back(adjacency[static_cast<std::size_t>(e)]);
        index.push_back(static_cast<std::int64_t>(j));
        start[j + 1] = static_cast<std::int64_t>(index.size());
    }
    std::vector<std::int64_t> given;
    ordering_ = nodes > kMetisNodes ? Ordering::Metis : Ordering::Amd;
    if (nodes > kMetisNodes && !coordinates.empty()) {
        assert(coordinates.size() == nodes);
        const std::vector<std::uint32_t> order =
            geometricNestedDissection(GeometricGraph{adjacencyStart, adjacency, coordinates});
        if (!order.empty()) {
            given.assign(order.begin(), order.end());
            ordering_ = Ordering::Geometric;
        }
    }
    CholmodCommon common;
    cholmod_common* c = common.get();
    cholmod_sparse pattern{};
    pattern.nrow = pattern.ncol = nodes;
    pattern.nzmax = index.size();
    pattern.p = start.data();
    pattern.i = index.data();
    pattern.stype = 1;
    pattern.itype = CHOLMOD_LONG;
    pattern.xtype = CHOLMOD_PATTERN;
    pattern.dtype = CHOLMOD_DOUBLE;
    pattern.sorted = 1;
    pattern.packed = 1;
    c->nmethods = 1;
    c->method[0].ordering = ordering_ == Ordering::Geometric ? CHOLMOD_GIVEN
                            : ordering_ == Ordering::Metis   ? CHOLMOD_METIS
                                                             : CHOLMOD_AMD;
    c->postorder = 1;
    c->supernodal = CHOLMOD_SUPERNODAL;
    for (int k = 0; k < 3; ++k) {
        c->nrelax[k] = kRelaxNodes[k];
        c->zrelax[k] = kRelaxZeros[k];
    }
    cholmod_factor* factor = nullptr;
    if (nodes > 0) {
        factor = given.empty() ? cholmod_l_analyze(&pattern, c)
                               : cholmod_l_analyze_p(&pattern, given.data(), nullptr, 0, c);
        if (!factor)
            cholmodFailed("ordering and supernodal symbolic factorization", c);
        if (!factor->is_super)
            cholmodFailed("supernodal symbolic factorization", c);
    }
    struct FreeFactor {
        cholmod_common* common;
        void operator()(cholmod_factor* f) const { cholmod_l_free_factor(&f, common); }
    };
    std::unique_ptr<cholmod_factor, FreeFactor> owner(factor, FreeFactor{c});

    const std::size_t supers = factor ? factor->nsuper : 0;
    perm_.resize(dimension_);
    superStart_.assign(supers + 1, 0);
    rowStart_.assign(supers + 1, 0);
    valueStart_.assign(supers + 1, 0);
    rows_.clear();
    if (factor) {
        const auto* perm = static_cast<const std::int64_t*>(factor->Perm);
        const auto* super = static_cast<const std::int64_t*>(factor->super);
        const auto* pi = static_cast<const std::int64_t*>(factor->pi);
        const auto* s = static_cast<const std::int64_t*>(factor->s);
        for (std::size_t k = 0; k < nodes; ++k)
            for (int a = 0; a < 3; ++a)
                perm_[3 * k + a] = 3 * perm[k] + a;
        rows_.reserve(3 * static_cast<std::size_t>(pi[supers]));
        for (std::size_t k = 0; k < supers; ++k) {
            superStart_[k + 1] = 3 * super[k + 1];
            for (std::int64_t r = pi[k]; r < pi[k + 1]; ++r)
                for (int a = 0; a < 3; ++a)
                    rows_.push_back(3 * s[r] + a);
            rowStart_[k + 1] = static_cast<std::int64_t>(rows_.size());
            valueStart_[k + 1] =
                valueStart_[k] + 9 * (pi[k + 1] - pi[k]) * (super[k + 1] - super[k]);
        }
    }
    owner.reset();

    columnSuper_.assign(dimension_, 0);
    maxRows_ = 0;
    for (std::size_t s = 0; s < supers; ++s) {
        const std::int64_t rowCount = rowStart_[s + 1] - rowStart_[s];
        maxRows_ = std::max(maxRows_, static_cast<std::size_t>(rowCount));
        for (std::int64_t k = superStart_[s]; k < superStart_[s + 1]; ++k)
            columnSuper_[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(s);
    }
    flops_ = 0; // as CHOLMOD counts: the square of each column's entry count
    for (std::size_t s = 0; s < supers; ++s)
        for (std::int64_t k = 0; k < superColumns(s); ++k)
            flops_ += static_cast<double>(superRows(s) - k) * static_cast<double>(superRows(s) - k);

    // Updates: the rows of supernode d below its own columns, in runs by target supernode.
    std::vector<std::int64_t> updateCount(supers + 1, 0);
    std::vector<std::uint32_t> parent(supers, kNone);
    auto forEachRun = [&](std::size_t d, auto&& visit) {
        const std::int64_t first = rowStart_[d], cols = superColumns(d), count = superRows(d);
        for (std::int64_t i = cols; i < count;) {
            const std::uint32_t target = columnSuper_[static_cast<std::size_t>(rows_[first + i])];
            std::int64_t e = i + 1;
            while (e < count && columnSuper_[static_cast<std::size_t>(rows_[first + e])] == target)
                ++e;
            visit(target, i, e);
            i = e;
        }
    };
    for (std::size_t d = 0; d < supers; ++d) {
        forEachRun(d, [&](std::uint32_t target, std::int64_t, std::int64_t) {
            ++updateCount[target + 1];
        });
        if (superRows(d) > superColumns(d))
            parent[d] =
                columnSuper_[static_cast<std::size_t>(rows_[rowStart_[d] + superColumns(d)])];
    }
    updateStart_.assign(supers + 1, 0);
    for (std::size_t s = 0; s < supers; ++s)
        updateStart_[s + 1] = updateStart_[s] + updateCount[s + 1];
    updates_.resize(static_cast<std::size_t>(updateStart_[supers]));
    {
        std::vector<std::int64_t> next(updateStart_.begin(), updateStart_.end() - 1);
        for (std::size_t d = 0; d < supers; ++d)
            forEachRun(d, [&](std::uint32_t target, std::int64_t b, std::int64_t e) {
                updates_[static_cast<std::size_t>(next[target]++)] =
                    Update{static_cast<std::uint32_t>(d), static_cast<std::uint32_t>(b),
                           static_cast<std::uint32_t>(e)};
            });
    }

    placeInput(pairs);
    planSchedule(parent);

    belowStart_.assign(supers + 1, 0);
    for (std::size_t s = 0; s < supers; ++s)
        belowStart_[s + 1] = belowStart_[s] + superRows(s) - superColumns(s);

    // Every block is zeroed and filled by its factorization before anything reads it.
    values_.allocate(static_cast<std::size_t>(valueStart_[supers]));
    workers_.clear();
    analysed_ = true;
}

// Where each input block goes, placed block by block (a node's three unknowns are consecutive
// pivots, columns of one supernode and consecutive rows of every supernode that holds them):
// the offset in its target supernode's dense block of the block's first entry, and whether it
// lands transposed (its node of rows is pivoted before its node of columns).
void SupernodalCholesky::placeInput(std::span<const std::array<std::uint32_t, 2>> pairs) {
    const std::size_t nodes = nodes_;
    const std::size_t supers = superStart_.size() - 1;
    std::vector<std::int64_t> nodePivot(nodes);
    for (std::size_t k = 0; k < nodes; ++k)
        nodePivot[static_cast<std::size_t>(perm_[3 * k] / 3)] = static_cast<std::int64_t>(k);
    const std::size_t blockCount = nodes + pairs_;
    std::vector<std::uint32_t> blockTarget(blockCount);
    std::vector<std::uint32_t> blockBase(blockCount);
    auto base = [&](std::int64_t rowPivot, std::int64_t colPivot) {
        const std::int64_t row = 3 * rowPivot, col = 3 * colPivot;
        const std::uint32_t s = columnSuper_[static_cast<std::size_t>(col)];
        const auto* begin = rows_.data() + rowStart_[s];
        const auto* end = rows_.data() + rowStart_[s + 1];
        const auto* at = std::lower_bound(begin, end, row);
        assert(at + 2 < end && *at == row);
        const std::int64_t offset = (col - superStart_[s]) * superRows(s) + (at - begin);
        if (offset + 2 * superRows(s) + 2 > std::numeric_limits<std::uint32_t>::max())
            throw std::runtime_error("sparse Cholesky analysis: a supernode is too large");
        return std::pair{s, static_cast<std::uint32_t>(offset)};
    };
    for (std::size_t node = 0; node < nodes; ++node) {
        const std::int64_t k = nodePivot[node];
        std::tie(blockTarget[node], blockBase[node]) = base(k, k);
    }
    for (std::size_t p = 0; p < pairs_; ++p) {
        const std::int64_t i = nodePivot[pairs[p][0]], j = nodePivot[pairs[p][1]];
        std::tie(blockTarget[nodes + p], blockBase[nodes + p]) = i > j ? base(i, j) : base(j, i);
        if (i < j)
            blockTarget[nodes + p] |= kTransposed;
    }
    fillStart_.assign(supers + 1, 0);
    for (std::uint32_t target : blockTarget)
        ++fillStart_[(target & ~kTransposed) + 1];
    for (std::size_t s = 0; s < supers; ++s)
        fillStart_[s + 1] += fillStart_[s];
    fillBlock_.resize(blockCount);
    fillBase_.resize(blockCount);
    {
        std::vector<std::int64_t> next(fillStart_.begin(), fillStart_.end() - 1);
        for (std::size_t v = 0; v < blockCount; ++v) {
            const std::uint32_t target = blockTarget[v] & ~kTransposed;
            const auto k = static_cast<std::size_t>(next[target]++);
            fillBlock_[k] = static_cast<std::uint32_t>(v) | (blockTarget[v] & kTransposed);
            fillBase_[k] = blockBase[v];
        }
    }
    diagonalOffset_.resize(dimension_);
    for (std::size_t s = 0; s < supers; ++s)
        for (std::int64_t k = 0; k < superColumns(s); ++k)
            diagonalOffset_[static_cast<std::size_t>(superStart_[s] + k)] =
                static_cast<std::uint32_t>(k * superRows(s) + k);
}

/// The worker's product scratch for n doubles, at a 64-byte boundary. Eigen computes a small
/// product coefficient by coefficient, with vector lanes from the first aligned entry on and
/// scalar code before it; the two differ in their last bits where the compiler does not
/// contract the scalar code's multiply-adds (unoptimized builds), so an address that moved
/// with the heap's state made a factor's bits depend on what ran before.
template <class T> T* SupernodalCholesky::alignedProduct(Worker& worker, std::int64_t n) {
    constexpr std::size_t kAlign = 64 / sizeof(T);
    std::vector<T>& product = [&]() -> std::vector<T>& {
        if constexpr (std::is_same_v<T, double>)
            return worker.product;
        else
            return worker.productSingle;
    }();
    if (product.size() < static_cast<std::size_t>(n) + kAlign)
        product.resize(static_cast<std::size_t>(n) + kAlign);
    const auto address = reinterpret_cast<std::uintptr_t>(product.data());
    return product.data() + (kAlign - address / sizeof(T) % kAlign) % kAlign;
}

template <class T>
void SupernodalCholesky::applyUpdates(std::size_t s, std::int64_t columnBegin,
                                      std::int64_t columnEnd, const std::int64_t* position,
                                      Worker& worker) {
    const std::int64_t cols = superStart_[s + 1] - superStart_[s];
    const std::int64_t rowCount = rowStart_[s + 1] - rowStart_[s];
    T* block = factorValues<T>() + valueStart_[s];
    // Left-looking: subtract L_d[rows from begin on] * L_d[begin, end)^T for every descendant d
    // with rows among this supernode's columns, in increasing d (the fixed order of the sum).
    // A range of the columns takes from each update the product's columns that land in it.
    for (std::int64_t u = updateStart_[s]; u < updateStart_[s + 1]; ++u) {
        const Update& update = updates_[static_cast<std::size_t>(u)];
        const std::size_t d = update.source;
        const std::int64_t sourceRows = rowStart_[d + 1] - rowStart_[d];
        const std::int64_t sourceCols = superStart_[d + 1] - superStart_[d];
        ConstMatrixMap<T> source(factorValues<T>() + valueStart_[d], sourceRows, sourceCols);
        const std::int64_t m = sourceRows - update.begin, k = update.end - update.begin;
        const std::int64_t* sourceRowIndex = rows_.data() + rowStart_[d] + update.begin;
        std::int64_t j0 = 0, j1 = k; // the product's columns that land in the range
        if (columnBegin > 0 || columnEnd < cols) {
            j0 =
                std::lower_bound(sourceRowIndex, sourceRowIndex + k, superStart_[s] + columnBegin) -
                sourceRowIndex;
            j1 = std::lower_bound(sourceRowIndex + j0, sourceRowIndex + k,
                                  superStart_[s] + columnEnd) -
                 sourceRowIndex;
            if (j0 == j1)
                continue;
        }
        // The product's columns [a, b) that are computed: all, or those asked for widened to
        // whole register blocks, at least 2 (Eigen computes a one-column product as a GEMV), and
        // all again where Eigen would compute the part coefficient by coefficient.
        std::int64_t a = 0, b = k;
        if (j0 > 0 || j1 < k) {
            a = j0 - j0 % kRegisterColumns;
            b = std::min(k, (j1 + kRegisterColumns - 1) / kRegisterColumns * kRegisterColumns);
            if (b - a < 2)
                a = std::max<std::int64_t>(0, a - kRegisterColumns);
            if (m + k + sourceCols < kCoefficientProduct ||
                m + (b - a) + sourceCols < kCoefficientProduct) {
                a = 0;
                b = k;
            }
        }
        MatrixMap<T> product(alignedProduct<T>(worker, m * (b - a)), m, b - a);
        product.noalias() = source.middleRows(update.begin, m) *
                            source.middleRows(update.begin + a, b - a).transpose();
        // Each entry of the product is subtracted from its place in the block once, in the same
        // order whichever way: the places are looked up once per update, and where they are
        // consecutive (the usual case: a descendant's rows are runs of whole nodes) a column's
        // subtraction is one contiguous pass.
        if (worker.place.size() < static_cast<std::size_t>(m))
            worker.place.resize(static_cast<std::size_t>(m));
        std::int64_t* place = worker.place.data();
        for (std::int64_t ii = 0; ii < m; ++ii)
            place[ii] = position[static_cast<std::size_t>(sourceRowIndex[ii])];
        const bool consecutive = place[m - 1] - place[0] == m - 1;
        for (std::int64_t jj = j0; jj < j1; ++jj) {
            T* column = block + (sourceRowIndex[jj] - superStart_[s]) * rowCount;
            const T* p = product.data() + (jj - a) * m;
            if (consecutive) {
                T* to = column + place[0];
                for (std::int64_t ii = jj; ii < m; ++ii)
                    to[ii] -= p[ii];
            } else {
                for (std::int64_t ii = jj; ii < m; ++ii)
                    column[place[ii]] -= p[ii];
            }
        }
    }
}

template <class T>
bool SupernodalCholesky::factorSupernode(std::size_t s, std::span<const double> values,
                                         double shift, Worker& worker, Team* team) {
    const std::int64_t cols = superStart_[s + 1] - superStart_[s];
    const std::int64_t rowCount = rowStart_[s + 1] - rowStart_[s];
    T* block = factorValues<T>() + valueStart_[s];
    MatrixMap<T> l(block, rowCount, cols);
    l.setZero();
    // The input blocks: a diagonal one's lower triangle, a pair's nine entries, each entry (a, b)
    // at row a, column b of the block (b, a when transposed).
    for (std::int64_t k = fillStart_[s]; k < fillStart_[s + 1]; ++k) {
        const std::uint32_t entry = fillBlock_[static_cast<std::size_t>(k)];
        const std::size_t source = entry & ~kTransposed;
        const double* v = values.data() + 9 * source;
        T* to = block + fillBase_[static_cast<std::size_t>(k)];
        if (source < nodes_) {
            for (int b = 0; b < 3; ++b)
                for (int a = b; a < 3; ++a)
                    to[b * rowCount + a] = static_cast<T>(v[3 * a + b]);
        } else if (entry & kTransposed) {
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    to[a * rowCount + b] = static_cast<T>(v[3 * a + b]);
        } else {
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    to[b * rowCount + a] = static_cast<T>(v[3 * a + b]);
        }
    }
    for (std::int64_t k = 0; k < cols; ++k)
        block[diagonalOffset_[static_cast<std::size_t>(superStart_[s] + k)]] +=
            static_cast<T>(shift);

    const std::int64_t* rows = rows_.data() + rowStart_[s];
    for (std::int64_t i = 0; i < rowCount; ++i)
        worker.position[static_cast<std::size_t>(rows[i])] = i;

    const std::uint32_t* split = splitColumns_.data() + splitStart_[s];
    const std::size_t boundaries = splitStart_[s + 1] - splitStart_[s];
    const bool shared = team && boundaries > 1;
    if (!shared) {
        applyUpdates<T>(s, 0, cols, worker.position.data(), worker);
    } else {
        const std::int64_t* position = worker.position.data();
        const Team::Body job = [&](std::size_t r, Worker& w) {
            applyUpdates<T>(s, split[r], split[r + 1], position, w);
        };
        team->run(boundaries - 1, job, worker);
    }

    StridedRef<T> diagonal = l.topRows(cols);
    Eigen::LLT<StridedRef<T>> llt(diagonal); // in place: the lower triangle becomes L_ss
    bool ok = llt.info() == Eigen::Success;
    for (std::int64_t k = 0; ok && k < cols; ++k)
        ok = std::isfinite(diagonal(k, k)) && diagonal(k, k) > 0;
    if (!ok)
        return false;
    const std::int64_t below = rowCount - cols;
    if (below == 0)
        return true;
    // L21 = A21 L11^-T, row by row; a shared supernode's rows in ranges of whole register blocks.
    const std::int64_t rangeRows =
        shared ? std::max(kSharedRows,
                          (below + 3 * kRegisterRows<T> - 1) / (3 * kRegisterRows<T>) *
                              kRegisterRows<T>)
               : below;
    const auto solveRows = [&](std::size_t r, Worker&) {
        const std::int64_t first = static_cast<std::int64_t>(r) * rangeRows;
        const std::int64_t count = std::min(rangeRows, below - first);
        diagonal.transpose().template triangularView<Eigen::Upper>().template solveInPlace<
            Eigen::OnTheRight>(
            l.middleRows(cols + first, count));
    };
    const auto rowRanges = static_cast<std::size_t>((below + rangeRows - 1) / rangeRows);
    if (rowRanges > 1)
        team->run(rowRanges, solveRows, worker);
    else
        solveRows(0, worker);
    return true;
}

template <class T>
void SupernodalCholesky::runSchedule(std::span<const double> values, double shift,
                                     ThreadPool* pool) {
    const std::size_t threads = pool ? static_cast<std::size_t>(pool->threadsNow()) : 1;
    if (workers_.size() != threads) {
        workers_.assign(threads, Worker{});
        for (Worker& w : workers_)
            w.position.assign(dimension_, 0);
    }
    const std::size_t supers = superStart_.size() - 1;
    if (threads == 1 || taskStart_.size() <= 2) {
        for (std::size_t s = 0; s < supers && !failed_; ++s)
            failed_ = !factorSupernode<T>(s, values, shift, workers_[0]);
        return;
    }

    // Tasks become ready when every task below them is done; any thread may run any ready one.
    const std::size_t tasks = taskStart_.size() - 1;
    std::vector<std::uint32_t> waits = taskWaits_;
    std::vector<std::uint32_t> ready;
    for (std::size_t t = 0; t < tasks; ++t)
        if (waits[t] == 0)
            ready.push_back(static_cast<std::uint32_t>(t));
    std::mutex mutex;
    Team team(mutex);
    std::size_t remaining = tasks;
    std::atomic<bool> failed{false};
    auto loop = [&](Worker& worker) {
        for (;;) {
            std::uint32_t task = kNone;
            const Team::Body* job = nullptr;
            std::size_t jobCount = 0;
            {
                std::lock_guard<std::mutex> lock(mutex);
                if (remaining == 0 || failed.load(std::memory_order_relaxed))
                    return;
                if (!ready.empty()) {
                    task = ready.back();
                    ready.pop_back();
                } else {
                    job = team.join(jobCount);
                }
            }
            if (job) {
                team.help(*job, jobCount, worker);
                continue;
            }
            if (task == kNone) {
                std::this_thread::yield();
                continue;
            }
            for (std::uint32_t k = taskStart_[task]; k < taskStart_[task + 1]; ++k)
                if (!factorSupernode<T>(taskSupers_[k], values, shift, worker, &team)) {
                    failed.store(true, std::memory_order_relaxed);
                    break;
                }
            std::lock_guard<std::mutex> lock(mutex);
            --remaining;
            const std::uint32_t up = taskParent_[task];
            if (up != kNone && --waits[up] == 0)
                ready.push_back(up);
        }
    };
    pool->parallelFor(threads, [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t w = begin; w < end; ++w)
            loop(workers_[w]);
    });
    if (failed.load())
        failed_ = true;
}

bool SupernodalCholesky::factorize(std::span<const double> values, double shift, ThreadPool* pool,
                                   Precision precision) {
    assert(analysed_ && values.size() == 9 * (nodes_ + pairs_) && shift >= 0);
    failed_ = false;
    precision_ = precision;
    fixProductBlocking();
    if (precision == Precision::Single)
        runSchedule<float>(values, shift, pool);
    else
        runSchedule<double>(values, shift, pool);
    return !failed_;
}

} // namespace netsculpt
