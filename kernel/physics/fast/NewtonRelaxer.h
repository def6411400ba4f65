#pragma once
// The "fast" relaxation backend: Newton's method on the total potential energy of the net,
//
//   E(x) = sum over bars of 1/2 k (l - l_eq)^2  -  sum over free knots of m_j g . x_j,
//
// whose gradient is minus the force of Eq. 3 (k = k_s when stretched, k_c otherwise; E is C1 and
// piecewise C2). Why Newton: at a rope's real stiffness (EA = 2e5 N against knots of a few grams)
// the explicit integration of the paper needs millions of force evaluations, because its step is
// bounded by the stiffest bar while the shape is set by the softest mode (the weight against the
// bars' geometric stiffness). Newton's step solves all modes at once; with a sparse Cholesky
// factorization each step costs a few force evaluations' worth of work per knot times the fill
// of a nested-dissection ordering (a 2D net: O(n^1.5) flops), and the number of steps does not
// grow with the stiffness.
//
// How:
// - Independent parts (physics/fast/Components.h: nets that share only rails) are relaxed each as
//   a system of its own, so each takes its own steps and an untouched part none (a part already
//   in equilibrium is not even analysed: the first relax after opening a relaxed sculpture and
//   editing one part orders and factorizes that part alone); several at a time when no part
//   dominates: as many as a given thread count, or with the automatic count every part at
//   once, each on a thread of its own; a part's pool runs each task on the part's fair share of
//   the machine's threads (its threads over the parts going on), so the last one left takes the
//   cores the others freed
//   (FastRelaxerParts.cpp, SharedCores in physics/ThreadPool.h; the same bits).
// - Near the end of a stage, once few knots are left out of balance (a free edge creeping while
//   the rest of its net is in equilibrium), they and a few rings of neighbours are relaxed as a
//   system of their own at the stage's stiffness, the rest held, and the whole goes on from there
//   (physics/fast/FocusRegion.h).
// - Unknowns are the free knots only (fixed knots are eliminated).
// - Hessian per bar: k u u^T + q (I - u u^T), u the bar's direction, q = the geometric stiffness
//   t / l >= 0. For a slack bar the negative geometric term is dropped (the positive
//   semidefinite projection), so the Newton matrix is never indefinite; a Levenberg shift mu I is
//   added when a factorization fails or a step does not pay off.
// - Globalization: backtracking (Armijo) line search on E, with energy differences computed bar
//   by bar in a form that keeps their relative accuracy near convergence.
// - Stiffness continuation: from a cold start (bars unstretched, such as the Eq. 2 geometry) the
//   net is first relaxed with every stiffness scaled down until strains are a few per cent
//   (large rotations are then cheap for Newton), then in stages 100 times stiffer each, up to
//   the material's. A taut net jumps straight from the soft stage to the material; the final
//   stage is a mixed (tension + position) Newton: its geometric stiffness uses the bars'
//   tensions carried over from the step before (the linearised elastic tension) instead of
//   k (l - l_eq) at the new positions, so a step that rotates a stiff bar is not punished for
//   the second-order stretch it would cause. If it stalls it falls back to the energy line
//   search. A warm start (most bars already taut) goes to the material's stiffness directly.
// - A start with a tension hint (RelaxOptions::startTensions: the tensions the start shape had
//   before an edit) first takes up to six mixed iterations seeded with it, in which a bar the
//   hint has taut keeps k_s when slack: the first is the edit's tangent predictor, and after a
//   small edit (a drag step) two or three reach the tolerance. Otherwise the run goes on as above,
//   warm whatever its residual when the bars carry their load and the hinted state was kept (an
//   edited equilibrium: a soft stage would throw away the equilibrium of every part the edit did
//   not touch); when it is not warm, its stages start one kStageFactor stiffer than a cold start's
//   soft stage unless a bar is stretched more than kEditStageMaxStrain (NewtonRun.h).
// - Slack nets (bars in compression at the first soft stage's equilibrium): the energy stages
//   after the first add a second, trust-region-driven Levenberg shift scaled by the knots'
//   weights per bar length (the soft modes of slack parts otherwise make the line search cut
//   every step), and the material's stiffness is reached first with k_c raised to k_s (no kink
//   at the rest length for the many bars near zero tension), then with the material's k_c.
// - Slack bars: each iteration first tries the exact Hessian (the negative geometric stiffness
//   of compressed bars included), which converges quadratically near a stable equilibrium with
//   slack parts, and uses the projected one when that is not positive definite.
// - Linear algebra: SupernodalCholesky (a geometric nested-dissection ordering of the free
//   knots at their positions when the analysis is made, METIS's when those do not separate the
//   net well; CHOLMOD's symbolic analysis; done once per topology and kept by the relaxer
//   between calls; own numeric factorization). The geometric ordering takes a fifth to a third
//   of METIS's time, and its factor costs 1-5% fewer flops on the benchmark's nets.
// - Wind is a position-dependent load without a potential (it turns with the bars). Each step
//   solves the Newton system with the wind's part of the Jacobian, which is not symmetric, by
//   GMRES with the Cholesky factor as its preconditioner (WindSteps.cpp), and the line search
//   measures the energy with the wind's load frozen where the step starts. Without that part a
//   free net in a wind of a fair part of its weight did not converge.
//
// Converged means what it means for every backend: the residual of Eq. 3 at the material's
// stiffness (physics/Forces.h residual(), max over free knots of |F_j| / (m_j |g|)) below the
// tolerance, computed on exactly the positions returned. A run stopped before converging
// (time, step limit, cancel) in its last stage returns that stage's lowest-residual state: its
// residual rises and falls from one iteration to the next while the energy goes down.
//
// Determinism: every pass that threads share writes per-bar or per-knot results and every sum
// runs in a fixed order on one thread, and the factorization is deterministic by construction,
// so a run gives the same bits whatever the number of threads and on every rerun. The ordering
// depends on the knots' positions when the analysis was made, so a run that reuses the analysis
// of an earlier call (same topology, other positions) may differ from a fresh relaxer's in the
// last bits (both converged to the tolerance); a fresh relaxer and a rerun of the same sequence
// of calls give the same bits.
//
// Options: tolerance, maxSeconds, maxSteps (a step = one Newton iteration, i.e. one
// factorization and solve, or with reuseFactor a few solves with the last run's factor),
// threads, cancel, progress, progressInterval, continuation (false: no soft stage),
// startTensions, reuseFactor (ReusedFactor.cpp), singlePrecisionSteps, focusAfterHint,
// hintBeforeCancel and wind are honoured; previewStiffnessScale and
// continuationFactor are RK4's and ignored (the soft stage's scale comes from the load, see
// kSoftLoadFactor).

