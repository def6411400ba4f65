#pragma once
// Live relaxation for the studio: a background thread relaxes a copy of the compiled system and
// publishes its positions a few dozen times a second; the UI thread never waits for it.
//
// preview() relaxes a soft copy of the material (every stiffness scaled by the preview scale, so
// it settles in a fraction of the time; the shape is close to the final one) in one run whose
// progress reports carry positions, each published (about every publishInterval). Each call
// cancels the run in progress (RelaxOptions::cancel) and starts again from the positions it is
// given, so every edit restarts from the current shape (a warm start: the fast path then needs a
// few Newton iterations); when the run cut short was a preview of the same knots, from where it
// stopped, which the new run shows at once (a drag as fast as the frames cuts every run short;
// its hinted iterations first reach a state worth keeping: RelaxOptions::hintBeforeCancel).
// refine() relaxes at the material's stiffness in one run (the backend's own stiffness
// continuation) down to the refine tolerance, publishing its residual as it converges and the
// positions at the end.
//
// Warm starts: each preview passes the backend the tensions its start shape had in the system
// before the edit (startTensions), which the fast path turns into a predictor step: after a small
// edit it converges in two or three Newton iterations instead of redoing its soft start stage.
// Along a drag (the same rest-length edit again and again) a step starts where the path through
// the last steps' shapes leads (DragPath.h), a few thousandths of a knot weight off its
// equilibrium on a taut net, and the fast path solves its one Newton step with the factor the
// last step left (RelaxOptions::reuseFactor) when that takes a few solves: most steps of a drag
// then factorize nothing.
// A refine after an edit of a refined shape first tries that shape, carried across the edit, with
// the tensions it had (refineRun), and goes on from the preview's shape if that does not converge
// within a few iterations.
//
// Publication: the worker builds a new immutable LiveState and swaps a shared_ptr under a mutex;
// latest() copies the pointer (the UI reads a state nobody writes).

#include "interaction/DragPath.h"
#include "physics/Forces.h"
#include "physics/MassSpringSystem.h"
#include "physics/Relaxer.h"
#include "physics/WarmStart.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace netsculpt {

struct LiveState;

struct LiveRelaxOptions {
    /// Stiffness of the preview relative to the material, in (0, 1]. Raised when it would be so soft
    /// that the net stretches visibly (EA is kept >= 20 x the mean load per held knot).
    double previewStiffnessScale = 1e-2;
    double previewTolerance = 1e-3;   ///< the preview stops below this residual (at its stiffness)
    double refineTolerance = 1e-6;    ///< refine: converged below this residual at full stiffness
    double maxSeconds = 600;          ///< a run gives up after this long, s
    double publishInterval = 1.0 / 30; ///< s, at least, between two published preview shapes
    std::string backend = "auto";     ///< see makeRelaxer
    int threads = 0;                  ///< RelaxOptions::threads
    /// RelaxOptions::threads for the runs no drag waits on: a preview of an edit made with no
    /// handle held (preview()'s `dragging`: typed, a button, an undo), a preview from a cold
    /// start (a new or opened sculpture: no hint from a shape before it), and a refine. 0:
    /// `threads`.
    int settleThreads = 0;
    /// RelaxOptions::singlePrecisionSteps for the preview's hinted runs (after an edit)
    bool singlePrecisionSteps = true;
    /// Called on the worker thread right after each publication, with the state published (to
    /// wake a UI, or to time publications). Empty = none. Must not call back into the relaxer.
    std::function<void(const LiveState&)> onPublish;
};

/// The threads the studio gives its live preview: every hardware thread but one, kept for drawing
/// frames (with a software renderer the frames need a core of their own), and at least one.
int threadsBesideTheFrames();
/// The threads the studio gives the runs no drag waits on (LiveRelaxOptions::settleThreads): every
/// hardware thread. The relaxation runs below the frames' priority (LiveRelaxer::setNiceness), so
/// the frames still get the CPU first.
int threadsForSettling();

enum class LivePhase { Idle, Preview, Refine };

/// One published shape and how the run stands. Immutable once published.
struct LiveState {
    std::uint64_t generation = 0; ///< the tag given to preview()/refine(): which document state
    std::uint64_t sequence = 0;   ///< increases with every publication
    /// m, from the origin of the system it was given (MassSpringSystem::origin), one per knot;
    /// empty in a refine's progress reports (the positions are those of the last state that had
    /// them).
    std::vector<Vec3> positions;
    LivePhase phase = LivePhase::Idle;
    bool running = false;         ///< more publications of this run will follow
    bool converged = false;       ///< the run reached its tolerance (preview: at its soft stiffness)
    double residual = 0;          ///< max |F|/(m|g|) at stiffnessScale, at these positions
    double stiffnessScale = 1;    ///< of the stage the positions come from
    std::int64_t steps = 0;       ///< integration steps of this run so far
    double seconds = 0;           ///< wall time of this run so far, s
    /// when !running: "converged", "cancelled", "time limit", "diverged", "precision limit"
    /// (RelaxResult::stopReason), "error"
    std::string stopReason;
    std::string error;            ///< the UserError text when stopReason == "error"
};

