#pragma once
// Relaxation: moving the free knots of a mass-spring system until the force of Eq. 3 vanishes
// (DESIGN.md "Physics"). The options, progress and result are shared by every backend; the
// default backend integrates the paper's overdamped motion dx/dt = M^-1 F (Eq. 7) with
// classical RK4 and stiffness continuation.

#include "physics/MassSpringSystem.h"
#include "physics/Wind.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace netsculpt {

/// A snapshot of a running relaxation, handed to RelaxOptions::progress.
struct RelaxProgress {
    /// max |F_j| / (m_j |g|) over free knots at the current stiffness scale.
    double residual = 0;
    std::int64_t steps = 0;           ///< integration steps taken so far (rejected ones included)
    double seconds = 0;               ///< wall time since the start, s
    double estimatedSecondsLeft = -1; ///< s until the tolerance at full stiffness; < 0 = unknown
    double stiffnessScale = 1; ///< the continuation stage's scale s in (0, 1]; 1 = the material
    /// The knots' positions at this moment (valid during the call only; empty when the backend
    /// does not expose them). What a live view shows while one run goes on.
    std::span<const Vec3> positions;
};

/// The loosest tolerance a document's relaxation takes (Document::relax, the CLI, Lua): knots
/// out of balance by up to 1 % of their weight. Looser, a "converged" shape's rail reactions can
/// miss the weight by tens of per cent (a tube relaxed to 2 put 16.8 N on its ring for 11.9 N of
/// net) while the shape counts as relaxed. A solver's own stages may be looser.
inline constexpr double kMaxTolerance = 1e-2;

struct RelaxOptions {
    /// Converged when the residual at full stiffness is below it; finite, > 0 (a document's
    /// relaxation: at most kMaxTolerance).
    double tolerance = 1e-6;
    double maxSeconds = 60;     ///< wall-time limit, s; finite, > 0 (infinity is refused)
    std::int64_t maxSteps = -1; ///< limit on integration steps; -1 = none, else >= 0
    /// Threads of the force evaluation: 0 = automatic (the hardware's, but one for systems too
    /// small to gain from more), n >= 1 = exactly n. Results do not depend on it, bit for bit.
    int threads = 0;
    /// Polled once per step; when it reads true the run stops with stopReason "cancelled" and
    /// the last state reached. Null = not cancellable. Must outlive the call.
    const std::atomic<bool>* cancel = nullptr;
    /// Called on the calling thread about every progressInterval seconds, and once at the end.
    /// Empty = none. It must not touch the system being relaxed.
    std::function<void(const RelaxProgress&)> progress;
    double progressInterval = 0.2; ///< s; finite, >= 0 (0 = every step)
    /// Stiffness continuation (the paper's): relax first with every stiffness scaled by
    /// previewStiffnessScale, then scale up by continuationFactor per stage to the material's.
    /// A soft stage ends when its residual (at its own stiffness) is below 1e-3 or the
    /// tolerance, whichever is larger; only the last stage, at scale 1, can converge.
    /// Skipped when the start already meets the tolerance. A warm start from an already relaxed
    /// shape converges faster with continuation = false.
    bool continuation = true;
    /// s of the first stage, in (0, 1]. The first stage is never softer than needed to keep the
    /// strain modest: its EA is at least 20 times the mean load per held knot.
    double previewStiffnessScale = 1e-3;
    double continuationFactor = 10; ///< stiffness ratio between stages, finite, > 1
    std::optional<Wind> wind;       ///< a steady wind load; empty = none
    /// A warm-start hint: the tension of every bar (N; negative = compressed) in the start
    /// positions under the law of a system they were close to equilibrium in, such as the
    /// system before an edit of rest lengths, stiffness or rows. Empty = none (the start is judged
    /// from the positions alone); else one per bar, finite, and it must outlive the call. The
    /// fast backend then first tries a few Newton iterations seeded with these tensions; others
    /// ignore it. It changes how the equilibrium is found, never what counts as converged.
    std::span<const double> startTensions;
    /// Fast backend: the iterations seeded with startTensions factorize the Newton matrix in
    /// single precision (a factorization about 1.3 times as fast, a solve 1.6 times), each step
    /// refined in double; a step that stays too far off is solved again in double, and so is the
    /// rest of the run (NewtonRun.h, kSingleAccuracy). Worth it where the steps are hinted and
    /// the tolerance loose, such as the studio's preview after an edit. Others ignore it. It
    /// changes how the equilibrium is found, never what counts as converged.
    bool singlePrecisionSteps = false;
    /// Fast backend: when the iterations seeded with startTensions end short of the tolerance,
    /// the knots still out of balance and rings of their neighbours are relaxed on their own at
    /// once, the rest held (a focus region, physics/fast/FocusRegion.h), before the whole net's
    /// iterations go on. Worth it in the studio's preview of a slack net, where a drag leaves a
    /// few hundred knots of its folds to settle; not at the rope's stiffness, where a region held
    /// at its boundary can choose another way down for a slack piece (docs/performance.md). Others
    /// ignore it. It changes how the equilibrium is found, never what counts as converged.
    bool focusAfterHint = false;
    /// Fast backend: the first iteration seeded with startTensions solves with the factor the
    /// relaxer's last run on the same topology left, when its matrix was of the same scale (a
    /// chord step: a solve instead of a factorization), and the iterations after it factorize as
    /// usual. Worth it where a run starts within a few hundredths of a knot weight of its
    /// equilibrium, as the studio's preview does along a drag (interaction/DragPath.h). The run
    /// then depends on the runs before it (deterministically: the same calls give the same bits).
    /// Others ignore it. It changes how the equilibrium is found, never what counts as converged.
    bool reuseFactor = false;
    /// Fast backend: a cancel during the iterations seeded with startTensions waits until one of
    /// them has reached a state good enough to keep (at most those few iterations). The studio's
    /// preview after an edit: a drag as fast as the frames cancels each run within its first
    /// iteration, which on a slack net is not yet such a state, and the shape on screen would not
    /// move until the drag stopped. Others ignore it.
    bool hintBeforeCancel = false;
    /// With hintBeforeCancel: when this reads true too, a cancel does not wait (the caller stops
    /// for good: no newer edit will go on from the state). Null = every cancel waits.
    const std::atomic<bool>* cancelNow = nullptr;
};

