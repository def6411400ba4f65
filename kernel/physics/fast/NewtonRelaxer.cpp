#include "physics/fast/NewtonRelaxer.h"

#include "model/Error.h"
#include "physics/Forces.h"
#include "physics/fast/Components.h"
#include "physics/fast/FocusRegion.h"
#include "physics/fast/NewtonAnalysis.h"
#include "physics/fast/NewtonRun.h"
#include "physics/fast/SupernodalCholesky.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace netsculpt {

namespace newton {

RelaxResult NewtonRun::run() {
    const double tolerance = options_.tolerance;
    setScale(1.0);
    residual_ = evaluate(x_);
    if (options_.startTensions.size() == system_.barCount() && !analysis_.freeKnots.empty() &&
        !(residual_ < tolerance))
        hintedStart(tolerance);

    // Stages: an optional soft one (cold start), then the material's stiffness.
    double softScale = 1.0;
    bool warm = false;
    const double ratio = axialToLoad();
    if (!analysis_.freeKnots.empty() && !(residual_ < tolerance)) {
        const bool hinted = stats_.hintIterations > 0;
        const StartStrain strain = startStrain();
        warm = isWarm(strain, hintKeptAt_ >= 0);
        if (options_.continuation && !warm) {
            softScale = softStageScale(ratio);
            if (hinted && strain.largest <= kEditStageMaxStrain) // an edited relaxed shape
                softScale = std::min(1.0, softScale * kStageFactor);
        }
    }
    stats_.softScale = softScale;
    const std::vector<Stage> stages = planStages(softScale, warm, ratio);

    if (analysis_.freeKnots.empty() || residual_ < tolerance)
        stopReason_ = "converged";
    bool slack = false;
    for (std::size_t stageIndex = 0; stageIndex < stages.size() && stopReason_.empty();
         ++stageIndex) {
        const Stage& stage = stages[stageIndex];
        // The first soft stage tells a slack net (bars in compression at its equilibrium) from
        // a taut one; only a slack one gets the stiffer compression and the damping after it.
        if (stageIndex == 1)
            slack = anyCompressed();
        const double blend = stageIndex > 0 && slack ? stage.blend : 0.0;
        if (stage.blend > 0 && stage.scale == 1.0 && blend == 0)
            continue;
        if (stageIndex > 0 && stage.scale < 1.0 && !slack) // a taut net goes to the material
            continue;
        if (stageIndex > 0 || stage.scale != 1.0) {
            // Tensions of the previous stage's equilibrium (or of the warm start) seed the
            // mixed stage; then the new stiffness.
            if (stage.mixed)
                elasticTensions();
            setScale(stage.scale);
            setCompression(blend);
            residual_ = evaluate(x_);
        } else if (stage.mixed) {
            elasticTensions();
        }
        if (stageIndex == 1 && slack) // later stages go on with the previous one's
            damping_ = kDampingStart;
        runStage(stage, stageIndex + 1 == stages.size(), slack);
        if (stageIndex + 1 < stages.size())
            stats_.softIterations = steps_;
    }
    return finish(tolerance);
}

/// The share of the bars stretched by more than kTautStrain at x_, and the largest strain.
StartStrain NewtonRun::startStrain() const {
    const std::size_t bars = system_.barCount();
    std::size_t taut = 0;
    StartStrain strain;
    for (std::size_t b = 0; b < bars; ++b) {
        const double e =
            distance(x_[system_.barA[b]], x_[system_.barB[b]]) / system_.restLength[b] - 1;
        taut += e > kTautStrain ? 1 : 0;
        strain.largest = std::max(strain.largest, e);
    }
    strain.tautShare = bars > 0 ? static_cast<double>(taut) / static_cast<double>(bars) : 1.0;
    return strain;
}

/// Whether the start is warm: at least kWarmTautShare of the bars stretched by more than
/// kTautStrain, none by more than kWarmMaxStrain, and, unless the start is the state of hinted
/// iterations that was kept (`hintKept`), the residual at most kWarmMaxResidual.
bool NewtonRun::isWarm(const StartStrain& strain, bool hintKept) const {
    return strain.tautShare >= kWarmTautShare && strain.largest <= kWarmMaxStrain &&
           (hintKept || residual_ <= kWarmMaxResidual);
}

/// The softest bar's EA over the mean load per held knot, at scale 1.
double NewtonRun::axialToLoad() const {
    double minAxial = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < system_.barCount(); ++b)
        minAxial = std::min(minAxial, system_.kTension[b] * system_.restLength[b]);
    const std::size_t held = system_.knotCount() - analysis_.freeKnots.size();
    const double meanHeldLoad =
        totalWeight(system_) / static_cast<double>(std::max<std::size_t>(held, 1));
    return minAxial / meanHeldLoad;
}