class LiveRelaxer {
  public:
    explicit LiveRelaxer(LiveRelaxOptions options = {});
    ~LiveRelaxer(); ///< cancels and joins the worker
    LiveRelaxer(const LiveRelaxer&) = delete;
    LiveRelaxer& operator=(const LiveRelaxer&) = delete;

    /// Restarts the soft preview from `system`'s positions (copied). Returns at once.
    /// `dragging`: the edit is a step of a drag, whose next step comes within frames (the run
    /// takes `threads`, else `settleThreads`).
    void preview(const MassSpringSystem& system, std::uint64_t generation, bool dragging = false);
    /// Relaxes at the material's stiffness from `system`'s positions (copied). Returns at once.
    void refine(const MassSpringSystem& system, std::uint64_t generation);
    /// Cancels the run in progress (the last published state stays).
    void cancel();

    /// The last published state; null before the first publication.
    std::shared_ptr<const LiveState> latest() const;
    /// Waits until no run is queued or running, up to `timeoutSeconds`. True when idle.
    bool waitIdle(double timeoutSeconds) const;
    /// Runs the worker (and the threads it starts) at this nice value above the one it started
    /// with, from the next run on: 0 (the default) to 19. Linux only (elsewhere nothing changes).
    /// Going back down may be refused without privileges; the worker then stays lower.
    void setNiceness(int niceness);
    const LiveRelaxOptions& options() const { return options_; }

  private:
    struct Job {
        MassSpringSystem system;
        std::uint64_t generation = 0;
        LivePhase phase = LivePhase::Preview;
        bool dragging = false; ///< preview(): a step of a drag
    };
    void start(Job job);
    void workerLoop();
    void applyNiceness();
    /// One job on the worker: what it publishes, and since when it runs.
    struct JobRun {
        Job& job;
        std::chrono::steady_clock::time_point start;
        LiveState state;
        double seconds() const; ///< since start
    };
    void runJob(Job& job);
    void runPreview(JobRun& run);
    void runRefine(JobRun& run);
    /// The options every run shares: the cancel flags, threads (settleThreads when `settling`)
    /// and time limit.
    RelaxOptions jobOptions(bool settling);
    /// Publishes run's state, ended with `reason` at `positions`.
    void finish(JobRun& run, const std::string& reason, std::vector<Vec3> positions);
    void publish(LiveState state);
    bool superseded() const;
    bool hasPending() const;

