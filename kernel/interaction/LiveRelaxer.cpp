#include "interaction/LiveRelaxer.h"

#include "geometry/ShapeHash.h"
#include "model/Error.h"
#include "physics/Backends.h"
#include "physics/Forces.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace netsculpt {

namespace {

using Clock = std::chrono::steady_clock;

// Two rest-length edits are the same edit (a drag's steps) when the second, less its best
// multiple of the first, is below this share of it (Euclidean norms over the bars).
constexpr double kRepeatTolerance = 1e-3;

// A refine after an edit of a refined shape first takes at most this many Newton iterations from
// that shape carried across the edit, with the tensions it had (the edit's predictor, then warm
// steps): an edit that leaves most bars as they were converges within them (the installation's
// banner edited: 8 iterations, 0.6 s, against 76 and 6.1 s from the preview's shape). One that
// changes the slack parts (the installation's core lengthened, its tied bell slackening: 161
// iterations that way, 47 from the preview's shape) goes on from the preview's shape instead.
constexpr std::int64_t kRefinedStartSteps = 12;

// A drag's shape this near its equilibrium (knot weights, at the preview's law) is near enough
// to show and to go on from. A step's prediction so near is shown at once, before the step's
// Newton iteration corrects it: along the tube's drag of netsculpt-bench-live the secant's starts
// (0.6-1 knot weights off) have every knot within 0.11 mm of its settled place and the cubic's
// (0.002-0.01) within 0.013 mm, so a 42 mm step is on screen the frame after the edit. A step cut
// short by the next edit after an iteration that brought it so near goes on the drag's path: a
// drag as fast as the frames cuts most of them short. A start further off (a slack net's folds
// turning) is neither shown nor kept.
constexpr double kNearEquilibrium = 1.0;

// A drag step's prediction further off by its residual (a slack net's folds: bars turning between
// the tension and compression laws give it tens to hundreds of knot weights, where the shape
// before the edit may have ten, and it is then not the step's start either) is still shown at once
// when the predictions of two neighbouring degrees agree to within this share of the motion they
// predict: the path is then a guide to where the knots go, though not to the forces. On the
// 20,000-knot slack sheet of netsculpt-bench-live 16 of 20 steps are shown so, within 0.7-17 mm of
// their settled shape (median 6.5 mm), against 37-38 mm for the shape before the edit.
constexpr double kAgreement = 0.25;

} // namespace

void scaleStiffness(MassSpringSystem& system, double scale) {
    for (double& k : system.kTension) k *= scale;
    for (double& k : system.kCompression) k *= scale;
}

double previewScale(const MassSpringSystem& system, double requested) {
    double minAxialStiffness = std::numeric_limits<double>::infinity(); // EA, N
    for (std::size_t b = 0; b < system.barCount(); ++b)
        minAxialStiffness = std::min(minAxialStiffness, system.kTension[b] * system.restLength[b]);
    const auto fixedCount = std::count(system.fixed.begin(), system.fixed.end(), std::uint8_t{1});
    if (!std::isfinite(minAxialStiffness) || minAxialStiffness <= 0 || fixedCount == 0) return 1;
    const double meanHeldLoad = totalWeight(system) / double(fixedCount);
    return std::clamp(std::max(requested, 20 * meanHeldLoad / minAxialStiffness), 1e-9, 1.0);
}

int threadsBesideTheFrames() {
    return static_cast<int>(std::max(2u, std::thread::hardware_concurrency()) - 1);
}

int threadsForSettling() {
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

LiveRelaxer::LiveRelaxer(LiveRelaxOptions options) : options_(std::move(options)), worker_([this] { workerLoop(); }) {}

LiveRelaxer::~LiveRelaxer() {
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
        cancel_ = true;
        cancelNow_ = true;
    }
    wake_.notify_all();
    worker_.join();
}

void LiveRelaxer::preview(const MassSpringSystem& system, std::uint64_t generation, bool dragging) {
    start(Job{system, generation, LivePhase::Preview, dragging}); // copied outside the lock
}

void LiveRelaxer::refine(const MassSpringSystem& system, std::uint64_t generation) {
    start(Job{system, generation, LivePhase::Refine, false});
}

