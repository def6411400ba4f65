#include "physics/fast/NewtonRelaxer.h"

#include "model/Error.h"
#include "physics/Forces.h"
#include "physics/ThreadPool.h"
#include "physics/fast/HugePageArray.h"
#include "physics/fast/SupernodalCholesky.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <thread>

namespace netsculpt {

namespace {

// Soft stage: EA scaled down to kSoftLoadFactor times the mean load per held knot (strains of a
// few per cent at the top of a net; the same floor as RK4's first continuation stage). No soft
// stage when that would not soften the material by at least kMaxSoftScale.
constexpr double kSoftLoadFactor = 20;
constexpr double kMaxSoftScale = 0.1;
// Then, for a slack net only, stages kStageFactor times stiffer each (the last intermediate one
// at least sqrt(kStageFactor) below the material's): a tension-dominated net needs none (the jump
// from the soft stage to the material costs four or five mixed iterations), a slack one needs
// them because the shape of its slack parts changes with the stiffness. Each soft stage only has to bring the shape
// near the next one: it stops at kSoftTolerance.
constexpr double kStageFactor = 100;
constexpr double kSoftTolerance = 1e-1;
// A slack net (bars in compression at the first soft stage's equilibrium) is then taken to the
// material's stiffness first with compression stiffness max(k_c, blend k_s) for each blend of
// kFinalBlends (1: the energy has no kink at the rest length, so bars hovering at zero tension
// in the slack parts do not make Newton chatter), down to kBlendTolerance, and only then with
// the material's k_c (the compressed bars then shorten by ~1e-6 of a bar: one or two mixed
// iterations).
constexpr std::array<double, 1> kFinalBlends = {1};
constexpr double kBlendTolerance = 1e-3;
// Slack nets, energy stages after the first: a second Levenberg shift lambda_D D, D = diag(m_j |g|
// / mean rest length) (the geometric stiffness of a bar carrying one knot's weight, the scale of
// the soft modes of slack parts that the line search would otherwise cut the whole step for),
// driven like a trust region: starts at kDampingStart, is multiplied by kDampingDown after a full
// step whose energy decrease is more than kRatioGood of the model's (dropped below kDampingMin),
// and by kDampingUp (at least kDampingMin) when the step was cut below kDampingCut or the ratio
// is below kRatioPoor. It carries over from stage to stage.
constexpr double kDampingStart = 1;
constexpr double kDampingMin = 1e-3;
constexpr double kDampingUp = 4;
constexpr double kDampingDown = 0.1;
constexpr double kDampingCut = 0.5;
constexpr double kRatioGood = 0.75;
constexpr double kRatioPoor = 0.25;
// A start is warm (no soft stage) when at least this share of the bars is stretched by more
// than kTautStrain (the bars already carry the load; their tensions seed the mixed Newton) ...
constexpr double kWarmTautShare = 0.5;
constexpr double kTautStrain = 1e-9;
// ... and none is stretched by more than this (new knots placed far from their carried
// neighbours after an edit need the soft stage again).
constexpr double kWarmMaxStrain = 0.05;
// ... and the start's residual is below this: the forces are out of balance by at most a
// hundred times the knots' weights (rows added below a relaxed net are not; their weight, not
// yet carried, is a cold start in disguise).
constexpr double kWarmMaxResidual = 100;
// A start with a tension hint (RelaxOptions::startTensions) first gets at most this many mixed
// Newton iterations seeded with the hint (see NewtonRun::hintedStart); a small edit needs two or
// three, and a start the hint does not fit goes on to the usual decision after them.
constexpr int kHintIterations = 6;
// Line search: Armijo's sufficient decrease, at most kMaxBacktracks halvings (safeguarded
// quadratic interpolation).
constexpr double kArmijo = 1e-4;
constexpr int kMaxBacktracks = 30;
// Levenberg shift mu = lambda * (mean diagonal of the Newton matrix). lambda never goes below
// kMinShift (it keeps exactly singular directions, such as the out-of-plane motion of a planar
// slack net, factorizable), jumps to at least kFailShift when a factorization or a line search
// fails and grows tenfold per further failure; beyond kMaxShift the run has diverged. The last
// stage, when mixed (near an equilibrium), lets it fall to kFinalMinShift: kMinShift times the
// mean diagonal (the bars' axial stiffness) is a thousandth of the geometric stiffness of a bar
// carrying one knot, which would make the last iterations converge linearly at that rate
// instead of quadratically.
constexpr double kMinShift = 1e-10;
constexpr double kFinalMinShift = 1e-14;
constexpr double kFailShift = 1e-6;
constexpr double kMaxShift = 1e6;
// Mixed stage: a step is taken while the residual grows by less than kMixedGrowth; when the best
// residual has not improved for kMixedPatience iterations the stage falls back to the energy line
// search.
constexpr double kMixedGrowth = 10;
constexpr int kMixedPatience = 4;
// An accepted step shorter than this (a fraction of the Newton step) raises the shift (not on a
// stage's first iteration, whose direction is poor by nature from a cold start).
constexpr double kSmallStep = 0.2;
// After the exact Hessian was found indefinite, the projected one is used for this many
// iterations before the exact one is tried again.
constexpr int kExactPause = 3;
// Automatic thread count: at most one thread per this many bars.
constexpr std::size_t kAutoBarsPerThread = 4096;

using Clock = std::chrono::steady_clock;

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

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

} // namespace

/// The topology-dependent part of a run: the free numbering, the block pattern and its
/// factorization analysis, and the storage of a run (its force field, per-knot and per-bar
/// vectors, the Newton matrix): kept between calls for a system with the same topology, so that
/// a warm run (a drag step) allocates nothing and touches no fresh page.
struct NewtonAnalysis {
    std::vector<std::uint8_t> fixed;
    std::vector<std::uint32_t> barA, barB;