/// The soft stage's stiffness scale for a cold start: the softest bar's EA brought to
/// kSoftLoadFactor times the mean load per held knot; 1 (no soft stage) when that would not
/// soften the material by at least kMaxSoftScale.
double NewtonRun::softStageScale(double axialToLoad) const {
    const double scale = std::min(1.0, kSoftLoadFactor / axialToLoad);
    return scale <= kMaxSoftScale ? scale : 1.0;
}

/// The stages of a run: from a soft scale below 1, that stage, the intermediate ones (slack
/// nets only, decided in run()), the compression blends; always the material's last, mixed
/// when the start is warm or the run comes from a softer stage.
std::vector<Stage> NewtonRun::planStages(double softScale, bool warm, double axialToLoad) const {
    const double tolerance = options_.tolerance;
    const auto bent = [&](double scale) { return scale * axialToLoad >= kBendAxialToLoad; };
    const auto third = [&](double scale) { return scale * axialToLoad >= kThirdOrderAxialToLoad; };
    std::vector<Stage> stages;
    if (softScale < 1.0) {
        const double softTolerance = std::max(kSoftTolerance, tolerance);
        stages.push_back({softScale, softTolerance, false, 0.0, bent(softScale), third(softScale)});
        for (double s = softScale * kStageFactor; s < 1 / std::sqrt(kStageFactor);
             s *= kStageFactor)
            stages.push_back({s, softTolerance, false, 0.0, bent(s), third(s), true});
        for (double blend : kFinalBlends)
            if (blend > 0)
                stages.push_back({1.0, std::max(kBlendTolerance, tolerance), true, blend,
                                  bent(1.0), third(1.0)});
    }
    stages.push_back({1.0, tolerance, warm || softScale < 1.0, 0.0, bent(1.0), third(1.0)});
    return stages;
}