void LiveRelaxer::start(Job job) {
    {
        std::lock_guard lock(mutex_);
        pending_ = std::move(job);
        cancel_ = true; // the run in progress stops at its next step
    }
    wake_.notify_one();
}

void LiveRelaxer::cancel() {
    std::lock_guard lock(mutex_);
    pending_.reset();
    cancel_ = true;
    cancelNow_ = true; // nothing goes on from the run's state: its hinted steps need not finish
}

std::shared_ptr<const LiveState> LiveRelaxer::latest() const {
    std::lock_guard lock(mutex_);
    return latest_;
}

bool LiveRelaxer::waitIdle(double timeoutSeconds) const {
    std::unique_lock lock(mutex_);
    return idle_.wait_for(lock, std::chrono::duration<double>(timeoutSeconds), [&] { return !busy_ && !pending_; });
}

bool LiveRelaxer::superseded() const {
    std::lock_guard lock(mutex_);
    return quit_ || pending_.has_value() || cancel_.load();
}

bool LiveRelaxer::hasPending() const {
    std::lock_guard lock(mutex_);
    return pending_.has_value() || quit_;
}

void LiveRelaxer::publish(LiveState state) {
    auto shared = std::make_shared<LiveState>(std::move(state));
    {
        std::lock_guard lock(mutex_);
        shared->sequence = ++sequence_;
        latest_ = shared;
    }
    if (options_.onPublish) options_.onPublish(*shared);
}

void LiveRelaxer::setNiceness(int niceness) { niceness_ = std::clamp(niceness, 0, 19); }

#ifdef __linux__
// On Linux the nice value is per thread: PRIO_PROCESS with a thread id reaches one thread.
void LiveRelaxer::applyNiceness() {
    const int wanted = niceness_;
    if (wanted == appliedNiceness_) return;
    const auto thread = static_cast<id_t>(syscall(SYS_gettid));
    if (setpriority(PRIO_PROCESS, thread, std::min(startNice_ + wanted, 19)) == 0) appliedNiceness_ = wanted;
}
#else
void LiveRelaxer::applyNiceness() {}
#endif

void LiveRelaxer::workerLoop() {
#ifdef __linux__
    startNice_ = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
#endif
    for (;;) {
        Job job;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return quit_ || pending_.has_value(); });
            if (quit_) break;
            job = std::move(*pending_);
            pending_.reset();
            cancel_ = false;
            cancelNow_ = false;
            busy_ = true;
        }
        applyNiceness();
        runJob(job);
        {
            std::lock_guard lock(mutex_);
            busy_ = false;
        }
        idle_.notify_all();
    }
    std::lock_guard lock(mutex_);
    busy_ = false;
    idle_.notify_all();
}

LiveRelaxer::PreviewStart LiveRelaxer::preparePreviewStart(MassSpringSystem& soft) {
    PreviewStart start;
    // A preview cancelled by this edit never reached the screen or the document: this one goes on
    // from where it stopped, not from the shape before it (a drag as fast as the frames cancels
    // every run within its first iteration or two), where its knots are still the same ones.
    const std::size_t carried = previous_ && previewCancelled_ &&
                                        sameKnotsWhereMatched(*previous_, soft)
                                    ? carryMatchedPositions(*previous_, soft)
                                    : 0;
    previewCancelled_ = false;
    // A shape the last preview showed on its way, taken by the document before the run ended:
    // the edit goes on from where it ended.
    if (previous_ && carried == 0 && previous_->knotCount() == soft.knotCount() &&
        previous_->origin == soft.origin && wasShownOnTheWay(soft.position))
        soft.position = previous_->position;
    // A change of the knot count on the same knots from a settled shape: rows added or removed.
    start.rowStep = previous_ && previousSettled_ && carried == 0 &&
                    previous_->knotCount() != soft.knotCount() &&
                    sameKnotsWhereMatched(*previous_, soft);
    // Rows added below go on with the shape above them, and the tensions the start shape had
    // before the edit make the fast path's predictor. The same edit once more (a drag's next
    // step) goes on as far as the last step went; its hint is then the new law's tensions there.
    const std::size_t continued = previous_ ? continueNewRows(*previous_, soft) : 0;
    // A row drag's next step is shown at once as far on as the last one moved the knots (the
    // rows it adds with the knots above them; rows removed, the others). The run starts from the
    // shape before: from the moved one the tube's row steps took 4 iterations instead of 2 (the
    // hint, the tensions of the shape before, makes the first iteration the edit's whole response).
    if (repeatsRowStep(soft, start.rowStep)) {
        start.shown = soft.position;
        continueRowDrag(*rowDragBefore_, *previous_, soft, start.shown);
    }
    start.positions = soft.position; // the step is measured from here
    start.settled = previous_ && previousSettled_ && previous_->position == soft.position;
    const std::optional<double> predicted =
        previous_ ? extrapolate(*previous_, soft, start.restChange) : std::nullopt;
    const bool repeated = predicted.has_value();
    start.residual = predicted.value_or(0.0);
    const bool near = repeated && *predicted <= kNearEquilibrium;
    if (const std::vector<Vec3>* agreed =
            near ? nullptr : agreedPrediction(start.positions, start.residual))
        start.shown = *agreed;
    start.showAtOnce = carried + continued > 0 || near || !start.shown.empty();
    start.repeated = repeated;
    start.before = std::move(previous_);
    previous_.reset();
    return start;
}