    std::vector<std::uint32_t> freeKnots;     ///< free index -> knot
    std::vector<std::int64_t> freeIndex;      ///< knot -> free index, -1 when fixed
    std::vector<std::int64_t> barPair;        ///< bar -> block pair, -1 when an end is fixed
    std::vector<std::array<std::uint32_t, 2>> pairs; ///< free indices of the blocks' nodes
    SupernodalCholesky cholesky;

    // A run's storage (NewtonRun's members of the same names). Every run sets what it reads: its
    // law into the field (ForceField::setLaw), its start into the vectors.
    ForceField field;
    std::vector<Vec3> x, trial, force, step, bestX;
    std::vector<double> tension, kCompression, rhs, barTerm, weightOf, dampingUnit;
    HugePageArray barBlock; ///< written whole by every assembly
    HugePageArray values;   ///< likewise

    bool matches(const MassSpringSystem& system) const {
        return system.fixed == fixed && system.barA == barA && system.barB == barB;
    }

    /// `checked`: the system's force field (built, so validated, by the caller).
    NewtonAnalysis(const MassSpringSystem& system, ForceField&& checked) : field(std::move(checked)) {
        analyse(system);
    }

    /// Analyses `system`'s topology (its force field is already in `field`), keeping the
    /// storage of the previous one where it is large enough (the factor's among it).
    void analyse(const MassSpringSystem& system) {
        fixed = system.fixed;
        barA = system.barA;
        barB = system.barB;
        const std::size_t knots = system.knotCount(), bars = system.barCount();
        freeKnots.clear();
        pairs.clear();
        freeIndex.assign(knots, -1);
        for (std::size_t j = 0; j < knots; ++j)
            if (!fixed[j]) {
                freeIndex[j] = static_cast<std::int64_t>(freeKnots.size());
                freeKnots.push_back(static_cast<std::uint32_t>(j));
            }
        // One block per pair of free knots joined by a bar (two bars between the same knots
        // share it), numbered in the order of their first bar. The pairs found so far are listed
        // by their lower free index (flat: a slot per bar, grouped by that index).
        barPair.assign(bars, -1);
        std::vector<std::uint32_t> slotStart(freeKnots.size() + 1, 0);
        for (std::size_t b = 0; b < bars; ++b) {
            const std::int64_t i = freeIndex[barA[b]], j = freeIndex[barB[b]];
            if (i >= 0 && j >= 0)
                ++slotStart[static_cast<std::size_t>(std::min(i, j)) + 1];
        }
        for (std::size_t f = 0; f < freeKnots.size(); ++f)
            slotStart[f + 1] += slotStart[f];
        std::vector<std::uint32_t> slotEnd(slotStart.begin(), slotStart.end() - 1);
        std::vector<std::uint32_t> slotPair(slotStart.back());
        pairs.reserve(slotStart.back());
        for (std::size_t b = 0; b < bars; ++b) {
            const std::int64_t i = freeIndex[barA[b]], j = freeIndex[barB[b]];
            if (i < 0 || j < 0)
                continue;
            const auto low = static_cast<std::size_t>(std::min(i, j));
            const auto high = static_cast<std::uint32_t>(std::max(i, j));
            std::uint32_t k = slotStart[low];
            while (k < slotEnd[low] && std::max(pairs[slotPair[k]][0], pairs[slotPair[k]][1]) != high)
                ++k;
            if (k == slotEnd[low]) {
                slotPair[slotEnd[low]++] = static_cast<std::uint32_t>(pairs.size());
                pairs.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
            }
            barPair[b] = slotPair[k];
        }
        // The free knots' positions (the start's) guide the ordering.
        std::vector<std::array<double, 3>> coordinates(freeKnots.size());
        for (std::size_t f = 0; f < freeKnots.size(); ++f) {
            const Vec3& p = system.position[freeKnots[f]];
            coordinates[f] = {p.x, p.y, p.z};
        }
        cholesky.analyse(freeKnots.size(), pairs, coordinates);
        barBlock.allocate(9 * bars);
        values.allocate(9 * (freeKnots.size() + pairs.size()));
    }
};

namespace {

/// One stage of a run: a stiffness scale, the residual it stops at, whether it starts mixed.
struct Stage {
    double scale;
    double tolerance;
    bool mixed;
    double blend; ///< compression stiffness max(k_c, blend k_s)
};

/// One relaxation: the Newton iteration and its bookkeeping.
class NewtonRun {
  public:
    NewtonRun(MassSpringSystem& system, const RelaxOptions& options, NewtonAnalysis& analysis,
              NewtonStatistics& statistics, Clock::time_point start);
    RelaxResult run();

