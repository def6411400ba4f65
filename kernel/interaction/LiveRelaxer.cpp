#include "interaction/LiveRelaxer.h"

#include "model/Error.h"
#include "physics/Backends.h"
#include "physics/Forces.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace netsculpt {

namespace {

using Clock = std::chrono::steady_clock;

MassSpringSystem scaledCopy(const MassSpringSystem& system, double scale) {
    MassSpringSystem soft = system;
    for (double& k : soft.kTension) k *= scale;
    for (double& k : soft.kCompression) k *= scale;
    return soft;
}

/// The stiffness scales a run walks through: the preview's only, or the ladder up to 1.
std::vector<double> stages(double first, LivePhase phase, double factor) {
    if (phase == LivePhase::Preview) return {first};
    std::vector<double> out;
    if (first < 1) {
        const double n = std::ceil(std::log(1 / first) / std::log(factor) - 1e-9);
        const double step = std::pow(1 / first, 1 / n);
        for (int i = 0; i < int(n); ++i) out.push_back(first * std::pow(step, i));
    }
    out.push_back(1.0);
    return out;
}

} // namespace

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

void LiveRelaxer::workerLoop() {
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
        Relaxer* relaxer = relaxer_.get();
        const double first = previewScale(job.system, options_.previewStiffnessScale);
        const std::vector<double> ladder = stages(first, job.phase, options_.continuationFactor);
        for (std::size_t stage = 0; stage < ladder.size(); ++stage) {
            const bool lastStage = stage + 1 == ladder.size();
            MassSpringSystem soft = scaledCopy(job.system, ladder[stage]);
            RelaxOptions o;
            o.tolerance = job.phase == LivePhase::Preview ? options_.previewTolerance
                          : lastStage                     ? options_.refineTolerance
                                                          : std::max(options_.stageTolerance, options_.refineTolerance);
            o.continuation = false; // the ladder is walked here, so every chunk publishes
            o.cancel = &cancel_;
            o.threads = options_.threads;
            o.maxSeconds = options_.publishInterval;
            for (;;) {
                const RelaxResult r = relaxer->relax(soft, o);
                state.steps += r.steps;
                state.residual = r.residual;
                state.stiffnessScale = ladder[stage];
                state.seconds = seconds();
                if (r.stopReason == "cancelled" || superseded()) {
                    if (!hasPending()) finish("cancelled", soft.position); // else a newer run follows
                    return;
                }
                if (r.stopReason == "diverged") return finish("diverged", soft.position);
                if (r.converged) break;
                if (state.seconds > options_.maxSeconds) return finish("time limit", soft.position);
                state.positions = soft.position;
                publish(state);
            }
            job.system.position = soft.position;
            if (!lastStage) {
                state.positions = job.system.position;
                publish(state);
            }
        }
        state.converged = true;
        finish("converged", job.system.position);
    } catch (const UserError& e) {
        state.error = e.what();
        finish("error", job.system.position);
    }
}

} // namespace netsculpt
