#include "physics/Relaxer.h"

#include "model/Error.h"
#include "physics/Forces.h"
#include "physics/ThreadPool.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace netsculpt {

namespace {

// Classical RK4 is stable for real negative lambda dt down to about -2.785; keep 7% margin.
constexpr double kRk4StableReach = 2.6;
// Soft continuation stages stop at this residual (or the tolerance if looser): they only have to
// bring the shape close to the next stage's.
constexpr double kStageTolerance = 1e-3;
// Back-off. Every kCheckpointSteps steps the state becomes the "last good" one; a residual over
// kBlowUpFactor times the last good one, or any non-finite number, restores the last good state
// and halves the step. The Gershgorin step is stable for the linearized system unless a bar is
// crushed to about compressionRatio of its length, so this is for violent states. (A residual
// that merely grows is not a blow-up: a net leaving an unstable equilibrium, e.g. buckling out
// of plane, speeds up before it settles.) After kRecoverSteps good steps the step grows back
// by 1.5, up to the stable one. The step never shrinks below kMinStepFraction of the stable
// one ("diverged").
constexpr std::int64_t kCheckpointSteps = 32;
constexpr double kBlowUpFactor = 1e3;
constexpr std::int64_t kRecoverSteps = 256;
constexpr double kMinStepFraction = 1e-6;
// The first continuation stage keeps EA >= kPreviewLoadFactor times the mean load per held knot.
constexpr double kPreviewLoadFactor = 20;

using Clock = std::chrono::steady_clock;

bool positiveFinite(double value) {
    return std::isfinite(value) && value > 0;
}

/// Per-chunk reduction slot on its own cache line.
struct alignas(64) Partial {
    double maxResidual = 0;
    bool finite = true;
};

/// One relaxation run: the integrator state and its bookkeeping.
class Rk4Run {
  public:
    Rk4Run(MassSpringSystem& system, const RelaxOptions& options)
        : system_(system), options_(options), field_(system) {
        field_.setLoad(options.wind, 1.0); // validates the wind
        const std::size_t knots = system.knotCount();
        for (std::size_t j = 0; j < knots; ++j)
            if (!system.position[j].isFinite())
                throw UserError("mass-spring system: knot " + std::to_string(j) +
                                " has a non-finite position");

        pool_ = relaxationPool(options.threads, field_.barCount());
        partials_.resize(pool_ ? pool_->chunkCount(knots) : 1); // one per chunk of the knot pass

        x_ = system.position;
        stagePositions_ = x_;
        checkpoint_ = x_;
        rate_.assign(knots, Vec3{});
        mobility_.assign(knots, 0.0);
        for (std::size_t j = 0; j < knots; ++j) {
            if (field_.isFixed(j)) {
                ++fixedCount_;
                continue;
            }
            ++freeCount_;
            // Fictitious mass of dynamic relaxation (scale 1): the sum of the bar stiffnesses.
            double stiffness = 0;
            for (std::uint32_t b : field_.barsOfKnot(j))
                stiffness += field_.barTensionStiffness(b);
            mobility_[j] = 1.0 / stiffness;
        }
        if (freeCount_ > 0 && fixedCount_ == 0)
            throw UserError("mass-spring system: no knot is fixed, so the net has no "
                            "equilibrium (it would fall)");
        stableStep_ = kRk4StableReach / gershgorinBound();
    }

    RelaxResult run();

  private:
    template <typename Body> void forRange(std::size_t count, Body&& body) {
        if (pool_)
            pool_->parallelFor(count, body);
        else
            body(std::size_t{0}, count, std::size_t{0});
    }

    double gershgorinBound() const;
    double firstStageScale() const;
    double evaluateResidual(const Vec3* positions);
    bool rk4Stage(int stage, double step);
    double stageResidual() const;
    bool stageFinite() const;
    double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