  private:
    template <typename Body> void forRange(std::size_t count, Body&& body) {
        if (pool_)
            pool_->parallelFor(count, body);
        else if (count > 0)
            body(std::size_t{0}, count, std::size_t{0});
    }

    double evaluate(const std::vector<Vec3>& at);
    void setScale(double scale);
    void setCompression(double blend);
    bool anyCompressed() const;
    void elasticTensions();
    void assemble(bool mixed, bool exact);
    bool factorize();
    void solve();
    double energyChange(double alpha);
    double meritOf(const std::vector<Vec3>& at);
    void takeStep(double alpha, bool mixed);
    void hintedStart(double tolerance);
    bool isWarm() const;
    double softStageScale() const;
    std::vector<Stage> planStages(double softScale, bool warm) const;
    void runStage(const Stage& stage, bool lastStage, bool slack);
    bool assembleAndFactorize(bool mixed, int& exactPause);
    double searchLine(bool mixed, double slope, double best, bool& accepted, double& fullChange);
    void adaptDamping(double alpha, double slope, double fullChange);
    RelaxResult finish(double tolerance);
    bool stopRequested();
    void keepIfBest();
    void report(bool force);

    MassSpringSystem& system_;
    const RelaxOptions& options_;
    NewtonAnalysis& analysis_;
    NewtonStatistics& stats_;
    Clock::time_point start_;
    // The run's storage lives in the analysis (kept between calls on one topology).
    ForceField& field_;
    std::unique_ptr<ThreadPool> pool_;

