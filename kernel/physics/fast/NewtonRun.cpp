#include "physics/fast/NewtonRun.h"

#include "physics/fast/FocusRegion.h"
#include "physics/fast/PathLength.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace netsculpt::newton {

NewtonRun::NewtonRun(MassSpringSystem& system, const RelaxOptions& options,
                     NewtonAnalysis& analysis, NewtonStatistics& statistics,
                     Clock::time_point start, RegionRelax regions)
    : system_(system), options_(options), analysis_(analysis), stats_(statistics), start_(start),
      field_(analysis.field), x_(analysis.x), trial_(analysis.trial), force_(analysis.force),
      step_(analysis.step), bend_(analysis.bend), bendThird_(analysis.bendThird),
      tension_(analysis.tension),
      kCompression_(analysis.kCompression),
      barBlock_(analysis.barBlock), values_(analysis.values), rhs_(analysis.rhs),
      linearResidual_(analysis.linearResidual),
      barTerm_(analysis.barTerm), weightOf_(analysis.weightOf),
      dampingUnit_(analysis.dampingUnit), bestX_(analysis.bestX) {
    field_.setLoad(options.wind, 1.0);
    windy_ = options.wind && options.wind->pressure > 0;
    pool_ = relaxationPool(options.threads, field_.barCount());
    regions_ = std::move(regions);

    const std::size_t knots = system.knotCount(), bars = system.barCount();
    x_ = system.position;
    trial_ = x_;
    force_.assign(knots, Vec3{});
    step_.assign(knots, Vec3{});
    bend_.assign(knots, Vec3{});
    bendThird_.assign(knots, Vec3{});
    tension_.assign(bars, 0.0);
    kCompression_ = system.kCompression;
    rhs_.assign(3 * analysis.freeKnots.size(), 0.0);
    barTerm_.assign(bars, 0.0);
    weightOf_.resize(knots);
    bestX_.clear();
    const double g = system.gravity.norm();
    for (std::size_t j = 0; j < knots; ++j)
        weightOf_[j] = system.mass[j] * g;
    double restSum = 0;
    for (double rest : system.restLength)
        restSum += rest;
    meanRest_ = bars > 0 && restSum > 0 ? restSum / static_cast<double>(bars) : 1.0;
    dampingUnit_.resize(analysis.freeKnots.size());
    for (std::size_t f = 0; f < analysis.freeKnots.size(); ++f)
        dampingUnit_[f] = weightOf_[analysis.freeKnots[f]] / meanRest_;
}


/// Eq. 3 at `at` for the current scale into force_; returns the max residual over free knots
/// (+inf if any is not finite).
double NewtonRun::evaluate(const std::vector<Vec3>& at) {
    field_.evaluate(at, force_, pool_.get());
    ++evaluations_;
    double worst = 0;
    for (std::uint32_t j : analysis_.freeKnots) {
        const double r = field_.residualOf(j, force_[j]);
        if (!std::isfinite(r))
            return std::numeric_limits<double>::infinity();
        worst = std::max(worst, r);
    }
    return worst;
}

void NewtonRun::setScale(double scale) {
    scale_ = scale;
    field_.setLoad(options_.wind, scale);
}

/// Compression stiffness max(k_c, blend k_s) (blend 0: the material's), force field included.
void NewtonRun::setCompression(double blend) {
    if (blend == compressionBlend_)
        return;
    compressionBlend_ = blend;
    for (std::size_t b = 0; b < system_.barCount(); ++b)
        kCompression_[b] = std::max(system_.kCompression[b], blend * system_.kTension[b]);
    field_.setCompressionStiffness(kCompression_);
}

/// Whether some bar whose compression stiffness differs from its tension one is shorter than its
/// rest length at x_.
bool NewtonRun::anyCompressed() const {
    for (std::size_t b = 0; b < system_.barCount(); ++b)
        if (system_.kCompression[b] != system_.kTension[b] &&
            distance(x_[system_.barA[b]], x_[system_.barB[b]]) < system_.restLength[b])
            return true;
    return false;
}

/// tension_ = s k (l - l_eq) at x_: the elastic tensions at the current scale.
void NewtonRun::elasticTensions() {
    forRange(system_.barCount(), [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t b = begin; b < end; ++b) {
            const double l = distance(x_[system_.barA[b]], x_[system_.barB[b]]);
            const double extension = l - system_.restLength[b];
            tension_[b] = stiffness(b, extension) * extension;
        }
    });
}

