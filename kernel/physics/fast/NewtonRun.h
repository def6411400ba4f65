#pragma once
// One relaxation of the "fast" backend (NewtonRelaxer.h): the Newton iteration on the net's
// potential energy and its bookkeeping. NewtonRun.cpp has the parts of an iteration (forces,
// the Newton matrix, its factorization and solve, energy changes, steps, reports);
// NewtonRelaxer.cpp the strategy (the start's judgement, the stages, the line search) and
// FastRelaxer. Internal to kernel/physics/fast.

#include "physics/Forces.h"
#include "physics/Relaxer.h"
#include "physics/ThreadPool.h"
#include "physics/fast/FocusRegion.h"
#include "physics/fast/HugePageArray.h"
#include "physics/fast/NewtonAnalysis.h"
#include "physics/fast/NewtonRelaxer.h"

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace netsculpt::newton {

// Soft stage: EA scaled down to kSoftLoadFactor times the mean load per held knot (strains of a
// few per cent at the top of a net; the same floor as RK4's first continuation stage). No soft
// stage when that would not soften the material by at least kMaxSoftScale.
constexpr double kSoftLoadFactor = 20;
// Under wind a step solves (M - G) d = F by GMRES with M's factor (WindSteps.cpp): at most
// kWindKrylovVectors vectors, to kWindKrylovTolerance of the frozen wind's step.
constexpr int kWindKrylovVectors = 30;
constexpr double kWindKrylovTolerance = 1e-6;
constexpr double kMaxSoftScale = 0.1;
// Then, for a slack net only, stages kStageFactor times stiffer each (the last intermediate one
// at least sqrt(kStageFactor) below the material's): a tension-dominated net needs none (the jump
// from the soft stage to the material costs four or five mixed iterations), a slack one needs
// them because the shape of its slack parts changes with the stiffness. Each soft stage only has
// to bring the shape near the next one: it stops at kSoftTolerance.
constexpr double kStageFactor = 100;
constexpr double kSoftTolerance = 1e-1;
// The first step of each of those stiffer stages starts its line search from the length at
// which no knot moves more than kFirstStepCap mean rest lengths (the bent path shortened,
// PathLength.h), and lengthens it from there while the energy falls (expandStep). The soft
// stage's stretched bars now pull kStageFactor times harder, and the full Newton step, linear
// in the slack parts' folding modes, moved knots up to 0.3 m on the 100x200 sheet and left
// 15,500 of its 39,500 bars in compression (1,400 before it, 2,900 at the end): the stage then
// took 57 whole iterations to unfold them, 32 after the shortened step (docs/performance.md,
// forty-second session).
constexpr double kFirstStepCap = 0.1;
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
// yet carried, is a cold start in disguise). Not after hinted iterations whose state was kept:
// the hint says the shape is an edited equilibrium, whose load the bars away from the edit still
// carry, and a soft stage would throw that equilibrium away everywhere (an edit of the
// installation's core that slackens its bell: 70 iterations, 6 s, warm; not converged in 120 s
// through the stages). When their state was not kept the hint did not fit the edit, and the
// edited start is judged as any other (the bell's two more rows: its hinted iterations end at
// 4.1e4 knot weights; warm at the material's stiffness 201 steps, through stages 135).
constexpr double kWarmMaxResidual = 100;
// A hinted start that is not warm (an edit the hinted iterations did not fit, or whose hinted
// state was not kept) is a relaxed shape edited: most of its bars still carry their load. Its
// continuation starts one kStageFactor stiffer than a cold start's soft stage, which would let
// the whole part sag a hundredfold further than it hangs and pull it back up (edits of the
// installation's core, bell and tail, docs/performance.md, thirty-third session: 1,068 steps
// to 93 for four rows of the tail, 201 to 135 for two of the bell) ... unless a bar of the start
// is stretched by more than kEditStageMaxStrain: rows moved far from the piece they hang from
// need the soft stage (sixty rows added to the README's example between its tube and its skirt
// stretch the skirt's top bars 68-fold: not converged in 2,000 steps from the stiffer stage,
// 1,406 from the soft one).
constexpr double kEditStageMaxStrain = 2;
// A start with a tension hint (RelaxOptions::startTensions) first gets at most this many mixed
// Newton iterations seeded with the hint (see NewtonRun::hintedStart); a small edit needs two or
// three, and a start the hint does not fit goes on to the usual decision after them.
constexpr int kHintIterations = 6;
// They also stop when, from the third on, an iteration leaves the residual above this fraction of
// the lowest so far: the hinted law is not converging to the material's equilibrium (a slack sheet
// whose bar lengths are dragged: bars the hint has taut go slack, the hinted iterations stall
// near 4e-3 with 0.03-0.6 left under the material's law, and the run gets on faster from there:
// in netsculpt-bench-live --sheet a bar-length step's median Newton iterations 10 -> 9, a row
// step's 93 -> 80).
constexpr double kHintStallRatio = 0.5;
// The state those iterations reach is kept only when its residual is below the start's and below
// this: further off, the hint did not fit (sixty rows added below a relaxed piece: 1.6e8 knot
// weights after the hinted iterations, with the new rows thrown about, from where the run did not
// converge in 60 s; from the start as the edit left it, 4.3 s), and the run goes on from the start.
constexpr double kHintKeepResidual = 1e4;
// With RelaxOptions::singlePrecisionSteps the hinted iterations factorize in single precision.
// A single-precision step is off by about the matrix's condition number times 6e-8,
// relatively, which a stiff or large net's steps would notice near their tolerance, so each is
// refined in double (NewtonRun::refineSingleStep) until the forces it leaves out of balance,
// to first order, are within kSingleAccuracy of the tolerance at every knot, at most
// kSingleRefinements times; a step still off then is solved again in double, and so is the
// rest of the run. The studio's drag step at 20,000 knots needs no refinement and a row step's
// second iteration one (netsculpt-bench-live); the rope's stiffness to 1e-6 goes to double.
constexpr double kSingleAccuracy = 0.5;
constexpr int kSingleRefinements = 2;
// With RelaxOptions::reuseFactor a hinted start first takes one step solved with the last run's
// factor (NewtonRun::previousFactorStep), when that factor's system had a mean k_s within
// kChordScale of this one's: conjugate gradients preconditioned with it, at most
// kMaxReusedIterations (each a solve and a product: a seventh of a factorization at 20,000 knots;
// along netsculpt-bench-live's drag of the tube, before kRefreshAfter, most steps took 2 to 6,
// and a cap of 6 instead of 8 failed more often, each failure paying for its iterations and a factorization: 90th
// percentile 85-89 ms against 54-80). Only from a start within kReuseBelow knot weights of its
// equilibrium under the hinted law: further off (a drag's first steps, which have no path to
// predict them yet, start 0.99 and 790 off) the old factor needs more iterations than a
// factorization costs.
constexpr double kChordScale = 2;
constexpr int kMaxReusedIterations = 8;
// Once a step has taken more than kRefreshAfter iterations with the factor, the next one
// factorizes, which makes the factor anew: a factor left to age until it fails took 6 to 8
// iterations a step over most of a long drag (bench, 60 steps: median 46.4-46.9 ms, 16-22 steps
// within a frame), one refreshed after 3 took 28.3-32.1 ms, 34-43 steps within a frame (after 4:
// 32.4-46.1 ms).
constexpr double kReuseBelow = 0.05;
constexpr int kRefreshAfter = 3;
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
constexpr double kLastSmallStepShift = 1e-10;
constexpr double kMaxShift = 1e6;
// Mixed stage: a step is taken while the residual grows by less than kMixedGrowth; when the best
// residual has not improved for kMixedPatience iterations the stage falls back to the energy line
// search.
constexpr double kMixedGrowth = 10;
constexpr int kMixedPatience = 4;
// A full energy step lowers the shift tenfold only when the energy fell by at least this share of
// what the quadratic model predicts (half the slope): after a full step on a poor model the next
// one was often cut a thousandfold (the slack 100x200 sheet 169 -> 154 iterations, slack sheets
// of other sizes 968 -> 832 in all).
constexpr double kShiftDownRatio = 0.5;
// An accepted step shorter than this (a fraction of the Newton step) raises the shift (not on a
// stage's first iteration, whose direction is poor by nature from a cold start): tenfold, and to
// at least kFailShift, or kLastSmallStepShift in the last stage. There kFailShift times the mean
// diagonal (the bars' axial stiffness) is about fifty times the geometric stiffness of a strand
// of knots, so after each short step the steps of creeping strands stayed short for the eight
// good steps the shift takes to fall back; with 1e-10 the banners of docs/performance.md took
// 4,389 iterations in all instead of 4,760 (8 of 9 fewer or the same), the installation 1,338
// instead of 1,464, the slack sheets the same (1e-8: 4,542; 1e-12: 4,451; in every stage, the
// sheets took 6-10 % more).
constexpr double kSmallStep = 0.2;
// A stage whose softest bar's EA is at least kBendAxialToLoad times the mean load per held knot
// bends its steps: a step that turns bars moves their ends along straight lines, which stretches
// each such bar by |turn|^2 / 2l, and for so stiff a rope a micrometre of stretch is many knot
// weights. Where the net has to move far with almost no change in its bars' lengths (the free
// edge of a net hanging in vertical strands that swing and twist), straight steps are therefore
// cut to a fraction of a millimetre and the run creeps. The path tried is x + a p + a^2 / 2 c
// instead, c the correction that undoes that stretch to second order (the geodesic acceleration
// of Levenberg-Marquardt methods), solved with the step's factor. A full step along it whose
// energy decrease is more than kExpandDecrease of the slope (the quadratic model predicts half)
// is tried at twice, four times ... the length, up to kMaxExpansion, while the energy keeps
// falling. The soft stage (at kSoftLoadFactor) takes straight steps: bent ones cost it
// iterations. The studio's preview rope is 300-2,000 times its load: bent, its 20,000-knot demo
// tube's first settle takes 28 iterations instead of 26, and the installation's banner (623
// times, relaxed alone as an independent part) 103 instead of 3,193. A hinted start bends every
// iteration after its first (the edit's tangent predictor).
constexpr double kBendAxialToLoad = 300;
constexpr double kExpandDecrease = 0.75;
constexpr double kMaxExpansion = 4096;
// A stage at least kThirdOrderAxialToLoad times its load (the rope's stages after the soft one,
// which are 2,000 times their load or more) bends its steps to the third order: x + a p +
// a^2 / 2 c + a^3 / 6 e, e undoing the stretch the second-order path still causes (one more
// solve per iteration). The path then holds for longer steps where strands creep: the nine
// banners of docs/performance.md 4,382 -> 2,572 iterations in all, eight other banners 3,617 ->
// 2,644, the installation 1,889 -> 1,141, the eight slack sheets 997 -> 967. The studio's
// preview stiffness (300-2,000 times) keeps the second order: there it cost the live bench's
// drag step about 3 ms for no fewer iterations.
constexpr double kThirdOrderAxialToLoad = 1500;
// After the exact Hessian was found indefinite, the projected one is used for this many
// iterations before the exact one is tried again.
constexpr int kExactPause = 3;
// The last stage stops with "precision limit" (not converged) after kRoundingPatience iterations
// in a row whose steps moved no knot by more than kRoundingUnits units in the last place of its
// coordinates: the knots are then as near the equilibrium as doubles can place them. At the
// rope's stiffness one unit in the last place of a coordinate between 64 and 128 m (1.4e-14 m)
// stretches a 0.1 m bar by about a millionth of a knot's weight, so a net that far from the
// origin cannot reach the usual tolerance (a sheet 100 m long stalled at 1.08e-6 and 1.6e-6 for
// 700 and 3,000 iterations, up to the time limit).
constexpr double kRoundingUnits = 4;
constexpr int kRoundingPatience = 10;

using Clock = std::chrono::steady_clock;

inline double dot(const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        sum += a[i] * b[i];
    return sum;
}

inline double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// What FastRelaxer::relax() needs of the start beyond a valid system: finite positions, a knot
/// held by a rail, and a tension hint of one finite value per bar or none (UserError).
void checkStart(const MassSpringSystem& system, const RelaxOptions& options);

/// One stage of a run: a stiffness scale, the residual it stops at, whether it starts mixed.
struct Stage {
    double scale;
    double tolerance;
    bool mixed;
    double blend; ///< compression stiffness max(k_c, blend k_s)
    bool bent;    ///< its steps are bent (kBendAxialToLoad)
    bool thirdOrder; ///< ... to the third order (kThirdOrderAxialToLoad)
    bool firstStepCapped = false; ///< a slack net's stiffer stage (kFirstStepCap)
};

/// How a run's start is stretched: the share of its bars stretched by more than kTautStrain,
/// and the largest strain.
struct StartStrain {
    double tautShare = 0;
    double largest = 0;
};

/// One relaxation: the Newton iteration and its bookkeeping.
class NewtonRun {
  public:
    /// Relaxes a region of the system's knots on its own (FocusRegion.h) from the positions in
    /// the system, the others held, and leaves them there; `tolerance`, `blend` (compression
    /// stiffness max(k_c, blend k_s)) and `scale` (of both stiffnesses) are the stage's, and the
    /// region's steps are counted from `stepsBefore`.
    using RegionRelax =
        std::function<RelaxResult(const std::vector<std::uint32_t>& region, double tolerance,
                                  double blend, double scale, std::int64_t stepsBefore)>;

    /// `regions`: empty, every iteration is on the whole system.
    NewtonRun(MassSpringSystem& system, const RelaxOptions& options, NewtonAnalysis& analysis,
              NewtonStatistics& statistics, Clock::time_point start, RegionRelax regions = {});
    /// Shares the machine's threads with other runs going on (null: all of the pool's).
    void shareCores(const SharedCores* cores) {
        if (pool_)
            pool_->share(cores);
    }
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
    /// With wind: step_ turned from M^-1 F into the solution of (M - G) d = F, G the wind's part of
    /// the force's Jacobian (WindSteps.cpp), when the energy with the wind frozen falls along it.
    void correctStepForWind();
    void applyWindOperator(const std::vector<double>& v, std::vector<double>& out);
    void solveInto(std::vector<Vec3>& out);
    void multiplyStep(std::vector<double>& out) const;
    /// out = (H + mu I) p at the free knots (3 per free knot), H as assembled in values_ (the
    /// diagonal blocks, then the pairs' blocks), p's block of free knot f given by p(f).
    template <class Vector> void multiply(Vector p, std::vector<double>& out) const {
        const std::size_t freeCount = analysis_.freeKnots.size();
        const double mu = shift_ * meanDiagonal_;
        for (std::size_t f = 0; f < freeCount; ++f) {
            const double* h = &values_[9 * f];
            const Vec3 v = p(f);
            for (std::size_t i = 0; i < 3; ++i)
                out[3 * f + i] = h[3 * i] * v.x + h[3 * i + 1] * v.y + h[3 * i + 2] * v.z +
                                 mu * (i == 0   ? v.x
                                       : i == 1 ? v.y
                                                : v.z);
        }
        const std::size_t pairBase = 9 * freeCount;
        for (std::size_t k = 0; k < analysis_.pairs.size(); ++k) {
            const double* h = &values_[pairBase + 9 * k];
            const auto [a, b] = analysis_.pairs[k];
            const Vec3 pa = p(a), pb = p(b);
            for (std::size_t i = 0; i < 3; ++i) {
                out[3 * a + i] += h[3 * i] * pb.x + h[3 * i + 1] * pb.y + h[3 * i + 2] * pb.z;
                out[3 * b + i] += h[i] * pa.x + h[3 + i] * pa.y + h[6 + i] * pa.z;
            }
        }
    }
    bool refineSingleStep(double tolerance);
    bool linearResidualWithin(const std::vector<double>& r, double tolerance) const;
    void bendStep();
    void bendThirdOrder();
    void capStepLength();
    void solveBarTerms(std::vector<Vec3>& out);
    /// Bar b's stiffness at the current scale and compression law for `extension` (l - l_eq).
    double stiffness(std::size_t b, double extension) const {
        return (extension > 0 ? system_.kTension[b] : kCompression_[b]) * scale_;
    }
    Vec3 displacement(std::size_t j, double alpha) const {
        if (!bent_)
            return step_[j] * alpha;
        const Vec3 second = step_[j] * alpha + bend_[j] * (0.5 * alpha * alpha);
        return thirdOrder_ ? second + bendThird_[j] * (alpha * alpha * alpha / 6) : second;
    }
    double energyChange(double alpha);
    double takeStep(double alpha, bool mixed);
    void hintedStart(double tolerance);
    // ReusedFactor.cpp (RelaxOptions::reuseFactor)
    bool previousFactorStep(double tolerance);
    bool solveByPreviousFactor(double tolerance);
    void precondition(const std::vector<double>& in, std::vector<double>& out);
    bool previousFactorFits() const;
    double meanStiffness() const;
    void setHintedLaw();
    double materialLawResidual();
    bool hintStopRequested(bool moved, double startResidual);
    StartStrain startStrain() const;
    bool isWarm(const StartStrain& strain, bool hintKept) const;
    double axialToLoad() const;
    double softStageScale(double axialToLoad) const;
    std::vector<Stage> planStages(double softScale, bool warm, double axialToLoad) const;
    void runStage(const Stage& stage, bool lastStage, bool slack);
    bool assembleAndFactorize(bool mixed, int& exactPause);
    double searchLine(bool mixed, double slope, double best, bool& accepted, double& fullChange);
    double expandStep(double slope, double fullChange);
    void adaptDamping(double alpha, double slope, double fullChange);
    RelaxResult finish(double tolerance);
    /// A cancel, the time or the step limit ends the run (stopReason_ says which); a cancel only
    /// when `cancellable`.
    bool stopRequested(bool cancellable = true);
    bool relaxRegion(double tolerance, bool mixed);
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
    std::vector<Vec3>& step_;            ///< the Newton step p
    std::vector<Vec3>& bend_;            ///< its second-order correction c (when bent_)
    std::vector<Vec3>& bendThird_;       ///< its third-order correction e (when thirdOrder_)
    std::vector<double>& tension_;      ///< mixed stage: the bars' tension estimates, N
    /// the stage's compression stiffness per bar, N/m at scale 1
    std::vector<double>& kCompression_;
    HugePageArray& barBlock_;           ///< 9 per bar: its Hessian block
    HugePageArray& values_;             ///< the Newton matrix's blocks (SupernodalCholesky layout)
    std::vector<double>& rhs_;          ///< 3 per free knot
    std::vector<double>& linearResidual_; ///< 3 per free knot (refineSingleStep)
    std::vector<double>& barTerm_;      ///< per bar scratch for sums done in a fixed order
    std::vector<double>& weightOf_;     ///< m_j |g| per knot
    double scale_ = 1;
    bool bent_ = false; ///< the current step's path is x + a p + a^2 / 2 c
    bool thirdOrder_ = false; ///< ... + a^3 / 6 e
    bool single_ = false; ///< factorize in single precision (hintedStart, kSingleProgress)
    std::int64_t hintKeptAt_ = -1; ///< steps_ when the hinted iterations' state was kept
    double compressionBlend_ = 0;
    double residual_ = 0;            ///< at x_, current scale
    double shift_ = kMinShift;       ///< lambda of the Levenberg shift
    double damping_ = 0;             ///< lambda of the weight-scaled shift (energy stages)
    double meanRest_ = 1;            ///< the bars' mean rest length, m
    std::vector<double>& dampingUnit_; ///< per free knot: m_j |g| / (mean rest length), N/m
    double meanDiagonal_ = 1;
    bool windy_ = false;
    std::vector<Vec3> windMove_, windLoad_; ///< per knot (WindSteps.cpp)
    std::int64_t steps_ = 0, evaluations_ = 0;
    double lastProgress_ = -std::numeric_limits<double>::infinity();
    std::string stopReason_;
    RegionRelax regions_;
    // The last stage (the material's stiffness): its best state so far, returned when the run
    // stops before converging (its residual can rise and fall from one iteration to the next).
    std::vector<Vec3>& bestX_;
    double bestResidual_ = std::numeric_limits<double>::infinity();
};

} // namespace netsculpt::newton
