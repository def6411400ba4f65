// Newton steps under wind (NewtonRun.h). The wind's load turns with the bars, so the force's
// Jacobian has a part G with no symmetric form, which the Cholesky factor of the Newton matrix
// M cannot hold. Without it a step is a fixed point iteration on the wind's load, which
// converges slowly, or not at all, once the wind is a fair part of the weight (the net swings
// out, and each step takes the wind where the net was). The step solves (M - G) d = F instead,
// by GMRES on (I - M^-1 G) d = M^-1 F with the factor of M: one solve and one pass over the
// bars per Krylov vector.

#include "physics/fast/NewtonRun.h"

#include <Eigen/Dense>

#include <cmath>

namespace netsculpt::newton {

namespace {

double dot(const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        sum += a[i] * b[i];
    return sum;
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
    analysis_.cholesky.solve(rhs_, pool_.get());
    out.resize(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
        out[i] = v[i] - rhs_[i];
}

void NewtonRun::correctStepForWind() {
    const std::size_t freeCount = analysis_.freeKnots.size(), n = 3 * freeCount;
    windMove_.assign(system_.knotCount(), Vec3{});
    windLoad_.resize(system_.knotCount());
    windStep_.resize(system_.knotCount());
    std::vector<double> start(n);
    for (std::size_t f = 0; f < freeCount; ++f) {
        const Vec3& s = step_[analysis_.freeKnots[f]];
        start[3 * f] = s.x;
        start[3 * f + 1] = s.y;
        start[3 * f + 2] = s.z;
    }
    // From d = M^-1 F (the frozen wind's step): the residual M^-1 F - (I - M^-1 G) d = M^-1 G d.
    std::vector<double> image;
    applyWindOperator(start, image);
    std::vector<std::vector<double>> basis(1, std::vector<double>(n));
    for (std::size_t i = 0; i < n; ++i)
        basis[0][i] = start[i] - image[i];
    const double beta = std::sqrt(dot(basis[0], basis[0]));
    const double goal = kWindKrylovTolerance * std::sqrt(dot(start, start));
    if (!(beta > goal))
        return;
    for (double& value : basis[0])
        value /= beta;
    Eigen::MatrixXd hessenberg = Eigen::MatrixXd::Zero(kWindKrylovVectors + 1, kWindKrylovVectors);
    Eigen::VectorXd coefficients;
    for (int k = 0; k < kWindKrylovVectors; ++k) {
        std::vector<double> w;
        applyWindOperator(basis[k], w);
        for (int i = 0; i <= k; ++i) { // modified Gram-Schmidt
            hessenberg(i, k) = dot(basis[i], w);
            for (std::size_t e = 0; e < n; ++e)
                w[e] -= hessenberg(i, k) * basis[i][e];
        }
        hessenberg(k + 1, k) = std::sqrt(dot(w, w));
        Eigen::VectorXd target = Eigen::VectorXd::Zero(k + 2);
        target(0) = beta;
        const Eigen::MatrixXd h = hessenberg.topLeftCorner(k + 2, k + 1);
        coefficients = h.colPivHouseholderQr().solve(target);
        const double left = (h * coefficients - target).norm();
        if (!(left > goal) || !(hessenberg(k + 1, k) > 0))
            break;
        for (double& value : w)
            value /= hessenberg(k + 1, k);
        basis.push_back(std::move(w));
    }
    if (!coefficients.allFinite())
        return;
    double slope = 0;
    for (std::size_t f = 0; f < freeCount; ++f) {
        const std::uint32_t j = analysis_.freeKnots[f];
        Vec3 d{start[3 * f], start[3 * f + 1], start[3 * f + 2]};
        for (Eigen::Index i = 0; i < coefficients.size(); ++i)
            d += Vec3{basis[i][3 * f], basis[i][3 * f + 1], basis[i][3 * f + 2]} * coefficients(i);
        windStep_[j] = d;
        slope += force_[j].dot(d);
    }
    // The energy with the wind frozen must fall along it (the line search's measure); else the
    // frozen wind's step stays.
    if (slope > 0)
        for (std::uint32_t j : analysis_.freeKnots)
            step_[j] = windStep_[j];
}

} // namespace netsculpt::newton