#include "physics/Relaxer.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

namespace netsculpt {

class SharedCores;
struct NewtonAnalysis; // the topology-dependent part of a run (NewtonRelaxer.cpp)

/// What a FastRelaxer run did beyond RelaxResult, for tests and benchmarks.
struct NewtonStatistics {
    std::int64_t parts = 1;          ///< independent parts, each relaxed alone (Components.h)
    /// of them, the ones in equilibrium at the start: no step and no analysis (a part an edit of
    /// another did not touch)
    std::int64_t partsInEquilibrium = 0;
    /// parts relaxed at the same time, sharing the run's threads (1: one after the other)
    std::int64_t partsTogether = 1;
    /// regions of knots still out of balance relaxed on their own, the rest of their system held
    /// (FocusRegion.h; a region's own regions included)
    std::int64_t focusRegions = 0;
    /// of them, regions taken in a stage softer than the material's (FocusRegion.h,
    /// kSoftFocusShare)
    std::int64_t softFocusRegions = 0;
    /// of them, regions taken at once when the material's last stage stalled (FocusRegion.h)
    std::int64_t stallFocusRegions = 0;
    /// Newton iterations before the material's stiffness (0: none)
    std::int64_t softIterations = 0;
    /// iterations seeded with RelaxOptions::startTensions (0: none)
    std::int64_t hintIterations = 0;
    /// of them, steps solved with the factor of a previous run (RelaxOptions::reuseFactor)
    std::int64_t reusedFactorSteps = 0;
    std::int64_t iterations = 0;     ///< all Newton iterations (= RelaxResult::steps)
    std::int64_t factorizations = 0; ///< numeric factorizations, failed ones included
    std::int64_t failedFactorizations = 0; ///< not positive definite (then the shift grows)
    /// of them, in single precision (RelaxOptions::singlePrecisionSteps)
    std::int64_t singleFactorizations = 0;
    double softScale = 1;            ///< stiffness scale of the first soft stage (1 = none)
    /// the ordering and symbolic analysis came from a previous call
    bool reusedAnalysis = false;
    double analysisSeconds = 0;      ///< wall time of the analysis (0 when reused)
    double factorSeconds = 0;        ///< wall time in numeric factorizations
    double solveSeconds = 0;         ///< wall time in triangular solves
    double factorFlops = 0;          ///< per factorization (the mean over parts' ones)
    /// The ordering of the last analysis: "AMD", "METIS" or "geometric" (SupernodalCholesky).
    const char* ordering = "";
};

/// The Newton backend ("fast"). Keeps the symbolic analysis of the last system it relaxed and
/// reuses it when the next one has the same knots, fixed flags and bars (a warm start after a
/// drag or a material edit), so keep one instance per document. With the analysis it keeps a
/// run's storage (force field, vectors, the Newton matrix and the factor): a run on the same
/// topology updates the field's law in place and allocates nothing, and one on a new topology
/// reuses the storage that is large enough. Nothing of an earlier run's state carries over: a
/// run gives the bits a new relaxer with the same analysis would, unless it is asked to step
/// with the last run's factor (RelaxOptions::reuseFactor).
class FastRelaxer final : public Relaxer {
  public:
    FastRelaxer();
    ~FastRelaxer() override;
    FastRelaxer(const FastRelaxer&) = delete;
    FastRelaxer& operator=(const FastRelaxer&) = delete;