/// The Newton matrix at x_: per bar k u u^T + q (I - u u^T) (q = t / l >= 0, the positive part
/// of the geometric stiffness; t = k (l - l_eq), or the tension estimate in the mixed stage),
/// summed per knot in the fixed order of ForceField::barsOfKnot.
void NewtonRun::assemble(bool mixed, bool exact) {
    const std::size_t bars = system_.barCount();
    forRange(bars, [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t b = begin; b < end; ++b) {
            const Vec3 d = x_[system_.barB[b]] - x_[system_.barA[b]];
            const double l = d.norm();
            const double extension = l - system_.restLength[b];
            const double k = stiffness(b, extension);
            double* h = &barBlock_[9 * b];
            if (!(l > 0)) { // no direction: isotropic, keeps the matrix definite
                for (int i = 0; i < 9; ++i)
                    h[i] = i % 4 == 0 ? k : 0.0;
                continue;
            }
            const double t = mixed ? tension_[b] : k * extension;
            const double q = (exact ? t : std::max(t, 0.0)) / l;
            const double u[3] = {d.x / l, d.y / l, d.z / l};
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    h[3 * i + j] = (k - q) * u[i] * u[j] + (i == j ? q : 0.0);
        }
    });
    const std::size_t freeCount = analysis_.freeKnots.size();
    forRange(freeCount, [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t f = begin; f < end; ++f) {
            double sum[9] = {};
            for (std::uint32_t b : field_.barsOfKnot(analysis_.freeKnots[f]))
                for (int i = 0; i < 9; ++i)
                    sum[i] += barBlock_[9 * b + i];
            std::copy(sum, sum + 9, &values_[9 * f]);
        }
    });
    // Off-diagonal blocks: -H_b (bars in increasing order, so a shared block sums in order).
    const std::size_t pairBase = 9 * freeCount;
    std::fill(values_.begin() + pairBase, values_.end(), 0.0);
    for (std::size_t b = 0; b < bars; ++b) {
        const std::int64_t p = analysis_.barPair[b];
        if (p >= 0)
            for (int i = 0; i < 9; ++i)
                values_[pairBase + 9 * static_cast<std::size_t>(p) + static_cast<std::size_t>(i)] -=
                    barBlock_[9 * b + static_cast<std::size_t>(i)];
    }
    double trace = 0;
    for (std::size_t f = 0; f < freeCount; ++f)
        trace += values_[9 * f] + values_[9 * f + 4] + values_[9 * f + 8];
    if (!mixed && damping_ > 0)
        for (std::size_t f = 0; f < freeCount; ++f)
            for (int i : {0, 4, 8})
                values_[9 * f + static_cast<std::size_t>(i)] += damping_ * dampingUnit_[f];
    meanDiagonal_ =
        freeCount > 0 && trace > 0 ? trace / (3.0 * static_cast<double>(freeCount)) : 1.0;
}

bool NewtonRun::factorize() {
    const auto t0 = Clock::now();
    const bool ok = analysis_.cholesky.factorize(
        values_, shift_ * meanDiagonal_, pool_.get(),
        single_ ? SupernodalCholesky::Precision::Single : SupernodalCholesky::Precision::Double);
    stats_.factorSeconds += secondsSince(t0);
    analysis_.factorStiffness = ok ? meanStiffness() : 0;
    analysis_.reusedIterations = 0;
    ++stats_.factorizations;
    if (single_)
        ++stats_.singleFactorizations;
    if (!ok)
        ++stats_.failedFactorizations;
    return ok;
}

/// step_ = (H + mu I)^-1 F at the free knots (zero at fixed ones).
void NewtonRun::solve() {
    const std::size_t freeCount = analysis_.freeKnots.size();
    for (std::size_t f = 0; f < freeCount; ++f) {
        const Vec3& F = force_[analysis_.freeKnots[f]];
        rhs_[3 * f] = F.x;
        rhs_[3 * f + 1] = F.y;
        rhs_[3 * f + 2] = F.z;
    }
    solveInto(step_);
}