LiveRelaxer::ResidualCheck& LiveRelaxer::residualCheckFor(const MassSpringSystem& system) {
    // The force field of a drag's topology is kept from one step to the next (only the law
    // changes): building one touches megabytes of fresh memory, about 12 ms at 20k knots.
    if (residualCheck_ && residualCheck_->barA == system.barA && residualCheck_->barB == system.barB &&
        residualCheck_->fixed == system.fixed) {
        residualCheck_->field.setLaw(system);
    } else {
        residualCheck_.reset();
        residualCheck_.emplace(
            ResidualCheck{ForceField(system), system.barA, system.barB, system.fixed, {}, {}, {}});
    }
    return *residualCheck_;
}

std::optional<double> LiveRelaxer::extrapolate(const MassSpringSystem& previous,
                                               MassSpringSystem& next,
                                               std::vector<double>& restChange) {
    if (residualCheck_)
        residualCheck_->residuals.clear(); // no prediction for this step yet
    // Only an edit of the shape the last run ended at that keeps the bars (masses and k_s = EA / l
    // follow the rest lengths; an edit of something else as well is caught by the residual test).
    if (previous.barA != next.barA || previous.barB != next.barB ||
        previous.origin != next.origin || previous.position != next.position)
        return std::nullopt;
    restChange.resize(next.barCount());
    for (std::size_t b = 0; b < next.barCount(); ++b) restChange[b] = next.restLength[b] - previous.restLength[b];
    // The residual test's force field is made ready at a drag's first step, which takes more
    // than a frame anyway (no predictor yet), so that the second one does not pay for it.
    ResidualCheck& check = residualCheckFor(next);
    // This edit as a multiple of the last one (a drag's next step), and the path's shapes where
    // it ends.
    const std::optional<double> rho = path_.ratio(restChange, kRepeatTolerance);
    if (!rho)
        return std::nullopt;
    check.force.resize(next.knotCount());
    auto worst = [&](const std::vector<Vec3>& at) {
        check.field.evaluate(at, check.force);
        double r = 0;
        for (std::size_t j = 0; j < next.knotCount(); ++j)
            if (!next.fixed[j]) r = std::max(r, check.field.residualOf(j, check.force[j]));
        return r;
    };
    // The prediction of the lowest residual, kept only when it is nearer the new equilibrium
    // than the shape it starts from.
    const double unpredicted = worst(next.position);
    const auto degrees = static_cast<std::size_t>(path_.degrees());
    check.predictions.resize(std::max(check.predictions.size(), degrees)); // kept for the next
    check.residuals.resize(degrees);
    for (std::size_t d = 0; d < degrees; ++d) {
        path_.predict(*rho, static_cast<int>(d + 1), next.fixed, check.predictions[d]);
        check.residuals[d] = worst(check.predictions[d]);
    }
    const auto best = std::min_element(check.residuals.begin(), check.residuals.end());
    if (best == check.residuals.end() || !(*best < unpredicted))
        return std::nullopt;
    next.position = check.predictions[static_cast<std::size_t>(best - check.residuals.begin())];
    return *best;
}