    std::vector<Vec3>& x_;
    std::vector<Vec3>& trial_;
    std::vector<Vec3>& force_;
    std::vector<Vec3>& step_;
    std::vector<double>& tension_;      ///< mixed stage: the bars' tension estimates, N
    std::vector<double>& kCompression_; ///< the stage's compression stiffness per bar, N/m at scale 1
    HugePageArray& barBlock_;           ///< 9 per bar: its Hessian block
    HugePageArray& values_;             ///< the Newton matrix's blocks (SupernodalCholesky layout)
    std::vector<double>& rhs_;          ///< 3 per free knot
    std::vector<double>& barTerm_;      ///< per bar scratch for sums done in a fixed order
    std::vector<double>& weightOf_;     ///< m_j |g| per knot
    double scale_ = 1;
    double compressionBlend_ = 0;
    double residual_ = 0;            ///< at x_, current scale
    double shift_ = kMinShift;       ///< lambda of the Levenberg shift
    double damping_ = 0;             ///< lambda of the weight-scaled shift (energy stages)
    std::vector<double>& dampingUnit_; ///< per free knot: m_j |g| / (mean rest length), N/m
    double meanDiagonal_ = 1;
    bool windy_ = false;
    std::int64_t steps_ = 0, evaluations_ = 0;
    double lastProgress_ = -std::numeric_limits<double>::infinity();
    std::string stopReason_;
    // The last stage (the material's stiffness): its best state so far, returned when the run
    // stops before converging (its residual can rise and fall from one iteration to the next).
    std::vector<Vec3>& bestX_;
    double bestResidual_ = std::numeric_limits<double>::infinity();
};

NewtonRun::NewtonRun(MassSpringSystem& system, const RelaxOptions& options,
                     NewtonAnalysis& analysis, NewtonStatistics& statistics,
                     Clock::time_point start)
    : system_(system), options_(options), analysis_(analysis), stats_(statistics), start_(start),
      field_(analysis.field), x_(analysis.x), trial_(analysis.trial), force_(analysis.force),
      step_(analysis.step), tension_(analysis.tension), kCompression_(analysis.kCompression),
      barBlock_(analysis.barBlock), values_(analysis.values), rhs_(analysis.rhs),
      barTerm_(analysis.barTerm), weightOf_(analysis.weightOf),
      dampingUnit_(analysis.dampingUnit), bestX_(analysis.bestX) {
    field_.setLoad(options.wind, 1.0);
    windy_ = options.wind && options.wind->pressure > 0;
    int threads = options.threads;
    if (threads == 0) {
        const std::size_t hardware = std::max(1u, std::thread::hardware_concurrency());
        threads = static_cast<int>(
            std::clamp<std::size_t>(field_.barCount() / kAutoBarsPerThread, 1, hardware));
    }
    if (threads > 1)
        pool_ = std::make_unique<ThreadPool>(threads);

    const std::size_t knots = system.knotCount(), bars = system.barCount();
    x_ = system.position;
    trial_ = x_;
    force_.assign(knots, Vec3{});
    step_.assign(knots, Vec3{});
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
    const double meanRest = bars > 0 && restSum > 0 ? restSum / static_cast<double>(bars) : 1.0;
    dampingUnit_.resize(analysis.freeKnots.size());
    for (std::size_t f = 0; f < analysis.freeKnots.size(); ++f)
        dampingUnit_[f] = weightOf_[analysis.freeKnots[f]] / meanRest;
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
            tension_[b] = (extension > 0 ? system_.kTension[b] : kCompression_[b]) *
                          scale_ * extension;
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
            const double k =
                (extension > 0 ? system_.kTension[b] : kCompression_[b]) *
                scale_;
            double* h = &barBlock_[9 * b];
            if (!(l > 0)) { // no direction: isotropic, keeps the matrix definite
                for (int i = 0; i < 9; ++i)
                    h[i] = i % 4 == 0 ? k : 0.0;
                continue;
            }
            const double t =
                mixed ? tension_[b]
                      : (extension > 0 ? system_.kTension[b] : kCompression_[b]) * scale_ *
                            extension;
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
    meanDiagonal_ = freeCount > 0 && trace > 0 ? trace / (3.0 * static_cast<double>(freeCount)) : 1.0;
}

bool NewtonRun::factorize() {
    const auto t0 = Clock::now();
    const bool ok = analysis_.cholesky.factorize(values_, shift_ * meanDiagonal_, pool_.get());
    stats_.factorSeconds += secondsSince(t0);
    ++stats_.factorizations;
    if (!ok)
        ++stats_.failedFactorizations;
    return ok;
}

/// step_ = (H + mu I)^-1 F at the free knots (zero at fixed ones).
void NewtonRun::solve() {
    const auto t0 = Clock::now();
    const std::size_t freeCount = analysis_.freeKnots.size();
    for (std::size_t f = 0; f < freeCount; ++f) {
        const Vec3& F = force_[analysis_.freeKnots[f]];
        rhs_[3 * f] = F.x;
        rhs_[3 * f + 1] = F.y;
        rhs_[3 * f + 2] = F.z;
    }
    analysis_.cholesky.solve(rhs_, pool_.get());
    for (std::size_t f = 0; f < freeCount; ++f)
        step_[analysis_.freeKnots[f]] = Vec3{rhs_[3 * f], rhs_[3 * f + 1], rhs_[3 * f + 2]};
    stats_.solveSeconds += secondsSince(t0);
}

/// E(x + alpha step) - E(x) at the current scale, bar by bar in a form exact to the relative
/// accuracy of the change itself (so the line search still sees a decrease near convergence).
double NewtonRun::energyChange(double alpha) {
    forRange(system_.barCount(), [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t b = begin; b < end; ++b) {
            const std::uint32_t a = system_.barA[b], e = system_.barB[b];
            const Vec3 d = x_[e] - x_[a];
            const Vec3 change = (step_[e] - step_[a]) * alpha;
            const Vec3 moved = d + change;
            const double l = d.norm(), lNew = moved.norm(), rest = system_.restLength[b];
            const double k = (l > rest ? system_.kTension[b] : kCompression_[b]) * scale_;
            const double kNew = (lNew > rest ? system_.kTension[b] : kCompression_[b]) * scale_;
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
        change -= (system_.gravity * system_.mass[j]).dot(step_[j]) * alpha;
    return change;
}

/// Sum over free knots of (|F_j| / (m_j |g|))^2 at `at` (the wind's merit), force_ overwritten.
double NewtonRun::meritOf(const std::vector<Vec3>& at) {
    field_.evaluate(at, force_, pool_.get());
    ++evaluations_;
    double sum = 0;
    for (std::uint32_t j : analysis_.freeKnots) {
        const double r = force_[j].norm() / weightOf_[j];
        sum += r * r;
    }
    return std::isfinite(sum) ? sum : std::numeric_limits<double>::infinity();
}

/// x += alpha step; in the mixed stage the tension estimates follow the linearised lengths.
void NewtonRun::takeStep(double alpha, bool mixed) {
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
                tension_[b] = (extension > 0 ? system_.kTension[b] : kCompression_[b]) *
                              scale_ * extension;
            }
        });
    for (std::uint32_t j : analysis_.freeKnots)
        x_[j] += step_[j] * alpha;
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
/// equilibrium. At most kHintIterations, down to `tolerance`; the state reached is kept only when
/// its residual under the material's law is below the start's, and the run goes on from there
/// (the usual decision: a start near the equilibrium is warm).
void NewtonRun::hintedStart(double tolerance) {
    const std::span<const double> hint = options_.startTensions;
    const std::vector<Vec3> start = x_;
    const double startResidual = residual_;
    for (std::size_t b = 0; b < system_.barCount(); ++b) {
        tension_[b] = hint[b];
        kCompression_[b] = hint[b] > 0 ? std::max(system_.kCompression[b], system_.kTension[b])
                                       : system_.kCompression[b];
    }
    field_.setCompressionStiffness(kCompression_);
    residual_ = evaluate(x_);
    double best = residual_;
    shift_ = kFinalMinShift;
    const std::int64_t first = steps_;
    while (steps_ - first < kHintIterations && !(residual_ < tolerance) && !stopRequested()) {
        report(false);
        assemble(true, false);
        bool factored = factorize();
        while (!factored && shift_ < kMaxShift) {
            shift_ = std::max(shift_ * 10, kFailShift);
            factored = factorize();
        }
        ++steps_;
        if (!factored)
            break;
        solve();
        double alpha = 1;
        bool accepted = false;
        for (int k = 0; k < kMaxBacktracks && !accepted; ++k, alpha *= 0.5) {
            for (std::uint32_t j : analysis_.freeKnots)
                trial_[j] = x_[j] + step_[j] * alpha;
            accepted = evaluate(trial_) < kMixedGrowth * best;
            if (accepted)
                break;
        }
        if (!accepted) {
            shift_ = std::max(shift_ * 10, kFailShift);
            residual_ = evaluate(x_);
            continue;
        }
        takeStep(alpha, true);
        residual_ = evaluate(x_);
        if (alpha == 1.0)
            shift_ = std::max(shift_ * 0.1, kFinalMinShift);
        best = std::min(best, residual_);
    }
    stats_.hintIterations = steps_ - first;
    // Back to the material's law.
    compressionBlend_ = -1;
    setCompression(0.0);
    residual_ = evaluate(x_);
    if (!(residual_ < startResidual)) {
        x_ = start;
        residual_ = evaluate(x_);
    }
}

bool NewtonRun::stopRequested() {
    if (options_.cancel && options_.cancel->load(std::memory_order_relaxed))
        stopReason_ = "cancelled";
    else if (secondsSince(start_) >= options_.maxSeconds)
        stopReason_ = "time limit";
    else if (options_.maxSteps >= 0 && steps_ >= options_.maxSteps)
        stopReason_ = "step limit";
    return !stopReason_.empty();
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
    if (!analysis_.freeKnots.empty() && !(residual_ < tolerance)) {
        warm = isWarm();
        if (options_.continuation && !warm)
            softScale = softStageScale();
    }
    stats_.softScale = softScale;
    const std::vector<Stage> stages = planStages(softScale, warm);

    if (analysis_.freeKnots.empty() || residual_ < tolerance)
        stopReason_ = "converged";
    bool slack = false;
    for (std::size_t stageIndex = 0; stageIndex < stages.size() && stopReason_.empty(); ++stageIndex) {
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

/// Whether the start is warm: at least kWarmTautShare of the bars stretched by more than
/// kTautStrain, none by more than kWarmMaxStrain, and the residual at most kWarmMaxResidual.
bool NewtonRun::isWarm() const {
    const std::size_t bars = system_.barCount();
    std::size_t taut = 0;
    double maxStrain = 0;
    for (std::size_t b = 0; b < bars; ++b) {
        const double strain =
            distance(x_[system_.barA[b]], x_[system_.barB[b]]) / system_.restLength[b] - 1;
        taut += strain > kTautStrain ? 1 : 0;
        maxStrain = std::max(maxStrain, strain);
    }
    return static_cast<double>(taut) >= kWarmTautShare * static_cast<double>(bars) &&
           maxStrain <= kWarmMaxStrain && residual_ <= kWarmMaxResidual;
}

/// The soft stage's stiffness scale for a cold start: the softest bar's EA brought to
/// kSoftLoadFactor times the mean load per held knot; 1 (no soft stage) when that would not
/// soften the material by at least kMaxSoftScale.
double NewtonRun::softStageScale() const {
    double minAxial = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < system_.barCount(); ++b)
        minAxial = std::min(minAxial, system_.kTension[b] * system_.restLength[b]);
    const std::size_t held = system_.knotCount() - analysis_.freeKnots.size();
    const double meanHeldLoad =
        totalWeight(system_) / static_cast<double>(std::max<std::size_t>(held, 1));
    const double scale = std::min(1.0, kSoftLoadFactor * meanHeldLoad / minAxial);
    return scale <= kMaxSoftScale ? scale : 1.0;
}

/// The stages of a run: from a soft scale below 1, that stage, the intermediate ones (slack
/// nets only, decided in run()), the compression blends; always the material's last, mixed
/// when the start is warm or the run comes from a softer stage.
std::vector<Stage> NewtonRun::planStages(double softScale, bool warm) const {
    const double tolerance = options_.tolerance;
    std::vector<Stage> stages;
    if (softScale < 1.0) {
        stages.push_back({softScale, std::max(kSoftTolerance, tolerance), false, 0.0});
        for (double s = softScale * kStageFactor; s < 1 / std::sqrt(kStageFactor); s *= kStageFactor)
            stages.push_back({s, std::max(kSoftTolerance, tolerance), false, 0.0});
        for (double blend : kFinalBlends)
            if (blend > 0)
                stages.push_back({1.0, std::max(kBlendTolerance, tolerance), true, blend});
    }
    stages.push_back({1.0, tolerance, warm || softScale < 1.0, 0.0});
    return stages;
}

/// Newton iterations at the current scale and compression law down to the stage's tolerance
/// (or a stop): mixed while the stage is and the residual keeps improving, else on the energy.
void NewtonRun::runStage(const Stage& stage, bool lastStage, bool slack) {
    bool mixed = stage.mixed;
    double best = residual_;
    int sinceBest = 0;
    const double minShift = lastStage && stage.mixed ? kFinalMinShift : kMinShift;
    shift_ = minShift;
    const std::int64_t stageStart = steps_;
    int exactPause = 0; // iterations left before the exact Hessian is tried again
    if (lastStage)
        keepIfBest();

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
            shift_ = std::max(shift_ * 10, kFailShift);
        takeStep(alpha, mixed);
        residual_ = evaluate(x_);
        if (lastStage)
            keepIfBest();
        if (alpha == 1.0)
            shift_ = std::max(shift_ * 0.1, minShift);
        if (!mixed && !windy_ && slack)
            adaptDamping(alpha, slope, fullChange);
        if (mixed) {
            if (residual_ < best) {
                best = residual_;
                sinceBest = 0;
            } else if (++sinceBest >= kMixedPatience) {
                mixed = false; // stalled: the energy line search always makes progress
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

/// The step length along step_: mixed, the first halving whose residual stays below
/// kMixedGrowth times the stage's best; with wind, Armijo on the residual's merit; else Armijo
/// on the energy with safeguarded quadratic interpolation (fullChange: the full step's energy
/// change). accepted: false when no length passed (the energy way also when slope <= 0).
double NewtonRun::searchLine(bool mixed, double slope, double best, bool& accepted,
                             double& fullChange) {
    double alpha = 1;
    if (mixed) {
        for (int k = 0; k < kMaxBacktracks && !accepted; ++k, alpha *= 0.5) {
            for (std::uint32_t j : analysis_.freeKnots)
                trial_[j] = x_[j] + step_[j] * alpha;
            const double r = evaluate(trial_);
            accepted = r < kMixedGrowth * best;
            if (accepted)
                break;
        }
    } else if (windy_) {
        const double merit = meritOf(x_);
        for (int k = 0; k < kMaxBacktracks && !accepted; ++k, alpha *= 0.5) {
            for (std::uint32_t j : analysis_.freeKnots)
                trial_[j] = x_[j] + step_[j] * alpha;
            accepted = meritOf(trial_) <= (1 - 2 * kArmijo * alpha) * merit;
            if (accepted)
                break;
        }
    } else if (slope > 0) {
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
    }
    return alpha;
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
    if (alpha == 1.0 && ratio > kRatioGood)
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

} // namespace

FastRelaxer::FastRelaxer() = default;
FastRelaxer::~FastRelaxer() = default;

RelaxResult FastRelaxer::relax(MassSpringSystem& system, const RelaxOptions& options) {
    const auto start = Clock::now();
    validate(options);
    // Validates the system (UserError naming the first problem): a system of the analysis's
    // topology in its force field, any other in a new one.
    const bool reuse = analysis_ && analysis_->matches(system);
    std::optional<ForceField> fresh;
    if (reuse)
        analysis_->field.setLaw(system);
    else
        fresh.emplace(system);
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
    NewtonRun run(system, options, *analysis_, statistics_, start);
    return run.run();
}

RelaxResult relaxFast(MassSpringSystem& system, const RelaxOptions& options) {
    return FastRelaxer().relax(system, options);
}

} // namespace netsculpt
