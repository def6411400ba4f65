#pragma once
// Sparse Cholesky factorization A = L L^T of a symmetric positive definite matrix made of 3x3
// blocks, one block row and column per node (a knot's three coordinates): the linear algebra of
// the Newton relaxer (NewtonRelaxer.h).
//
// The pattern is analysed once: nested-dissection ordering of the node graph (geometric when the
// nodes' positions are given, GeometricDissection.h; else METIS, through CHOLMOD), then CHOLMOD's
// supernodal symbolic factorization of the expanded scalar pattern. The numeric factorization is
// this file's own: a left-looking supernodal one whose dense kernels are Eigen's (the system BLAS
// that CHOLMOD would call is the slow reference one). Refactoring with new values reuses
// everything the analysis built.
//
// Determinism: every supernode pulls the updates of its descendants in a fixed order, whatever
// thread runs it and whenever, so the factor and the solutions are bit-identical for any number
// of threads. A large supernode near the top of the tree (where one supernode at a time is ready)
// is shared by the threads: its columns are split into fixed ranges (fixed by the analysis, not
// by the thread count), each range pulls every update in the same order, and the rows below the
// diagonal block are solved in fixed row ranges; every entry is computed by the same operations
// as without the split (the product and solve kernels are split only along their output, at
// boundaries of Eigen's register blocks), so the bits do not change. The same holds for a
// factorization in single precision (Precision), whose register blocks the ranges also respect.
// Eigen's blocks by cache size are fixed too (not the processor's), so one build gives the same
// bits on every processor.

#include "physics/fast/HugePageArray.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace netsculpt {

class ThreadPool;

class SupernodalCholesky {
  public:
    SupernodalCholesky() = default;

    /// How the last analysis ordered the nodes.
    enum class Ordering {
        Amd,       ///< approximate minimum degree (graphs of at most 2,000 nodes)
        Metis,     ///< METIS's nested dissection
        Geometric, ///< geometric nested dissection of the nodes' positions (GeometricDissection.h)
    };

    /// Analyses the pattern of a matrix of `nodes` x `nodes` blocks: the diagonal blocks and one
    /// block for each pair (i, j), i != j, of `pairs` (each unordered pair at most once).
    /// `coordinates` (empty, or one position per node, any unit) lets a large graph be ordered by
    /// geometric nested dissection instead of METIS; the ordering then depends on them too.
    void analyse(std::size_t nodes, std::span<const std::array<std::uint32_t, 2>> pairs,
                 std::span<const std::array<double, 3>> coordinates = {});

    bool analysed() const { return analysed_; }
    std::size_t nodes() const { return nodes_; }
    std::size_t pairs() const { return pairs_; }

    /// The arithmetic of a factorization and of the solves with it.
    enum class Precision {
        Double, ///< doubles throughout
        /// the factor stored and computed in floats (a factorization about 1.3 times as fast, a
        /// solve 1.6 times, in the same storage): a solution then has a relative error of about
        /// the matrix's condition number times 6e-8, enough for a Newton step towards a loose
        /// tolerance, not for the last steps to 1e-6 at the rope's stiffness
        Single,
    };

    /// Numeric factorization of the matrix whose values are `values`: first the nodes' diagonal
    /// blocks, then one block per pair in the order given to analyse(), each as 9 doubles, row
    /// major (the block of pair (i, j) has the rows of node i and the columns of node j; a
    /// diagonal block must be symmetric). `shift` (>= 0) is added to every diagonal entry.
    /// Returns false when the matrix is not numerically positive definite (a pivot <= 0 or not
    /// finite); the factor is then unusable until the next successful call.
    [[nodiscard]] bool factorize(std::span<const double> values, double shift,
                                 ThreadPool* pool = nullptr,
                                 Precision precision = Precision::Double);

    /// Solves A x = b in place for the last successful factorization, in its precision. b holds
    /// 3 * nodes() entries, node-major (x, y, z of node 0, then node 1, ...). With a pool,
    /// independent subtrees are solved on its threads (same bits); one solve at a time per
    /// object.
    void solve(std::span<double> b, ThreadPool* pool = nullptr) const;

    /// Size of the factor: stored entries of L (supernodal, some explicit zeros included).
    std::size_t factorEntries() const { return values_.size(); }
    /// Floating-point operations of one numeric factorization (CHOLMOD's count).
    double factorFlops() const { return flops_; }
    Ordering ordering() const { return ordering_; }
    /// How many supernodes the last analysis marked to be shared by the threads of a pool.
    std::size_t sharedSupernodes() const { return sharedSupernodes_; }

  private:
    static constexpr std::uint32_t kNone = UINT32_MAX; ///< no task / no parent
    std::int64_t superRows(std::size_t s) const { return rowStart_[s + 1] - rowStart_[s]; }
    std::int64_t superColumns(std::size_t s) const { return superStart_[s + 1] - superStart_[s]; }
    void placeInput(std::span<const std::array<std::uint32_t, 2>> pairs);
    void planSchedule(const std::vector<std::uint32_t>& parent);
    struct Update {
        std::uint32_t source; ///< a descendant supernode
        /// Its first row (index into its row list) inside the target's columns.
        std::uint32_t begin;
        std::uint32_t end; ///< one past its last such row
    };
    struct Worker {
        std::vector<std::int64_t> position; ///< scratch: row -> position in the current supernode
        std::vector<double> product;        ///< scratch: one update block
        std::vector<float> productSingle;   ///< the same for a single-precision factor
        std::vector<std::int64_t> place;    ///< scratch: an update's rows' positions in its target
    };