const std::vector<Vec3>* LiveRelaxer::agreedPrediction(const std::vector<Vec3>& from,
                                                       double& residual) const {
    if (!residualCheck_ || residualCheck_->residuals.size() < 2)
        return nullptr;
    const ResidualCheck& check = *residualCheck_;
    const auto best = static_cast<std::size_t>(
        std::min_element(check.residuals.begin(), check.residuals.end()) - check.residuals.begin());
    const std::size_t other = best == 0 ? 1 : best - 1;
    const std::vector<Vec3>& shown = check.predictions[best];
    double disagreement = 0, motion = 0;
    for (std::size_t j = 0; j < shown.size(); ++j) {
        disagreement = std::max(disagreement, distance(shown[j], check.predictions[other][j]));
        motion = std::max(motion, distance(shown[j], from[j]));
    }
    if (!(disagreement <= kAgreement * motion))
        return nullptr;
    residual = check.residuals[best];
    return &shown;
}

std::vector<double> LiveRelaxer::refinedStart(MassSpringSystem& system) const {
    if (!heldAtTheSamePlaces(*refined_, system))
        return {}; // another sculpture: nothing of its refined shape applies
    MassSpringSystem start = system;
    carryMatchedPositions(*refined_, start);
    continueNewRows(*refined_, start);
    std::vector<double> hint = startTensions(*refined_, start);
    if (!hint.empty()) system.position = std::move(start.position);
    return hint;
}

RelaxResult LiveRelaxer::refineRun(MassSpringSystem& system, const RelaxOptions& options) {
    if (refined_) {
        MassSpringSystem carried = system;
        const std::vector<double> hint = refinedStart(carried);
        if (!hint.empty()) {
            RelaxOptions first = options;
            first.startTensions = hint;
            first.maxSteps = kRefinedStartSteps;
            const RelaxResult tried = relaxer_->relax(carried, first);
            if (tried.converged || tried.stopReason == "cancelled") {
                system.position = std::move(carried.position);
                return tried;
            }
            RelaxResult rest = relaxer_->relax(system, options);
            rest.steps += tried.steps;
            rest.forceEvaluations += tried.forceEvaluations;
            rest.seconds += tried.seconds;
            return rest;
        }
    }
    return relaxer_->relax(system, options);
}

