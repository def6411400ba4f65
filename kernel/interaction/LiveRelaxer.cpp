#include "interaction/LiveRelaxer.h"

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

LiveRelaxer::LiveRelaxer(LiveRelaxOptions options) : options_(std::move(options)), worker_([this] { workerLoop(); }) {}

LiveRelaxer::~LiveRelaxer() {
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
        cancel_ = true;
    }
    wake_.notify_all();
    worker_.join();
}

void LiveRelaxer::preview(const MassSpringSystem& system, std::uint64_t generation) {
    start(system, generation, LivePhase::Preview);
}

void LiveRelaxer::refine(const MassSpringSystem& system, std::uint64_t generation) {
    start(system, generation, LivePhase::Refine);
}

void LiveRelaxer::start(const MassSpringSystem& system, std::uint64_t generation, LivePhase phase) {
    Job job{system, generation, phase}; // the copy is made outside the lock
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
    std::lock_guard lock(mutex_);
    shared->sequence = ++sequence_;
    latest_ = std::move(shared);
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

void LiveRelaxer::runJob(Job& job) {
    const auto start = Clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    LiveState state;
    state.generation = job.generation;
    state.phase = job.phase;
    state.running = true;
    auto finish = [&](const std::string& reason, std::vector<Vec3> positions) {
        state.running = false;
        state.stopReason = reason;
        state.positions = std::move(positions);
        state.seconds = seconds();
        publish(state);
    };
    try {
        // One relaxer for the worker's lifetime: a backend may keep per-topology analysis between
        // calls (the fast backend does), which a drag that keeps the topology reuses.
        if (!relaxer_) relaxer_ = makeRelaxer(options_.backend);
        RelaxOptions o;
        o.cancel = &cancel_;
        o.threads = options_.threads;
        if (job.phase == LivePhase::Preview) {
            // The soft copy in one run whose progress reports, with their positions, are
            // published: the net visibly settles. RK4's soft copy needs no continuation of its
            // own (its schedule is a way to such a stiffness); the fast path's continuation is
            // how it starts from a cold shape, and a warm one skips it.
            const double scale = previewScale(job.system, options_.previewStiffnessScale);
            MassSpringSystem soft = job.system;
            scaleStiffness(soft, scale);
            o.tolerance = options_.previewTolerance;
            o.continuation = relaxer_->name() == "fast";
            o.maxSeconds = options_.maxSeconds;
            o.progressInterval = options_.publishInterval;
            state.stiffnessScale = scale;
            o.progress = [&](const RelaxProgress& p) {
                if (p.positions.size() != soft.knotCount())
                    return;
                LiveState shown = state;
                shown.stiffnessScale = scale * p.stiffnessScale; // the fast path may start softer
                shown.residual = p.residual;
                shown.steps = p.steps;
                shown.seconds = seconds();
                shown.positions.assign(p.positions.begin(), p.positions.end());
                publish(std::move(shown));
            };
            const RelaxResult r = relaxer_->relax(soft, o);
            state.steps = r.steps;
            state.residual = r.residual;
            if (r.stopReason == "cancelled" || superseded()) {
                if (!hasPending()) finish("cancelled", soft.position); // else a newer run follows
                return;
            }
            state.converged = r.converged;
            return finish(r.stopReason, soft.position);
        }
        // Refine: the material's stiffness in one run, so the backend keeps its own continuation
        // (restarting it in pieces can lead a slack net to another equilibrium); its progress
        // reports are published without positions (the shape shown stays until the end).
        o.tolerance = options_.refineTolerance;
        o.maxSeconds = options_.maxSeconds;
        o.continuation = true;
        o.progressInterval = 3 * options_.publishInterval;
        o.progress = [&](const RelaxProgress& p) {
            LiveState report = state;
            report.residual = p.residual;
            report.stiffnessScale = p.stiffnessScale;
            report.steps = p.steps;
            report.seconds = seconds();
            publish(std::move(report));
        };
        const RelaxResult r = relaxer_->relax(job.system, o);
        state.steps = r.steps;
        state.residual = r.residual;
        state.stiffnessScale = 1;
        if (r.stopReason == "cancelled" || superseded()) {
            if (!hasPending()) finish("cancelled", job.system.position);
            return;
        }
        state.converged = r.converged;
        finish(r.stopReason, job.system.position);
    } catch (const UserError& e) {
        state.error = e.what();
        finish("error", job.system.position);
    }
}

} // namespace netsculpt