    struct Team;
    // The numeric kernels, for T = double or float (Precision).
    /// Fills, updates and factors supernode s; false when its pivots are not all > 0. With a
    /// team, a shared supernode's column and row ranges are handed to whichever threads join.
    template <class T>
    bool factorSupernode(std::size_t s, std::span<const double> values, double shift,
                         Worker& worker, Team* team = nullptr);
    /// Subtracts from supernode s's columns [columnBegin, columnEnd) (offsets in s) the updates
    /// of its descendants, in increasing descendant order. position: row -> position in s.
    template <class T>
    void applyUpdates(std::size_t s, std::int64_t columnBegin, std::int64_t columnEnd,
                      const std::int64_t* position, Worker& worker);
    template <class T> static T* alignedProduct(Worker& worker, std::int64_t n);
    template <class T> void runSchedule(std::span<const double> values, double shift,
                                        ThreadPool* pool);
    /// The factor's dense blocks as T (a single-precision factor uses the same storage).
    template <class T> T* factorValues() {
        if constexpr (std::is_same_v<T, double>)
            return values_.data();
        else
            return reinterpret_cast<float*>(values_.data());
    }
    template <class T> const T* factorValues() const {
        return const_cast<SupernodalCholesky*>(this)->factorValues<T>();
    }
    template <class T> void solveIn(std::span<double> b, ThreadPool* pool) const;

    bool analysed_ = false;
    std::size_t nodes_ = 0, pairs_ = 0, dimension_ = 0;
    double flops_ = 0;
    Ordering ordering_ = Ordering::Amd;

    // Supernodal structure (CHOLMOD's), rows and columns in pivot order.
    std::vector<std::int64_t> perm_;          ///< pivot k is original unknown perm_[k]
    /// Supernode s has columns [superStart_[s], superStart_[s+1]).
    std::vector<std::int64_t> superStart_;
    std::vector<std::int64_t> rowStart_;      ///< its rows: rows_[rowStart_[s] .. rowStart_[s+1])
    /// Its dense column-major block at values_[valueStart_[s]].
    std::vector<std::int64_t> valueStart_;
    std::vector<std::int64_t> rows_;
    std::vector<std::uint32_t> columnSuper_;  ///< column -> supernode
    /// updates_[updateStart_[s] .. updateStart_[s+1]) into s.
    std::vector<std::int64_t> updateStart_;
    std::vector<Update> updates_;
    // Filling a supernode from the input, block by block: supernode s takes the input blocks
    // fillBlock_[fillStart_[s] .. fillStart_[s+1]) (kTransposed set: it lands transposed), the
    // first entry of each at fillBase_[k] in its dense block.
    std::vector<std::int64_t> fillStart_;
    std::vector<std::uint32_t> fillBlock_;
    std::vector<std::uint32_t> fillBase_;
    std::vector<std::uint32_t> diagonalOffset_; ///< per column: its diagonal entry in its block

    // Schedule: tasks in a topological order; a task is one subtree (small ones, run as a whole)
    // or one supernode, ready when all the tasks it depends on are done.
    /// Task t runs supernodes taskSupers_[taskStart_[t] .. taskStart_[t+1]).
    std::vector<std::uint32_t> taskStart_;
    std::vector<std::uint32_t> taskSupers_;
    std::vector<std::uint32_t> taskParent_;  ///< the task waiting for t, or UINT32_MAX
    std::vector<std::uint32_t> taskWaits_;   ///< how many tasks t waits for
    // Shared supernodes: s's updates go by the column ranges between the boundaries
    // splitColumns_[splitStart_[s] .. splitStart_[s+1]) (offsets in s; none: s is not shared).
    std::vector<std::uint32_t> splitStart_;
    std::vector<std::uint32_t> splitColumns_;
    std::size_t sharedSupernodes_ = 0;

    /// The parallel solve: the products L21 y of the forward substitution, supernode s's at
    /// belowStart_[s] in the scratch (each pulled by the supernodes holding its rows).
    template <class T> void solveParallel(T* y, ThreadPool& pool) const;
    /// Supernode s's part of L y' = y on the permuted right-hand side y: its diagonal solve and
    /// its rows below times the result into scratch (maxRows_); returns the count of those rows.
    template <class T> std::int64_t solveForward(std::size_t s, T* y, T* scratch) const;
    /// Supernode s's part of L^T x = y' on the permuted right-hand side y (scratch: maxRows_).
    template <class T> void solveBackward(std::size_t s, T* y, T* scratch) const;
    template <class T> std::vector<T>& belowProducts() const;
    std::vector<std::int64_t> belowStart_;
    mutable std::vector<double> belowProducts_;
    mutable std::vector<float> belowProductsSingle_;

    HugePageArray values_; ///< the factor's dense blocks
    std::vector<Worker> workers_;
    std::size_t maxRows_ = 0;    ///< largest row count of a supernode
    bool failed_ = false;
    Precision precision_ = Precision::Double; ///< of the last factorization
};

} // namespace netsculpt