/// out = (H + mu I)^-1 rhs_ at the free knots, with the current factor.
void NewtonRun::solveInto(std::vector<Vec3>& out) {
    const auto t0 = Clock::now();
    analysis_.cholesky.solve(rhs_, pool_.get());
    for (std::size_t f = 0; f < analysis_.freeKnots.size(); ++f)
        out[analysis_.freeKnots[f]] = Vec3{rhs_[3 * f], rhs_[3 * f + 1], rhs_[3 * f + 2]};
    stats_.solveSeconds += secondsSince(t0);
}

/// out = (H + mu I) p at the free knots (3 per free knot), p = step_ and H as assembled in
/// values_ (the diagonal blocks, then the pairs' blocks).
void NewtonRun::multiplyStep(std::vector<double>& out) const {
    multiply([&](std::size_t f) { return step_[analysis_.freeKnots[f]]; }, out);
}

/// A step solved with a single-precision factor, refined in double: r = F - (H + mu I) p, then
/// p += (H + mu I)^-1 r with the same factor, at most kSingleRefinements times, until every free
/// knot's r is within kSingleAccuracy times the tolerance of its weight (the step then moves the
/// residual as a double one would, to that much). False when it is not.
bool NewtonRun::refineSingleStep(double tolerance) {
    const std::size_t freeCount = analysis_.freeKnots.size();
    std::vector<double>& r = linearResidual_;
    r.resize(3 * freeCount);
    for (int k = 0;; ++k) {
        multiplyStep(r);
        for (std::size_t f = 0; f < freeCount; ++f) {
            const Vec3 left =
                force_[analysis_.freeKnots[f]] - Vec3{r[3 * f], r[3 * f + 1], r[3 * f + 2]};
            rhs_[3 * f] = left.x;
            rhs_[3 * f + 1] = left.y;
            rhs_[3 * f + 2] = left.z;
        }
        if (linearResidualWithin(rhs_, tolerance))
            return true;
        if (k == kSingleRefinements)
            return false;
        solveInto(bend_); // the correction, in a vector free until the step is bent
        for (std::uint32_t j : analysis_.freeKnots)
            step_[j] += bend_[j];
    }
}

/// Whether every free knot's linear residual in `r` (3 per free knot) is within kSingleAccuracy
/// times the tolerance of its weight: a step solved so moves the residual as an exact one would,
/// to that much.
bool NewtonRun::linearResidualWithin(const std::vector<double>& r, double tolerance) const {
    for (std::size_t f = 0; f < analysis_.freeKnots.size(); ++f) {
        const Vec3 left{r[3 * f], r[3 * f + 1], r[3 * f + 2]};
        if (!(left.norm() <= kSingleAccuracy * tolerance * weightOf_[analysis_.freeKnots[f]]))
            return false;
    }
    return true;
}

/// bend_ = the correction c that undoes, to second order, the stretch a full step p causes by
/// turning bars: (H + mu I) c = -sum_b k_b r_b grad l_b, r_b = (|dp|^2 - (u . dp)^2) / l the second
/// derivative of bar b's length along p (dp its ends' relative step, u its direction), with the
/// factor of the step.
void NewtonRun::bendStep() {
    forRange(system_.barCount(), [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t b = begin; b < end; ++b) {
            const std::uint32_t a = system_.barA[b], e = system_.barB[b];
            const Vec3 d = x_[e] - x_[a];
            const double l = d.norm();
            const Vec3 dp = step_[e] - step_[a];
            const double along = l > 0 ? d.dot(dp) / l : 0.0;
            const double k = stiffness(b, l - system_.restLength[b]);
            barTerm_[b] = l > 0 ? k * (dp.dot(dp) - along * along) / (l * l) : 0.0; // k r_b / l
        }
    });
    solveBarTerms(bend_);
}

/// bendThird_ = the correction e that undoes, to third order, the stretch the path
/// x + a p + a^2 / 2 c still causes: (H + mu I) e = -sum_b k_b s_b grad l_b, s_b the third
/// derivative of bar b's length along that path at a = 0, with the factor of the step
/// (NewtonRun.h: kThirdOrderAxialToLoad).
void NewtonRun::bendThirdOrder() {
    forRange(system_.barCount(), [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t b = begin; b < end; ++b) {
            const std::uint32_t a = system_.barA[b], e = system_.barB[b];
            const Vec3 d = x_[e] - x_[a];
            const double l = d.norm();
            if (!(l > 0)) {
                barTerm_[b] = 0;
                continue;
            }
            const double third =
                lengthThirdDerivative(d, step_[e] - step_[a], bend_[e] - bend_[a]);
            barTerm_[b] = stiffness(b, l - system_.restLength[b]) * third / l; // k s_b / l
        }
    });
    solveBarTerms(bendThird_);
}