    MassSpringSystem& system_;
    const RelaxOptions& options_;
    ForceField field_;
    std::unique_ptr<ThreadPool> pool_;
    std::vector<Partial> partials_;
    std::vector<Vec3> x_;              ///< the state, m
    std::vector<Vec3> stagePositions_; ///< RK4 trial positions, m
    std::vector<Vec3> rate_;           ///< sum of the weighted stage velocities
    std::vector<Vec3> checkpoint_;     ///< last good state, m
    std::vector<double> mobility_;     ///< 1 / fictitious mass at scale 1 (0 for fixed knots)
    std::size_t freeCount_ = 0, fixedCount_ = 0;
    double stableStep_ = 1; ///< dimensionless (mobility is per unit stiffness)
    Clock::time_point start_;
    std::int64_t evaluations_ = 0;
};

/// lambda_max of M^-1 K <= max over free knots of (sum over bars of |K_b|, counted again for a
/// free other end) / m_j, with |K_b| <= kTension (Gershgorin). <= 2 for m_j = sum kTension.
double Rk4Run::gershgorinBound() const {
    double bound = 0;
    for (std::size_t j = 0; j < field_.knotCount(); ++j) {
        if (field_.isFixed(j))
            continue;
        double row = 0;
        for (std::uint32_t b : field_.barsOfKnot(j)) {
            const std::uint32_t other =
                field_.barEndA(b) == j ? field_.barEndB(b) : field_.barEndA(b);
            row += field_.barTensionStiffness(b) * (field_.isFixed(other) ? 1.0 : 2.0);
        }
        bound = std::max(bound, row * mobility_[j]);
    }
    return bound > 0 ? bound : 2.0;
}

double Rk4Run::firstStageScale() const {
    if (!options_.continuation)
        return 1.0;
    double minAxialStiffness = std::numeric_limits<double>::infinity(); // EA, N
    for (std::size_t b = 0; b < field_.barCount(); ++b)
        minAxialStiffness =
            std::min(minAxialStiffness, system_.kTension[b] * system_.restLength[b]);
    const double meanHeldLoad =
        totalWeight(system_) / static_cast<double>(std::max<std::size_t>(fixedCount_, 1));
    const double floor = kPreviewLoadFactor * meanHeldLoad / minAxialStiffness;
    return std::min(1.0, std::max(options_.previewStiffnessScale, floor));
}

double Rk4Run::stageResidual() const {
    double worst = 0;
    for (const Partial& p : partials_)
        worst = std::max(worst, p.maxResidual);
    return stageFinite() ? worst : std::numeric_limits<double>::infinity();
}

bool Rk4Run::stageFinite() const {
    return std::all_of(partials_.begin(), partials_.end(),
                       [](const Partial& p) { return p.finite; });
}

/// The residual at the current scale for positions (one evaluation; no state change).
double Rk4Run::evaluateResidual(const Vec3* positions) {
    for (Partial& p : partials_)
        p = Partial{};
    forRange(field_.barCount(), [&](std::size_t b, std::size_t e, std::size_t) {
        field_.computeBars(positions, b, e);
    });
    forRange(field_.knotCount(), [&](std::size_t b, std::size_t e, std::size_t chunk) {
        Partial& partial = partials_[chunk];
        for (std::size_t j = b; j < e; ++j) {
            if (field_.isFixed(j))
                continue;
            const double r = field_.residualOf(j, field_.knotForce(j));
            partial.finite = partial.finite && std::isfinite(r);
            partial.maxResidual = std::max(partial.maxResidual, r);
        }
    });
    ++evaluations_;
    return stageResidual();
}

/// One stage of classical RK4 on dx/dt = M^-1 F (Eq. 7): evaluates Eq. 3 at the stage's
/// positions (x for stage 0) and prepares the next stage's; stage 3 advances x by step. Stage 0
/// also measures the residual of x. Returns false if a non-finite number appeared.
bool Rk4Run::rk4Stage(int stage, double step) {
    for (Partial& p : partials_)
        p = Partial{};
    const Vec3* at = stage == 0 ? x_.data() : stagePositions_.data();
    forRange(field_.barCount(),
             [&](std::size_t b, std::size_t e, std::size_t) { field_.computeBars(at, b, e); });
    forRange(field_.knotCount(), [&](std::size_t begin, std::size_t end, std::size_t chunk) {
        Partial& partial = partials_[chunk];
        for (std::size_t j = begin; j < end; ++j) {
            if (field_.isFixed(j))
                continue;
            const Vec3 force = field_.knotForce(j);
            const Vec3 velocity = force * mobility_[j]; // per unit step
            switch (stage) {
            case 0: {
                const double r = field_.residualOf(j, force);
                partial.finite = partial.finite && std::isfinite(r);
                partial.maxResidual = std::max(partial.maxResidual, r);
                rate_[j] = velocity;
                stagePositions_[j] = x_[j] + velocity * (0.5 * step);
                break;
            }
            case 1:
                rate_[j] += velocity * 2.0;
                stagePositions_[j] = x_[j] + velocity * (0.5 * step);
                break;
            case 2:
                rate_[j] += velocity * 2.0;
                stagePositions_[j] = x_[j] + velocity * step;
                break;
            default:
                rate_[j] += velocity;
                x_[j] += rate_[j] * (step / 6.0);
                partial.finite = partial.finite && x_[j].isFinite();
                break;
            }
        }
    });
    ++evaluations_;
    return stageFinite();
}

RelaxResult Rk4Run::run() {
    start_ = Clock::now();
    RelaxResult result;
    result.backend = "rk4";
    const double tolerance = options_.tolerance;

    double scale = 1.0;
    field_.setLoad(options_.wind, scale);
    double r = evaluateResidual(x_.data());
    std::int64_t steps = 0;

    // Continuation ladder s0, s0 f, ..., 1 with n equal geometric steps.
    double stageFactor = 1.0;
    if (freeCount_ > 0 && !(r < tolerance)) {
        scale = firstStageScale();
        if (scale < 1.0) {
            const double stages =
                std::ceil(std::log(1.0 / scale) / std::log(options_.continuationFactor) - 1e-9);
            stageFactor = std::pow(1.0 / scale, 1.0 / stages);
            field_.setLoad(options_.wind, scale);
        }
    }

    double stepFraction = 1.0; // of the stable step, after back-offs
    double checkpointResidual = std::numeric_limits<double>::infinity();
    std::int64_t sinceCheckpoint = 0, sinceBackOff = 0;
    double lastProgress = -std::numeric_limits<double>::infinity();
    double previousLogResidual = 0, previousProgressSeconds = -1;
    std::string stopReason;
    RelaxProgress progress;

    auto report = [&](double residualNow, double now) {
        progress.residual = residualNow;
        progress.steps = steps;
        progress.seconds = now;
        progress.stiffnessScale = scale;
        progress.positions = x_;
        progress.estimatedSecondsLeft = -1;
        if (scale == 1.0 && residualNow > 0 && std::isfinite(residualNow)) {
            const double logResidual = std::log(residualNow);
            if (previousProgressSeconds >= 0 && now > previousProgressSeconds) {
                const double rate =
                    (previousLogResidual - logResidual) / (now - previousProgressSeconds);
                if (rate > 0)
                    progress.estimatedSecondsLeft =
                        std::max(0.0, (logResidual - std::log(tolerance)) / rate);
            }
            previousLogResidual = logResidual;
            previousProgressSeconds = now;
        }
        if (options_.progress)
            options_.progress(progress);
    };

    // Back to the last good state with half the step ("diverged" when the step is too small).
    auto backOff = [&] {
        x_ = checkpoint_;
        stepFraction *= 0.5;
        sinceBackOff = 0;
        if (stepFraction < kMinStepFraction)
            stopReason = "diverged";
    };

    if (freeCount_ == 0)
        stopReason = "converged";
    while (stopReason.empty()) {
        const double step = stableStep_ * stepFraction / scale; // mobility is at scale 1
        const bool finite = rk4Stage(0, step);
        r = stageResidual();

        if (!finite || r > kBlowUpFactor * checkpointResidual) {
            backOff();
            continue;
        }
        if (sinceCheckpoint == 0 || sinceCheckpoint >= kCheckpointSteps) {
            checkpoint_ = x_;
            checkpointResidual = r;
            sinceCheckpoint = 0;
        }

        if (r < std::max(tolerance, scale < 1.0 ? kStageTolerance : 0.0)) {
            if (scale == 1.0) {
                stopReason = "converged";
                break;
            }
            // Next continuation stage: stiffen and measure again from the same positions.
            scale = scale * stageFactor > 0.999999 ? 1.0 : scale * stageFactor;
            field_.setLoad(options_.wind, scale);
            sinceCheckpoint = 0;
            checkpointResidual = std::numeric_limits<double>::infinity();
            continue;
        }

        const double now = seconds();
        if (options_.cancel && options_.cancel->load(std::memory_order_relaxed))
            stopReason = "cancelled";
        else if (now >= options_.maxSeconds)
            stopReason = "time limit";
        else if (options_.maxSteps >= 0 && steps >= options_.maxSteps)
            stopReason = "step limit";
        if (!stopReason.empty())
            break;
        if (now - lastProgress >= options_.progressInterval) {
            report(r, now);
            lastProgress = now;
        }

        const bool finiteStep = rk4Stage(1, step) && rk4Stage(2, step) && rk4Stage(3, step);
        ++steps;
        ++sinceCheckpoint;
        if (!finiteStep) {
            backOff();
            continue;
        }
        if (++sinceBackOff >= kRecoverSteps && stepFraction < 1.0) {
            stepFraction = std::min(1.0, stepFraction * 1.5);
            sinceBackOff = 0;
        }
    }

    // The answer is judged at the material's stiffness, on exactly the positions returned.
    std::copy(x_.begin(), x_.end(), system_.position.begin());
    scale = 1.0;
    field_.setLoad(options_.wind, scale);
    result.residual = evaluateResidual(x_.data());
    result.converged = result.residual < tolerance;
    if (result.converged) // a stop at a soft stage may still meet the tolerance at full stiffness
        stopReason = "converged";
    result.stopReason = stopReason;
    result.steps = steps;
    result.forceEvaluations = evaluations_;
    result.seconds = seconds();
    report(result.residual, result.seconds);
    return result;
}

} // namespace