double LiveRelaxer::JobRun::seconds() const {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

void LiveRelaxer::finish(JobRun& run, const std::string& reason, std::vector<Vec3> positions) {
    run.state.running = false;
    run.state.stopReason = reason;
    run.state.positions = std::move(positions);
    run.state.seconds = run.seconds();
    publish(run.state);
}

RelaxOptions LiveRelaxer::jobOptions(bool settling) {
    RelaxOptions o;
    o.cancel = &cancel_;
    o.cancelNow = &cancelNow_;
    o.threads = settling && options_.settleThreads > 0 ? options_.settleThreads : options_.threads;
    o.maxSeconds = options_.maxSeconds;
    return o;
}

void LiveRelaxer::runJob(Job& job) {
    JobRun run{job, Clock::now(), {}};
    run.state.generation = job.generation;
    run.state.phase = job.phase;
    run.state.running = true;
    try {
        // One relaxer for the worker's lifetime: a backend may keep per-topology analysis between
        // calls (the fast backend does), which a drag that keeps the topology reuses.
        if (!relaxer_) relaxer_ = makeRelaxer(options_.backend);
        if (job.phase == LivePhase::Preview)
            runPreview(run);
        else
            runRefine(run);
    } catch (const UserError& e) {
        previous_.reset();
        previousSettled_ = false;
        rowDragBefore_.reset();
        previewCancelled_ = false;
        refined_.reset();
        shownOnTheWay_.clear();
        run.state.error = e.what();
        finish(run, "error", job.system.position);
    }
}

// The soft copy in one run whose progress reports, with their positions, are published: the net
// visibly settles. RK4's soft copy needs no continuation of its own (its schedule is a way to such
// a stiffness); the fast path's continuation is how it starts from a cold shape, and a warm one
// skips it.
void LiveRelaxer::runPreview(JobRun& run) {
    const double scale = previewScale(run.job.system, options_.previewStiffnessScale);
    MassSpringSystem soft = run.job.system;
    scaleStiffness(soft, scale);
    PreviewStart start = preparePreviewStart(soft);
    shownOnTheWay_.clear();
    run.state.stiffnessScale = scale;
    double lastShown = 0;
    if (start.showAtOnce) {
        // New rows are shown at once where the rows above lead them: the caller has them at the
        // document's Eq. 2 offsets, and the first iteration comes after the new topology's
        // analysis (tens of ms at 20,000 knots). So are a carried shape and a drag's step
        // predicted near its equilibrium. Before the hint below (5 ms at 20,000 knots).
        LiveState shown = run.state;
        shown.residual = start.residual;
        shown.seconds = lastShown = run.seconds();
        shown.positions = start.shown.empty() ? soft.position : start.shown;
        publishOnTheWay(std::move(shown));
    }
    if (start.before)
        start.hint = startTensions(start.repeated ? soft : *start.before, soft);
    // A drag's next step waits on a run of a drag step with a hint; a cold run (a new or opened
    // sculpture) or an edit made with no handle held has no next step coming.
    RelaxOptions o = jobOptions(!run.job.dragging || start.hint.empty());
    o.startTensions = start.hint;
    o.tolerance = options_.previewTolerance;
    o.continuation = relaxer_->name() == "fast";
    o.singlePrecisionSteps = options_.singlePrecisionSteps;
    o.focusAfterHint = true;   // a slack net's folds settle on their own after a drag
    o.reuseFactor = true;      // along a drag, a step often needs no new factorization
    o.hintBeforeCancel = true; // a drag as fast as the frames still moves the net
    setShapePublisher(run, o, soft.knotCount(), scale, lastShown);
    const RelaxResult r = relaxer_->relax(soft, o);
    run.state.steps = r.steps;
    run.state.residual = r.residual;
    bool unmoved = false; // cancelled before it moved its start
    if (r.stopReason == "cancelled" || superseded()) {
        if (!hasPending()) finish(run, "cancelled", soft.position); // else a newer run follows
        previewCancelled_ = hasPending();
        unmoved = soft.position == start.positions;
        // A step cut short goes on the drag's path when an iteration brought it near its
        // equilibrium, else the next step takes on its edit; one that did not move leaves its
        // edit to the next's change, which is measured from the system before it.
        if (!unmoved) {
            const bool near = r.converged || (r.steps > 0 && r.residual <= kNearEquilibrium);
            if (near)
                rememberStep(true, start, soft);
            else
                path_.skip(start.restChange, kRepeatTolerance);
            previousSettled_ = near;
        }
        rowDragBefore_.reset();
    } else {
        run.state.converged = r.converged;
        finish(run, r.stopReason, soft.position);
        rememberStep(r.converged, start, soft);
        previousSettled_ = r.converged;
        if (r.converged && start.rowStep)
            rowDragBefore_ = std::move(start.before); // unused below: the run moved
        else
            rowDragBefore_.reset();
    }
    // The next run's hint is the tensions its start had under the law it was relaxed for: a run
    // that did not move its start leaves that law to the one before it.
    previous_ = unmoved && start.before ? std::move(start.before) : std::move(soft);
}

// Every report reaches the callback, which publishes when waiting for the next one (about as far
// off as the last one was) would keep a shape on screen longer than the publish interval: with a
// Newton iteration of 25 ms that is every iteration, not every second one (50 ms) as an interval
// test alone would give.
void LiveRelaxer::setShapePublisher(JobRun& run, RelaxOptions& o, std::size_t knots,
                                    double scale, double lastShown) {
    o.progressInterval = 0;
    o.progress = [this, &run, knots, scale, lastShown,
                  lastReport = 0.0](const RelaxProgress& p) mutable {
        if (p.positions.size() != knots || p.steps == 0) // the start: shown already
            return;
        const double now = run.seconds();
        const double period = now - lastReport;
        lastReport = now;
        if (now - lastShown + period < options_.publishInterval)
            return;
        lastShown = now;
        LiveState shown = run.state;
        shown.stiffnessScale = scale * p.stiffnessScale; // the fast path may start softer
        shown.residual = p.residual;
        shown.steps = p.steps;
        shown.seconds = run.seconds();
        shown.positions.assign(p.positions.begin(), p.positions.end());
        publishOnTheWay(std::move(shown));
    };
}

bool LiveRelaxer::repeatsRowStep(const MassSpringSystem& soft, bool rowStep) const {
    if (!rowStep || !rowDragBefore_)
        return false;
    const auto count = [](const MassSpringSystem& s) {
        return static_cast<std::ptrdiff_t>(s.knotCount());
    };
    const std::ptrdiff_t last = count(*previous_) - count(*rowDragBefore_);
    return last != 0 && count(soft) - count(*previous_) == last;
}

bool LiveRelaxer::wasShownOnTheWay(const std::vector<Vec3>& positions) const {
    const std::uint64_t hash = shapeHash(positions);
    return std::find(shownOnTheWay_.begin(), shownOnTheWay_.end(), hash) != shownOnTheWay_.end();
}

void LiveRelaxer::publishOnTheWay(LiveState shown) {
    shownOnTheWay_.push_back(shapeHash(shown.positions));
    publish(std::move(shown));
}

// A preview that ended near its equilibrium after a rest-length edit is a step of the path the
// next one may go on along (DragPath.h).
void LiveRelaxer::rememberStep(bool nearEquilibrium, PreviewStart& start,
                               const MassSpringSystem& soft) {
    if (!nearEquilibrium || start.restChange.empty()) {
        path_.clear();
        return;
    }
    path_.add(start.settled ? start.positions : std::vector<Vec3>{}, soft.position,
              std::move(start.restChange), kRepeatTolerance);
}

// The material's stiffness in one run, so the backend keeps its own continuation (restarting it
// in pieces can lead a slack net to another equilibrium); its progress reports are published
// without positions (the shape shown stays until the end).
void LiveRelaxer::runRefine(JobRun& run) {
    shownOnTheWay_.clear(); // the document takes the refine's shape, or the preview's end
    RelaxOptions o = jobOptions(true);
    o.tolerance = options_.refineTolerance;
    o.continuation = true;
    o.progressInterval = 3 * options_.publishInterval;
    o.progress = [&](const RelaxProgress& p) {
        LiveState report = run.state;
        report.residual = p.residual;
        report.stiffnessScale = p.stiffnessScale;
        report.steps = p.steps;
        report.seconds = run.seconds();
        publish(std::move(report));
    };
    // A refine cut short by an edit publishes no shape: the document keeps the preview's, and the
    // next preview goes on as if there had been no refine: its hint is the law that shape was
    // relaxed under, not the material's, and a drag's next step is still predicted.
    std::optional<MassSpringSystem> beforeRefine = std::move(previous_);
    DragPath pathBeforeRefine = std::move(path_);
    const bool settledBeforeRefine = previousSettled_;
    previous_.reset();
    previousSettled_ = false;
    rowDragBefore_.reset();
    previewCancelled_ = false;
    path_.clear();
    MassSpringSystem& system = run.job.system;
    const RelaxResult r = refineRun(system, o);
    run.state.steps = r.steps;
    run.state.residual = r.residual;
    run.state.stiffnessScale = 1;
    const bool cancelled = r.stopReason == "cancelled" || superseded();
    if (cancelled) {
        if (!hasPending()) finish(run, "cancelled", system.position);
    } else {
        run.state.converged = r.converged;
        finish(run, r.stopReason, system.position);
        if (r.converged) refined_ = system;
    }
    if (cancelled && hasPending() && beforeRefine) {
        previous_ = std::move(beforeRefine);
        path_ = std::move(pathBeforeRefine);
        previousSettled_ = settledBeforeRefine;
    } else {
        previous_ = std::move(system);
    }
}

} // namespace netsculpt
