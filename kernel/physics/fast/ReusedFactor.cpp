// A hinted start's first step solved with the factor the relaxer's last run left
// (RelaxOptions::reuseFactor, NewtonRun.h): along a drag in the studio's preview each step starts
// a few thousandths of a knot weight off its equilibrium (interaction/DragPath.h), and the Newton
// system of such a start differs little from the last step's, so conjugate gradients
// preconditioned with the last factor solve it in a few iterations, each a solve and a product
// with the assembled matrix, instead of a new factorization.

#include "physics/fast/NewtonRun.h"

#include <algorithm>

namespace netsculpt::newton {

/// Under the hinted law: one Newton step solved by solveByPreviousFactor, kept when it lowers the
/// residual (else undone, the hint's tensions back); the hinted iterations go on from there.
/// Whether a step was kept.
bool NewtonRun::previousFactorStep(double tolerance) {
    if (!options_.reuseFactor || residual_ < tolerance || !(residual_ <= kReuseBelow) ||
        !previousFactorFits() || stopRequested())
        return false;
    report(false);
    assemble(true, false);
    if (!solveByPreviousFactor(tolerance))
        return false;
    ++steps_;
    ++stats_.reusedFactorSteps;
    takeStep(1.0, true);
    const double before = residual_;
    residual_ = evaluate(x_);
    if (residual_ < before)
        return true;
    for (std::uint32_t j : analysis_.freeKnots)
        x_[j] = trial_[j]; // the positions before the step (takeStep)
    std::copy(options_.startTensions.begin(), options_.startTensions.end(), tension_.begin());
    residual_ = evaluate(x_);
    return false;
}

/// step_ = (H + mu I)^-1 F at the free knots, H as assembled, by conjugate gradients
/// preconditioned with the factor in the analysis (the last run's), until every free knot's
/// linear residual is within kSingleAccuracy times the tolerance of its weight (the test a
/// single-precision step passes): false when that takes more than kMaxReusedIterations or the
/// numbers break down (step_ then unchanged).
bool NewtonRun::solveByPreviousFactor(double tolerance) {
    const std::size_t n = 3 * analysis_.freeKnots.size();
    std::vector<double>& x = analysis_.krylovX;
    std::vector<double>& r = linearResidual_;
    std::vector<double>& z = analysis_.krylovZ;
    std::vector<double>& d = analysis_.krylovD;
    std::vector<double>& q = analysis_.krylovQ;
    for (std::vector<double>* v : {&x, &r, &z, &d, &q})
        v->resize(n);
    std::fill(x.begin(), x.end(), 0.0);
    for (std::size_t f = 0; f < analysis_.freeKnots.size(); ++f) {
        const Vec3& F = force_[analysis_.freeKnots[f]];
        r[3 * f] = F.x;
        r[3 * f + 1] = F.y;
        r[3 * f + 2] = F.z;
    }
    precondition(r, z);
    d = z;
    double rz = dot(r, z);
    for (int k = 0; k < kMaxReusedIterations; ++k) {
        multiply([&](std::size_t f) { return Vec3{d[3 * f], d[3 * f + 1], d[3 * f + 2]}; }, q);
        const double curvature = dot(d, q);
        if (!(curvature > 0) || !(rz > 0))
            return false;
        const double a = rz / curvature;
        for (std::size_t i = 0; i < n; ++i) {
            x[i] += a * d[i];
            r[i] -= a * q[i];
        }
        if (linearResidualWithin(r, tolerance)) {
            analysis_.reusedIterations = k + 1;
            for (std::size_t f = 0; f < analysis_.freeKnots.size(); ++f)
                step_[analysis_.freeKnots[f]] = Vec3{x[3 * f], x[3 * f + 1], x[3 * f + 2]};
            return true;
        }
        precondition(r, z);
        const double next = dot(r, z);
        const double b = next / rz;
        rz = next;
        for (std::size_t i = 0; i < n; ++i)
            d[i] = z[i] + b * d[i];
    }
    return false;
}

/// out = the last factor's solution for `in` (3 per free knot).
void NewtonRun::precondition(const std::vector<double>& in, std::vector<double>& out) {
    const auto t0 = Clock::now();
    std::copy(in.begin(), in.end(), rhs_.begin());
    analysis_.cholesky.solve(rhs_, pool_.get());
    std::copy(rhs_.begin(), rhs_.begin() + static_cast<std::ptrdiff_t>(in.size()), out.begin());
    stats_.solveSeconds += secondsSince(t0);
}

/// Whether the factor a previous run left is of a system whose bars were about as stiff, their
/// mean k_s within kChordScale of this one's (not the refine's at the material's stiffness for a
/// preview's soft law, a hundred times apart).
bool NewtonRun::previousFactorFits() const {
    const double previous = analysis_.factorStiffness, now = meanStiffness();
    return previous > 0 && previous < kChordScale * now && now < kChordScale * previous &&
           analysis_.reusedIterations <= kRefreshAfter;
}

/// The mean k_s of the bars at the current scale, N/m.
double NewtonRun::meanStiffness() const {
    double sum = 0;
    for (double k : system_.kTension)
        sum += k;
    return system_.barCount() > 0 ? sum * scale_ / static_cast<double>(system_.barCount()) : 0;
}

} // namespace netsculpt::newton