/// The step's path shortened so that its full step moves no knot further than kFirstStepCap
/// mean rest lengths (unchanged when it already moves none that far).
void NewtonRun::capStepLength() {
    double largest = 0;
    for (std::uint32_t j : analysis_.freeKnots)
        largest = std::max(largest, displacement(j, 1.0).norm());
    const double cap = kFirstStepCap * meanRest_;
    if (!(largest > cap))
        return;
    for (std::uint32_t j : analysis_.freeKnots)
        shortenPath(step_[j], bend_[j], bendThird_[j], cap / largest);
}

/// out = (H + mu I)^-1 (-sum_b barTerm_[b] l_b grad l_b) with the current factor: per free knot j,
/// the sum over its bars of (x_other - x_j) barTerm_[b], in the fixed order of
/// ForceField::barsOfKnot.
void NewtonRun::solveBarTerms(std::vector<Vec3>& out) {
    const std::size_t freeCount = analysis_.freeKnots.size();
    forRange(freeCount, [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t f = begin; f < end; ++f) {
            const std::uint32_t j = analysis_.freeKnots[f];
            Vec3 sum{};
            for (std::uint32_t b : field_.barsOfKnot(j)) {
                const std::uint32_t other =
                    system_.barA[b] == j ? system_.barB[b] : system_.barA[b];
                sum += (x_[other] - x_[j]) * barTerm_[b];
            }
            rhs_[3 * f] = sum.x;
            rhs_[3 * f + 1] = sum.y;
            rhs_[3 * f + 2] = sum.z;
        }
    });
    solveInto(out);
}

/// E(x + alpha step) - E(x) at the current scale, bar by bar in a form exact to the relative
/// accuracy of the change itself (so the line search still sees a decrease near convergence).
double NewtonRun::energyChange(double alpha) {
    forRange(system_.barCount(), [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t b = begin; b < end; ++b) {
            const std::uint32_t a = system_.barA[b], e = system_.barB[b];
            const Vec3 d = x_[e] - x_[a];
            const Vec3 change = displacement(e, alpha) - displacement(a, alpha);
            const Vec3 moved = d + change;
            const double l = d.norm(), lNew = moved.norm(), rest = system_.restLength[b];
            const double k = stiffness(b, l - rest);
            const double kNew = stiffness(b, lNew - rest);
            if (k == kNew && l + lNew > 0) {
                // l' - l = (d' + d) . (d' - d) / (l' + l), without cancellation.
                const double dl = change.dot(d * 2.0 + change) / (l + lNew);
                barTerm_[b] = 0.5 * k * dl * (lNew + l - 2 * rest);
            } else {
                barTerm_[b] = 0.5 * kNew * (lNew - rest) * (lNew - rest) -
                              0.5 * k * (l - rest) * (l - rest);
            }
        }
    });
    double change = 0;
    for (double term : barTerm_)
        change += term;
    for (std::uint32_t j : analysis_.freeKnots)
        change -= (system_.gravity * system_.mass[j]).dot(displacement(j, alpha));
    if (windy_) // the load searchLine froze
        for (std::uint32_t j : analysis_.freeKnots)
            change -= field_.knotWind(j).dot(displacement(j, alpha));
    return change;
}

namespace {

/// How far a knot moved from `before` to `after`, in units in the last place of its largest
/// coordinate (what rounding its position changes its bars' lengths by).
double movedUnits(const Vec3& before, const Vec3& after) {
    const double size = std::max({std::abs(before.x), std::abs(before.y), std::abs(before.z)});
    const double unit = std::nextafter(size, HUGE_VAL) - size;
    const Vec3 move = after - before;
    return std::max({std::abs(move.x), std::abs(move.y), std::abs(move.z)}) / unit;
}

/// hintedStart's rule: its state is kept when its residual under the material's law is below the
/// start's and kHintKeepResidual.
bool hintWorthKeeping(double materialResidual, double startResidual) {
    return materialResidual < startResidual && materialResidual < kHintKeepResidual;
}

} // namespace