/// Newton iterations at the current scale and compression law down to the stage's tolerance
/// (or a stop): mixed while the stage is and the residual keeps improving, else on the energy.
void NewtonRun::runStage(const Stage& stage, bool lastStage, bool slack) {
    // With wind the energy way only: the mixed iterations' carried tensions and the wind's turning
    // load together converge slowly (the default sculpture in a 0.1 N/m wind: 246 iterations
    // against 144).
    bool mixed = stage.mixed && !windy_;
    double best = residual_;
    int sinceBest = 0;
    const double minShift = lastStage && stage.mixed ? kFinalMinShift : kMinShift;
    shift_ = minShift;
    const std::int64_t stageStart = steps_;
    int exactPause = 0; // iterations left before the exact Hessian is tried again
    int roundingSteps = 0; // steps in a row that moved no knot beyond kRoundingUnits
    std::int64_t sinceRegion = stageStart; // the stage's start or its last focus region's end
    if (lastStage)
        keepIfBest();
    // Right after hinted iterations whose state was kept (RelaxOptions::focusAfterHint).
    if (lastStage && options_.focusAfterHint && steps_ == hintKeptAt_ && stage.scale == 1.0 &&
        !(residual_ < stage.tolerance) && relaxRegion(stage.tolerance, mixed)) {
        sinceRegion = steps_;
        keepIfBest();
    }
    // After a region in the loop: the next one waits kFocusAfter iterations, and the stall test
    // starts again from where the region left the whole.
    const auto afterRegion = [&] {
        sinceRegion = steps_;
        if (lastStage)
            keepIfBest();
        best = residual_;
        sinceBest = 0;
    };

    while (!(residual_ < stage.tolerance)) {
        if (stopRequested())
            break;
        report(false);
        const bool factored = assembleAndFactorize(mixed, exactPause);
        ++steps_;
        if (!factored) {
            stopReason_ = "diverged";
            break;
        }
        solve();
        if (windy_)
            correctStepForWind();
        bent_ = stage.bent;
        thirdOrder_ = stage.bent && stage.thirdOrder;
        if (bent_)
            bendStep();
        if (thirdOrder_)
            bendThirdOrder();
        if (stage.firstStepCapped && steps_ == stageStart + 1)
            capStepLength();
        double slope = 0;
        for (std::uint32_t j : analysis_.freeKnots)
            slope += force_[j].dot(step_[j]);

        bool accepted = false;
        double fullChange = 0; // energy change of the full step (energy line search)
        const double alpha = searchLine(mixed, slope, best, accepted, fullChange);
        if (!accepted) {
            // No acceptable step along this direction: regularize more and try again from
            // the same positions.
            damping_ = std::max(damping_ * kDampingUp, kDampingMin);
            shift_ = std::max(shift_ * 10, kFailShift);
            if (shift_ > kMaxShift) {
                stopReason_ = "diverged";
                break;
            }
            residual_ = evaluate(x_);
            continue;
        }
        if (alpha < kSmallStep && steps_ > stageStart + 1) // a poor model: regularize more
            shift_ = std::max(shift_ * 10, lastStage ? kLastSmallStepShift : kFailShift);
        const double moved = takeStep(alpha, mixed);
        residual_ = evaluate(x_);
        if (lastStage)
            keepIfBest();
        roundingSteps = moved <= kRoundingUnits ? roundingSteps + 1 : 0;
        if (lastStage && roundingSteps >= kRoundingPatience && !(residual_ < stage.tolerance)) {
            stopReason_ = "precision limit";
            break;
        }
        if (steps_ - sinceRegion >= kFocusAfter && !(residual_ < stage.tolerance) &&
            relaxRegion(stage.tolerance, mixed)) {
            afterRegion();
            continue;
        }
        // A full step lowers the shift when its model was good: mixed (no energy measured), or
        // the energy fell by at least kShiftDownRatio of the model's half slope.
        const bool goodModel = mixed || -fullChange >= kShiftDownRatio * 0.5 * slope;
        if (alpha >= 1.0 && goodModel)
            shift_ = std::max(shift_ * 0.1, minShift);
        // With wind too, though its prediction assumes (H + D) p = F and a wind step solves with
        // G as well: without it the runs from rest took 5-25 % more steps (the free tube in
        // 0.5 N/m 670 against 588).
        if (!mixed && slack)
            adaptDamping(alpha, slope, fullChange);
        if (mixed) {
            if (residual_ < best) {
                best = residual_;
                sinceBest = 0;
            } else if (++sinceBest >= kMixedPatience) {
                mixed = false; // stalled: the energy line search always makes progress
                if (lastStage && relaxRegion(stage.tolerance, mixed)) { // FocusRegion.h
                    ++stats_.stallFocusRegions;
                    afterRegion();
                }
            }
        }
    }
}

/// The Newton matrix at x_, factorized: the exact Hessian first (a slack bar's negative
/// geometric stiffness included: near a stable equilibrium with slack bars only it converges
/// quadratically), the projected one when that is not positive definite (then for kExactPause
/// iterations), the shift raised while the factorization fails. False: it never succeeded.
bool NewtonRun::assembleAndFactorize(bool mixed, int& exactPause) {
    bool exact = exactPause == 0;
    if (exactPause > 0)
        --exactPause;
    assemble(mixed, exact);
    bool ok = factorize();
    if (!ok && exact) {
        exactPause = kExactPause;
        assemble(mixed, false);
        ok = factorize();
    }
    while (!ok && shift_ < kMaxShift) {
        shift_ = std::max(shift_ * 10, kFailShift);
        ok = factorize();
    }
    return ok;
}