struct RelaxResult {
    bool converged = false; ///< residual < tolerance at full stiffness
    double residual = 0;    ///< at the final positions, full stiffness (what residual() returns)
    std::int64_t steps = 0; ///< integration steps, rejected ones included
    std::int64_t forceEvaluations = 0; ///< passes of Eq. 3 over the whole system
    double seconds = 0;                ///< wall time, s
    std::string backend = "rk4";
    double tolerance = 0; ///< the tolerance the run was asked for (RelaxOptions::tolerance)
    /// "converged", "time limit", "step limit", "cancelled", "diverged" (the step size
    /// collapsed; the positions are the last good state, never NaN), "precision limit" (the fast
    /// backend: its steps no longer move any knot by more than a few units in the last place of
    /// its coordinates, so no nearer equilibrium can be written in doubles; far from the system's
    /// origin that floor is above the tolerance) or "stalled" (the Bullet backend).
    std::string stopReason;
    /// When the run did not converge, where the net has not settled: the (piece, row, column) of
    /// the free knot with the largest residual at the positions returned (its first reference
    /// when pieces share it). Filled by Document::relax() for every backend.
    std::optional<KnotRef> unsettledAt;
};

/// Throws UserError naming the first invalid option, its value and what is allowed.
void validate(const RelaxOptions& options);

/// A relaxation backend. relax() moves the free knots of system in place, starting from the
/// positions it has (a warm start), and returns how it went. On any stop the positions are
/// finite and are the best state reached. Throws UserError for invalid options or system.
class Relaxer {
  public:
    virtual ~Relaxer() = default;
    virtual std::string_view name() const = 0;
    [[nodiscard]] virtual RelaxResult relax(MassSpringSystem& system,
                                            const RelaxOptions& options) = 0;
};

/// The overdamped RK4 integration of Eq. 7 with fictitious masses (dynamic relaxation's
/// m_j = s * sum of kTension over the knot's bars), a step near RK4's stability limit from a
/// Gershgorin bound, automatic step back-off on blow-up, and stiffness continuation.
class Rk4Relaxer final : public Relaxer {
  public:
    std::string_view name() const override { return "rk4"; }
    [[nodiscard]] RelaxResult relax(MassSpringSystem& system, const RelaxOptions& options) override;
};

/// Rk4Relaxer().relax(system, options).
[[nodiscard]] RelaxResult relaxRk4(MassSpringSystem& system, const RelaxOptions& options = {});

} // namespace netsculpt