/// x += alpha step; in the mixed stage the tension estimates follow the linearised lengths.
/// Returns the largest move of a knot in units in the last place of its coordinates.
double NewtonRun::takeStep(double alpha, bool mixed) {
    if (mixed)
        forRange(system_.barCount(), [&](std::size_t begin, std::size_t end, std::size_t) {
            for (std::size_t b = begin; b < end; ++b) {
                const std::uint32_t a = system_.barA[b], e = system_.barB[b];
                const Vec3 d = x_[e] - x_[a];
                const double l = d.norm();
                if (!(l > 0))
                    continue;
                const double linear = l + d.dot(step_[e] - step_[a]) * (alpha / l);
                const double extension = linear - system_.restLength[b];
                tension_[b] = stiffness(b, extension) * extension;
            }
        });
    // The positions before the step into trial_ (the line search is done with it) in a loop of
    // their own: with the copy and the measure in the step's loop, g++ contracts the step's
    // arithmetic differently and every run's last bits (and erratic iteration counts) move.
    for (std::uint32_t j : analysis_.freeKnots)
        trial_[j] = x_[j];
    for (std::uint32_t j : analysis_.freeKnots)
        x_[j] += displacement(j, alpha);
    double largest = 0;
    for (std::uint32_t j : analysis_.freeKnots)
        largest = std::max(largest, movedUnits(trial_[j], x_[j]));
    return largest;
}

/// Keeps x_ as the last stage's best state when its residual is the lowest so far.
void NewtonRun::keepIfBest() {
    if (!(residual_ < bestResidual_))
        return;
    bestResidual_ = residual_;
    bestX_ = x_;
}

/// A start with a tension hint: mixed Newton iterations at the run's scale whose tension
/// estimates start from the hint, and in which a bar that the hint has taut keeps its tension
/// stiffness when it is shorter than its rest length (after an edit that lengthens bars, a bar
/// that carried load is slack until the net has dropped; with k_c the linear model would stretch
/// it back a hundred times too far). The first iteration is then the tangent predictor of the edit
/// (the linear response of the hinted state to the new rest lengths, stiffnesses and loads) and
/// the next ones converge quadratically, as long as the bars the hint has taut are taut at the
/// equilibrium. At most kHintIterations, down to `tolerance`, until they stall (kHintStallRatio);
/// the state reached is kept only when its residual under the material's law is below the start's
/// and kHintKeepResidual, and the run goes on from there (the usual decision: a start near the
/// equilibrium is warm).
void NewtonRun::hintedStart(double tolerance) {
    const std::span<const double> hint = options_.startTensions;
    const std::vector<Vec3> start = x_;
    const double startResidual = residual_;
    bent_ = false;
    thirdOrder_ = false; // a hinted start's bent steps stop at the second order
    for (std::size_t b = 0; b < system_.barCount(); ++b)
        tension_[b] = hint[b];
    setHintedLaw();
    residual_ = evaluate(x_);
    double best = residual_;
    shift_ = kFinalMinShift;
    single_ = options_.singlePrecisionSteps;
    const auto factorizeShifted = [&] {
        bool factored = factorize();
        while (!factored && shift_ < kMaxShift) {
            shift_ = std::max(shift_ * 10, kFailShift);
            factored = factorize();
        }
        return factored;
    };
    const bool reused = previousFactorStep(tolerance); // a step kept: the net has moved
    const std::int64_t first = steps_;
    while (steps_ - first < kHintIterations && !(residual_ < tolerance) &&
           !hintStopRequested(reused || steps_ > first, startResidual)) {
        report(false);
        assemble(true, false);
        bool factored = factorizeShifted();
        ++steps_;
        if (factored)
            solve();
        if (factored && single_ && !refineSingleStep(tolerance)) {
            single_ = false; // rounding holds the steps back: the rest of the run in double
            factored = factorizeShifted();
            if (factored)
                solve();
        }
        if (!factored)
            break;
        // The first iteration is the edit's tangent predictor; the ones after it correct the bars
        // it turned, with bent steps (NewtonRun.h: a row step's three iterations become two).
        bent_ = steps_ - first > 1;
        if (bent_)
            bendStep();
        bool accepted = false;
        double fullChange = 0; // (not measured in a mixed search)
        const double alpha = searchLine(true, 0.0, best, accepted, fullChange);
        if (!accepted) {
            shift_ = std::max(shift_ * 10, kFailShift);
            residual_ = evaluate(x_);
            continue;
        }
        takeStep(alpha, true);
        residual_ = evaluate(x_);
        if (alpha == 1.0)
            shift_ = std::max(shift_ * 0.1, kFinalMinShift);
        const bool stalled = steps_ - first >= 2 && residual_ > kHintStallRatio * best;
        best = std::min(best, residual_);
        if (stalled)
            break;
    }
    single_ = false;
    stats_.hintIterations = steps_ - first;
    residual_ = materialLawResidual();
    if (hintWorthKeeping(residual_, startResidual)) {
        hintKeptAt_ = steps_;
    } else {
        x_ = start;
        residual_ = evaluate(x_);
    }
}