    LiveRelaxOptions options_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    mutable std::condition_variable idle_;
    std::optional<Job> pending_;
    bool busy_ = false;
    bool quit_ = false;
    std::atomic<bool> cancel_{false};
    std::atomic<bool> cancelNow_{false}; ///< cancel() and quitting: RelaxOptions::cancelNow
    std::atomic<int> niceness_{0}; ///< requested by setNiceness
    int appliedNiceness_ = 0;      ///< worker thread only
    int startNice_ = 0;            ///< worker thread only: its nice value when it started
    std::uint64_t sequence_ = 0;
    std::shared_ptr<const LiveState> latest_;
    std::unique_ptr<Relaxer> relaxer_; ///< used by the worker thread only
    /// Worker thread only: the system of the last run (the preview's soft copy, or the material
    /// for a refine) with the positions it ended at, whose law gives the next preview's tension
    /// hint (startTensions below). Empty before the first run and after an error. Runs cut short
    /// by a newer one: a preview that did not move its start leaves the system before it, and a
    /// refine the preview's before it (the shape the document still shows).
    std::optional<MassSpringSystem> previous_;
    /// Worker thread only: previous_'s positions are where a preview ended near its equilibrium
    /// under previous_'s law (converged, or cut short after an iteration that came near): a drag's
    /// path may start there.
    bool previousSettled_ = false;
    /// Worker thread only: after a preview of a row step (PreviewStart::rowStep) that converged,
    /// the system before that step: a row drag's next step of the same size is shown along the
    /// motion of the last one (continueRowDrag). Empty otherwise.
    std::optional<MassSpringSystem> rowDragBefore_;
    /// Whether `soft`, a row step (PreviewStart::rowStep), repeats the last one: the same change
    /// of the knot count again.
    bool repeatsRowStep(const MassSpringSystem& soft, bool rowStep) const;
    /// Worker thread only: the last run was a preview superseded by a newer one before its end
    /// was published; previous_ holds where it stopped, which the next preview goes on from.
    bool previewCancelled_ = false;
    /// Worker thread only: the system of the last refine that converged, at its equilibrium.
    std::optional<MassSpringSystem> refined_;
    /// A refine's start after an edit of the refined shape: `system`'s positions become that
    /// shape carried across the edit (new rows where the rows above lead), and the hint returned
    /// is the tensions it had; empty (and `system` unchanged) when too few bars match or a knot
    /// held in both is held elsewhere (another sculpture).
    std::vector<double> refinedStart(MassSpringSystem& system) const;
    /// A refine of `system` (its positions: the preview's shape), after an edit of a refined shape
    /// tried from that shape first (kRefinedStartSteps in LiveRelaxer.cpp); the result of the run
    /// whose positions `system` ends with, the steps of both.
    RelaxResult refineRun(MassSpringSystem& system, const RelaxOptions& options);
    /// Worker thread only: the shapes the last previews converged in after rest-length edits
    /// that repeat one another (a drag's steps, DragPath.h). The next edit that repeats them
    /// starts where the path through them leads, so one Newton iteration, or a step with the last
    /// factor, corrects it.
    DragPath path_;
    /// When `next` repeats the last step's edit of `previous` (see path_), moves its free knots
    /// on to the path's prediction of the lowest residual (of degree 1, the secant, to
    /// DragPath::kMaxDegree), if that lowers the residual, and returns that residual (max
    /// |F|/(m|g|) over free knots at next's law); else nullopt. `restChange` gets
    /// next's rest lengths minus previous's whenever `next` is a rest-length edit of the shape
    /// `previous` ended at (else it is left empty).
    std::optional<double> extrapolate(const MassSpringSystem& previous, MassSpringSystem& next,
                                      std::vector<double>& restChange);
    /// After extrapolate(): its prediction of the lowest residual when the one of the degree next
    /// to it agrees with it, both moving the knots from `from` alike (to within kAgreement of the
    /// motion), its residual then in `residual`; else null (as when it made none).
    const std::vector<Vec3>* agreedPrediction(const std::vector<Vec3>& from,
                                              double& residual) const;
    /// How a preview starts (worker thread only): `soft`'s positions carried on from a cancelled
    /// preview, new rows continued, a repeated edit extrapolated (DragPath); what is shown at
    /// once. previous_ moves into `before`; the hint (from it) is the caller's to make.
    struct PreviewStart {
        std::vector<double> hint;       ///< RelaxOptions::startTensions; empty = none
        bool repeated = false;          ///< extrapolated along the drag's path: the hint's law
        std::vector<Vec3> positions;    ///< soft's before the extrapolation: a step's origin
        std::vector<double> restChange; ///< extrapolate()'s
        /// carried, continued, predicted near its equilibrium, or `shown`: published before
        /// iterating
        bool showAtOnce = false;
        /// a prediction shown at once in place of the start (agreedPrediction, a row drag's
        /// continueRowDrag); empty = none
        std::vector<Vec3> shown;
        double residual = 0; ///< of the predicted start, or of `shown`; 0 = not computed
        /// the knot count changed on the same knots (rows added or removed) from a settled
        /// shape: a row drag's step (rowDragBefore_)
        bool rowStep = false;
        /// `positions` are where the run before ended near its equilibrium (previousSettled_)
        bool settled = false;
        std::optional<MassSpringSystem> before;
    };
    PreviewStart preparePreviewStart(MassSpringSystem& soft);
    /// Sets o's progress callback to publish the preview's shapes of `knots` knots (at stiffness
    /// `scale`) as often as the publish interval asks; `lastShown`: when one was last shown.
    void setShapePublisher(JobRun& run, RelaxOptions& o, std::size_t knots, double scale,
                           double lastShown);
    /// After a preview: its step added to path_ when it ended `nearEquilibrium` (converged, or
    /// cut short near it) after a rest-length edit; else the path ends.
    void rememberStep(bool nearEquilibrium, PreviewStart& start, const MassSpringSystem& soft);
    /// Worker thread only: extrapolate()'s residual test, kept for the topology of its last use
    /// (a drag's steps share it; only the law is updated): the force field, the bars and fixed
    /// flags it was built for, and scratch.
    struct ResidualCheck {
        ForceField field;
        std::vector<std::uint32_t> barA, barB;
        std::vector<std::uint8_t> fixed;
        std::vector<Vec3> force;
        /// extrapolate()'s predictions for the step, of degree 1, 2, ..., one per residual (no
        /// residual: none made; the storage is kept from step to step)
        std::vector<std::vector<Vec3>> predictions;
        std::vector<double> residuals;
    };
    std::optional<ResidualCheck> residualCheck_;
    /// Worker thread only: a hash of each shape the last preview published before its end. The
    /// document may take one of them (a frame before the run ended) and edit it: the next
    /// preview then goes on from where the run ended, which a drag's path holds.
    std::vector<std::uint64_t> shownOnTheWay_;
    /// Publishes a preview's shape before its end, its hash kept in shownOnTheWay_.
    void publishOnTheWay(LiveState shown);
    /// Whether `positions` are one of the shapes the last preview published before its end.
    bool wasShownOnTheWay(const std::vector<Vec3>& positions) const;
    /// The residual check with `system`'s topology and law (UserError as ForceField's).
    ResidualCheck& residualCheckFor(const MassSpringSystem& system);
    std::thread worker_; // last: starts after everything it uses exists
};

/// The soft scale the preview uses for `system` (previewStiffnessScale raised to the strain floor).
double previewScale(const MassSpringSystem& system, double requested);
/// Every bar's stiffness (tension and compression) times `scale`: the preview's soft copy.
void scaleStiffness(MassSpringSystem& system, double scale);

} // namespace netsculpt