void validate(const RelaxOptions& options) {
    auto fail = [](const std::string& name, double value, const std::string& allowed) {
        throw UserError("relax: " + name + " = " + formatNumber(value) + "; expected " + allowed);
    };
    if (!positiveFinite(options.tolerance))
        fail("tolerance", options.tolerance, "a finite number > 0");
    if (!positiveFinite(options.maxSeconds))
        fail("maxSeconds", options.maxSeconds, "a finite number of seconds > 0");
    if (options.maxSteps < -1)
        fail("maxSteps", static_cast<double>(options.maxSteps), "-1 (no limit) or a count >= 0");
    if (options.threads < 0)
        fail("threads", options.threads, "0 (automatic) or a count >= 1");
    if (!std::isfinite(options.progressInterval) || options.progressInterval < 0)
        fail("progressInterval", options.progressInterval, "a finite number of seconds >= 0");
    if (!positiveFinite(options.previewStiffnessScale) || options.previewStiffnessScale > 1)
        fail("previewStiffnessScale", options.previewStiffnessScale, "a number in (0, 1]");
    if (!std::isfinite(options.continuationFactor) || !(options.continuationFactor > 1))
        fail("continuationFactor", options.continuationFactor, "a finite number > 1");
    if (options.wind)
        validatedWindDirection(*options.wind);
}

RelaxResult Rk4Relaxer::relax(MassSpringSystem& system, const RelaxOptions& options) {
    validate(options);
    Rk4Run run(system, options);
    return run.run();
}

RelaxResult relaxRk4(MassSpringSystem& system, const RelaxOptions& options) {
    return Rk4Relaxer().relax(system, options);
}

} // namespace netsculpt