/// Back to the material's law; the residual under it at x_.
double NewtonRun::materialLawResidual() {
    setCompression(0.0);
    return evaluate(x_);
}

/// The hinted start's law: a bar the hint has taut keeps its tension stiffness when it is
/// shorter than its rest length.
void NewtonRun::setHintedLaw() {
    const std::span<const double> hint = options_.startTensions;
    for (std::size_t b = 0; b < system_.barCount(); ++b)
        kCompression_[b] = hint[b] > 0 ? std::max(system_.kCompression[b], system_.kTension[b])
                                       : system_.kCompression[b];
    field_.setCompressionStiffness(kCompression_);
    compressionBlend_ = -1; // no blend: setCompression sets every bar's law again
}

/// Whether the hinted iterations stop before the next one. With hintBeforeCancel a cancel ends
/// them only once one has been taken (`moved`) and its state would be kept (hintWorthKeeping),
/// unless cancelNow reads true; checking that costs two force passes, only while a cancel waits.
bool NewtonRun::hintStopRequested(bool moved, double startResidual) {
    if (!options_.hintBeforeCancel ||
        (options_.cancelNow && options_.cancelNow->load(std::memory_order_relaxed)))
        return stopRequested();
    if (stopRequested(false))
        return true;
    if (!moved || !(options_.cancel && options_.cancel->load(std::memory_order_relaxed)))
        return false;
    const double material = materialLawResidual();
    setHintedLaw();
    residual_ = evaluate(x_);
    return hintWorthKeeping(material, startResidual) && stopRequested();
}

bool NewtonRun::stopRequested(bool cancellable) {
    if (cancellable && options_.cancel && options_.cancel->load(std::memory_order_relaxed))
        stopReason_ = "cancelled";
    else if (secondsSince(start_) >= options_.maxSeconds)
        stopReason_ = "time limit";
    else if (options_.maxSteps >= 0 && steps_ >= options_.maxSteps)
        stopReason_ = "step limit";
    return !stopReason_.empty();
}

/// When few knots are left out of balance (a stage at the material's stiffness, force_ being at
/// x_): they and rings of their neighbours relaxed on their own under the stage's law, the rest
/// held (FocusRegion.h), and the stage goes on from there. False when there is no such region.
bool NewtonRun::relaxRegion(double tolerance, bool mixed) {
    if (!regions_)
        return false;
    const std::vector<std::uint32_t> region =
        focusRegion(field_, force_, analysis_.freeKnots, tolerance,
                    scale_ < 1.0 ? kSoftFocusShare : kFocusShare);
    if (region.empty())
        return false;
    std::copy(x_.begin(), x_.end(), system_.position.begin());
    // (Its force passes are over the region only: not counted as the whole system's.)
    steps_ += regions_(region, tolerance, compressionBlend_, scale_, steps_).steps;
    for (std::uint32_t j : region)
        x_[j] = system_.position[j];
    residual_ = evaluate(x_);
    if (mixed)
        elasticTensions();
    return true;
}

void NewtonRun::report(bool force) {
    if (!options_.progress)
        return;
    const double now = secondsSince(start_);
    if (!force && now - lastProgress_ < options_.progressInterval)
        return;
    lastProgress_ = now;
    RelaxProgress progress;
    progress.residual = residual_;
    progress.steps = steps_;
    progress.seconds = now;
    progress.stiffnessScale = scale_;
    progress.positions = x_;
    options_.progress(progress);
}

} // namespace netsculpt::newton