/// The step length along the step's path (displacement()): mixed, the first halving whose
/// residual stays below kMixedGrowth times the stage's best; else Armijo on the energy (with
/// wind, its load frozen at x_) with safeguarded quadratic interpolation (fullChange: the
/// full step's energy change), then expandStep when the step is bent. accepted: false when no
/// length passed (the energy way also when slope <= 0).
double NewtonRun::searchLine(bool mixed, double slope, double best, bool& accepted,
                             double& fullChange) {
    double alpha = 1;
    if (mixed) {
        for (int k = 0; k < kMaxBacktracks && !accepted; ++k, alpha *= 0.5) {
            for (std::uint32_t j : analysis_.freeKnots)
                trial_[j] = x_[j] + displacement(j, alpha);
            const double r = evaluate(trial_);
            accepted = r < kMixedGrowth * best;
            if (accepted)
                break;
        }
    } else if (slope > 0) {
        // With wind the energy is measured with the wind's load frozen where the step starts
        // (it has no potential): a step that lowers it moves towards the equilibrium under that
        // load, and the next step takes the wind where the net then is.
        if (windy_)
            field_.freezeWind(x_);
        for (int k = 0; k < kMaxBacktracks; ++k) {
            const double change = energyChange(alpha);
            if (k == 0)
                fullChange = change;
            if (std::isfinite(change) && change <= -kArmijo * alpha * slope) {
                accepted = true;
                break;
            }
            // Minimiser of the parabola through E(0), E'(0) = -slope and E(alpha),
            // kept within [alpha / 10, alpha / 2].
            double next = 0.5 * alpha;
            if (std::isfinite(change)) {
                const double curvature = change + slope * alpha;
                if (curvature > 0)
                    next = std::clamp(slope * alpha * alpha / (2 * curvature), 0.1 * alpha,
                                      0.5 * alpha);
            }
            alpha = next;
        }
        // Not with wind: the frozen wind's energy is another function at every step, and steps
        // lengthened by it circled around the equilibrium (a split ring of long bars in 0.2 N/m).
        if (accepted && alpha == 1.0 && bent_ && !windy_ &&
            fullChange < -kExpandDecrease * slope)
            alpha = expandStep(slope, fullChange);
        field_.thawWind();
    }
    return alpha;
}

/// The longest of 2, 4, ... kMaxExpansion times a full step along the bent path up to which the
/// energy keeps falling (1 when twice is no lower).
double NewtonRun::expandStep(double slope, double fullChange) {
    double best = 1, bestChange = fullChange;
    for (double alpha = 2; alpha <= kMaxExpansion; alpha *= 2) {
        const double change = energyChange(alpha);
        if (!(std::isfinite(change) && change < bestChange && change <= -kArmijo * alpha * slope))
            break;
        best = alpha;
        bestChange = change;
    }
    return best;
}

/// Trust-region style update of the weight-scaled shift (slack nets, energy stages) from the
/// ratio of the full step's actual to predicted decrease (model: E - F.p + 1/2 p.H p, with
/// (H + D) p = F, so the prediction is 1/2 (F.p + p.D p)).
void NewtonRun::adaptDamping(double alpha, double slope, double fullChange) {
    double damped = 0;
    if (damping_ > 0)
        for (std::size_t f = 0; f < dampingUnit_.size(); ++f) {
            const Vec3& p = step_[analysis_.freeKnots[f]];
            damped += damping_ * dampingUnit_[f] * p.dot(p);
        }
    const double predicted = 0.5 * (slope + damped);
    const double ratio = predicted > 0 ? -fullChange / predicted : 0.0;
    if (alpha >= 1.0 && ratio > kRatioGood)
        damping_ = damping_ * kDampingDown < kDampingMin ? 0.0 : damping_ * kDampingDown;
    else if (alpha < kDampingCut || ratio < kRatioPoor)
        damping_ = std::max(damping_ * kDampingUp, kDampingMin);
}

/// The result: the positions returned (the last stage's best state when stopped early),
/// judged by the project's own measure on exactly them.
RelaxResult NewtonRun::finish(double tolerance) {
    if (stopReason_.empty())
        stopReason_ = "converged";
    else if (bestResidual_ < residual_)
        x_ = bestX_;

    // The answer is judged by the project's own measure on exactly the positions returned.
    for (std::uint32_t j : analysis_.freeKnots)
        if (!x_[j].isFinite()) // cannot happen: only finite trial states are accepted
            x_[j] = system_.position[j];
    std::copy(x_.begin(), x_.end(), system_.position.begin());
    RelaxResult result;
    result.backend = "fast";
    // residual(system_, options_.wind), on the field: the material's law at scale 1.
    setCompression(0.0);
    setScale(1.0);
    field_.evaluate(x_, force_, pool_.get());
    ++evaluations_;
    result.residual = field_.maxResidual(force_);
    result.converged = result.residual < tolerance;
    if (stopReason_ == "converged" && !result.converged)
        stopReason_ = "diverged";
    result.stopReason = stopReason_;
    result.steps = steps_;
    result.forceEvaluations = evaluations_;
    result.seconds = secondsSince(start_);
    stats_.iterations = steps_;
    residual_ = result.residual;
    report(true);
    return result;
}

} // namespace newton

