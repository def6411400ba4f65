// Newton steps under wind (NewtonRun.h). The wind's load turns with the bars, so the force's
// Jacobian has a part G with no symmetric form, which the Cholesky factor of the Newton matrix
// M cannot hold. Without it a step is a fixed point iteration on the wind's load, which
// converges slowly, or not at all, once the wind is a fair part of the weight (the net swings
// out, and each step takes the wind where the net was). The step solves (M - G) d = F instead,
// by GMRES on (I - M^-1 G) d = M^-1 F with the factor of M: one solve and one pass over the
// bars per Krylov vector.

#include "physics/EigenDense.h" // first: before anything that includes <immintrin.h>
#include "physics/fast/NewtonRun.h"

#include <cmath>
#include <functional>

namespace netsculpt::newton {

namespace {

using Operator = std::function<void(const std::vector<double>&, std::vector<double>&)>;

/// GMRES for A x = b from x (A applied by `apply`): at most `vectors` Krylov vectors, until the
/// residual's norm is at most `goal`. Returns false, x unchanged, when the numbers broke down.
bool solveByGmres(const Operator& apply, const std::vector<double>& b, std::vector<double>& x,
                  int vectors, double goal) {
    const std::size_t n = b.size();
    std::vector<double> image;
    apply(x, image);
    std::vector<std::vector<double>> basis(1, std::vector<double>(n));
    for (std::size_t i = 0; i < n; ++i)
        basis[0][i] = b[i] - image[i];
    const double beta = std::sqrt(dot(basis[0], basis[0]));
    if (!(beta > goal))
        return std::isfinite(beta);
    for (double& value : basis[0])
        value /= beta;
    Eigen::MatrixXd hessenberg = Eigen::MatrixXd::Zero(vectors + 1, vectors);
    Eigen::VectorXd coefficients;
    for (int k = 0; k < vectors; ++k) {
        std::vector<double> w;
        apply(basis[k], w);
        for (int i = 0; i <= k; ++i) { // modified Gram-Schmidt
            hessenberg(i, k) = dot(basis[i], w);
            for (std::size_t e = 0; e < n; ++e)
                w[e] -= hessenberg(i, k) * basis[i][e];
        }
        hessenberg(k + 1, k) = std::sqrt(dot(w, w));
        // The combination of the basis that leaves the least residual: a small least squares.
        Eigen::VectorXd target = Eigen::VectorXd::Zero(k + 2);
        target(0) = beta;
        const Eigen::MatrixXd h = hessenberg.topLeftCorner(k + 2, k + 1);
        coefficients = h.colPivHouseholderQr().solve(target);
        if (!((h * coefficients - target).norm() > goal) || !(hessenberg(k + 1, k) > 0))
            break;
        for (double& value : w)
            value /= hessenberg(k + 1, k);
        basis.push_back(std::move(w));
    }
    if (!coefficients.allFinite())
        return false;
    for (Eigen::Index i = 0; i < coefficients.size(); ++i)
        for (std::size_t e = 0; e < n; ++e)
            x[e] += coefficients(i) * basis[std::size_t(i)][e];
    return true;
}

} // namespace

/// out = v - M^-1 G v for v over the free knots (3 per free knot).
void NewtonRun::applyWindOperator(const std::vector<double>& v, std::vector<double>& out) {
    const std::size_t freeCount = analysis_.freeKnots.size();
    for (std::size_t f = 0; f < freeCount; ++f)
        windMove_[analysis_.freeKnots[f]] = Vec3{v[3 * f], v[3 * f + 1], v[3 * f + 2]};
    field_.windChange(x_, windMove_, windLoad_);
    for (std::size_t f = 0; f < freeCount; ++f) {
        const Vec3& g = windLoad_[analysis_.freeKnots[f]];
        rhs_[3 * f] = g.x;
        rhs_[3 * f + 1] = g.y;
        rhs_[3 * f + 2] = g.z;
    }
    const auto t0 = Clock::now();
    analysis_.cholesky.solve(rhs_, pool_.get());
    stats_.solveSeconds += secondsSince(t0);
    out.resize(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
        out[i] = v[i] - rhs_[i];
}

void NewtonRun::correctStepForWind() {
    const std::size_t freeCount = analysis_.freeKnots.size();
    windMove_.assign(system_.knotCount(), Vec3{});
    windLoad_.resize(system_.knotCount());
    // (I - M^-1 G) d = M^-1 F, from d = M^-1 F (the frozen wind's step, step_).
    std::vector<double> frozen(3 * freeCount);
    for (std::size_t f = 0; f < freeCount; ++f) {
        const Vec3& s = step_[analysis_.freeKnots[f]];
        frozen[3 * f] = s.x;
        frozen[3 * f + 1] = s.y;
        frozen[3 * f + 2] = s.z;
    }
    std::vector<double> d = frozen;
    const Operator apply = [this](const std::vector<double>& v, std::vector<double>& out) {
        applyWindOperator(v, out);
    };
    const double goal = kWindKrylovTolerance * std::sqrt(dot(frozen, frozen));
    if (!solveByGmres(apply, frozen, d, kWindKrylovVectors, goal))
        return;
    // The energy with the wind frozen must fall along it (the line search's measure); else the
    // frozen wind's step stays.
    double slope = 0;
    for (std::size_t f = 0; f < freeCount; ++f)
        slope += force_[analysis_.freeKnots[f]].dot(Vec3{d[3 * f], d[3 * f + 1], d[3 * f + 2]});
    if (slope > 0)
        for (std::size_t f = 0; f < freeCount; ++f)
            step_[analysis_.freeKnots[f]] = Vec3{d[3 * f], d[3 * f + 1], d[3 * f + 2]};
}

} // namespace netsculpt::newton