    std::string_view name() const override { return "fast"; }
    [[nodiscard]] RelaxResult relax(MassSpringSystem& system, const RelaxOptions& options) override;

    /// Of the last relax() call.
    const NewtonStatistics& statistics() const { return statistics_; }

    /// Whether a run near its end relaxes the knots still out of balance on their own
    /// (physics/fast/FocusRegion.h; on by default). Off, every iteration factorizes the whole
    /// system: the benchmark's comparison (netsculpt-bench-fast --no-focus) and the tests'.
    void setFocusRegions(bool on) { focusRegions_ = on; }

  private:
    using TimePoint = std::chrono::steady_clock::time_point;
    /// A system whose free knots are all connected: Newton's method as described above.
    RelaxResult relaxConnected(MassSpringSystem& system, const RelaxOptions& options,
                               TimePoint start);
    /// The knots `region` of `system` (physics/fast/FocusRegion.h) relaxed on their own by
    /// focus_, the others held, to kFocusTolerance times `tolerance` (the stage's; a region's own
    /// regions to the region's tolerance), with the stage's compression stiffness max(k_c,
    /// blend k_s) and stiffness `scale`; its steps counted from `stepsBefore`.
    RelaxResult relaxRegion(MassSpringSystem& system, const RelaxOptions& options, TimePoint start,
                            const std::vector<std::uint32_t>& region, double tolerance,
                            double blend, double scale, std::int64_t stepsBefore);
    /// A system of several independent parts (physics/fast/Components.h): each relaxed as a
    /// system of its own by a relaxer of its own (kept, so each part reuses its analysis), in
    /// turn or at the same time; the statistics summed in the order of the parts. Converged
    /// when every part is and the whole system's residual, on the positions returned, is below
    /// the tolerance.
    RelaxResult relaxParts(MassSpringSystem& system, const RelaxOptions& options,
                           const std::vector<std::vector<std::uint32_t>>& components,
                           TimePoint start);
    /// relaxParts' parts out of balance (`toRelax`, indices into `components`) one after the other,
    /// each with the run's threads ...
    void relaxPartsInTurn(MassSpringSystem& system, const RelaxOptions& options,
                          const std::vector<std::vector<std::uint32_t>>& components,
                          const std::vector<std::size_t>& toRelax, TimePoint start,
                          RelaxResult& result);
    /// ... or `workers` at a time, sharing the run's threads (SharedCores: each part on its fair
    /// share of them; the same bits: a part's result does not depend on its threads), the
    /// largest first; their results added in the parts' order.
    void relaxPartsTogether(MassSpringSystem& system, const RelaxOptions& options,
                            const std::vector<std::vector<std::uint32_t>>& components,
                            const std::vector<std::size_t>& toRelax, std::size_t workers,
                            TimePoint start, RelaxResult& result);

    std::unique_ptr<NewtonAnalysis> analysis_;
    NewtonStatistics statistics_;
    std::vector<std::unique_ptr<FastRelaxer>> parts_;
    std::unique_ptr<FastRelaxer> focus_; ///< relaxes focus regions (kept: its storage is reused)
    bool focusRegions_ = true;
    bool regionLevel_ = false; ///< this relaxer relaxes focus regions (its own: the same tolerance)
    /// Set while this relaxer relaxes one of several parts at the same time: its runs' pools
    /// share the machine's threads with the other parts'.
    const SharedCores* sharedCores_ = nullptr;
};

/// FastRelaxer().relax(system, options).
[[nodiscard]] RelaxResult relaxFast(MassSpringSystem& system, const RelaxOptions& options = {});

} // namespace netsculpt