namespace {

using newton::Clock;
using newton::NewtonRun;
using newton::secondsSince;

const char* orderingName(SupernodalCholesky::Ordering ordering) {
    switch (ordering) {
    case SupernodalCholesky::Ordering::Amd:
        return "AMD";
    case SupernodalCholesky::Ordering::Metis:
        return "METIS";
    case SupernodalCholesky::Ordering::Geometric:
        return "geometric";
    }
    return "";
}

} // namespace

void newton::checkStart(const MassSpringSystem& system, const RelaxOptions& options) {
    const std::size_t knots = system.knotCount();
    std::size_t fixedCount = 0;
    for (std::size_t j = 0; j < knots; ++j) {
        if (!system.position[j].isFinite())
            throw UserError("mass-spring system: knot " + std::to_string(j) +
                            " has a non-finite position");
        fixedCount += system.fixed[j] ? 1 : 0;
    }
    if (!options.startTensions.empty()) {
        if (options.startTensions.size() != system.barCount())
            throw UserError("relax: startTensions has " +
                            std::to_string(options.startTensions.size()) +
                            " values; expected none or one per bar (" +
                            std::to_string(system.barCount()) + ")");
        for (std::size_t b = 0; b < system.barCount(); ++b)
            if (!std::isfinite(options.startTensions[b]))
                throw UserError("relax: startTensions[" + std::to_string(b) +
                                "] is not finite; expected a tension in N");
    }
    if (fixedCount == 0 && knots > 0)
        throw UserError("mass-spring system: no knot is fixed, so the net has no equilibrium "
                        "(it would fall)");
}

FastRelaxer::FastRelaxer() = default;
FastRelaxer::~FastRelaxer() = default;

RelaxResult FastRelaxer::relax(MassSpringSystem& system, const RelaxOptions& options) {
    const auto start = Clock::now();
    validate(options);
    const auto components = freeComponents(system);
    if (components.size() <= 1)
        return relaxConnected(system, options, start);
    return relaxParts(system, options, components, start);
}

RelaxResult FastRelaxer::relaxConnected(MassSpringSystem& system, const RelaxOptions& options,
                                        Clock::time_point start) {
    // Validates the system (UserError naming the first problem): a system of the analysis's
    // topology in its force field, any other in a new one.
    const bool reuse = analysis_ && analysis_->matches(system);
    std::optional<ForceField> fresh;
    if (reuse)
        analysis_->field.setLaw(system);
    else
        fresh.emplace(system);
    newton::checkStart(system, options);

    statistics_ = NewtonStatistics{};
    if (reuse) {
        statistics_.reusedAnalysis = true;
    } else {
        const auto t0 = Clock::now();
        if (analysis_) {
            // A new topology (rows added, say): the previous one's storage is reused.
            try {
                analysis_->field = std::move(*fresh);
                analysis_->analyse(system);
            } catch (...) {
                analysis_.reset();
                throw;
            }
        } else {
            analysis_ = std::make_unique<NewtonAnalysis>(system, std::move(*fresh));
        }
        statistics_.analysisSeconds = secondsSince(t0);
    }
    statistics_.factorFlops = analysis_->cholesky.factorFlops();
    statistics_.ordering = orderingName(analysis_->cholesky.ordering());
    NewtonRun::RegionRelax regions;
    if (focusRegions_)
        regions = [this, &system, &options, start](const std::vector<std::uint32_t>& region,
                                                   double tolerance, double blend, double scale,
                                                   std::int64_t stepsBefore) {
            return relaxRegion(system, options, start, region, tolerance, blend, scale,
                               stepsBefore);
        };
    NewtonRun run(system, options, *analysis_, statistics_, start, regions);
    run.shareCores(sharedCores_);
    return run.run();
}

RelaxResult relaxFast(MassSpringSystem& system, const RelaxOptions& options) {
    return FastRelaxer().relax(system, options);
}

} // namespace netsculpt
