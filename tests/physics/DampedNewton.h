#pragma once
// A small damped Newton solver for the tests' independent reference problems (reductions of a
// net to a few unknowns): Jacobian by central differences of 1e-8 m, full-pivot LU, step
// halving until the residual norm decreases. (The real rope's stiff bars' forces curve sharply:
// with one-sided differences, or central ones of 1e-7 m, the Jacobian's soft directions were so
// far off that Newton crept linearly and stalled above the rounding's floor.)

#include "physics/EigenDense.h"

#include <algorithm>
#include <cmath>

namespace netsculpt::test {

/// Solves f(x) = 0 from x; returns the root (check f at it: the caller decides what is enough).
template <typename F> Eigen::VectorXd dampedNewton(const F& f, Eigen::VectorXd x, int iterations = 200) {
    for (int iteration = 0; iteration < iterations; ++iteration) {
        const Eigen::VectorXd value = f(x);
        if (value.lpNorm<Eigen::Infinity>() < 1e-14) break;
        Eigen::MatrixXd jacobian(x.size(), x.size());
        for (Eigen::Index j = 0; j < x.size(); ++j) {
            Eigen::VectorXd ahead = x, behind = x;
            const double h = 1e-8 * std::max(1.0, std::abs(x[j]));
            ahead[j] += h;
            behind[j] -= h;
            jacobian.col(j) = (f(ahead) - f(behind)) / (2 * h);
        }
        const Eigen::VectorXd step = jacobian.fullPivLu().solve(value);
        double scale = 1;
        while (scale > 1e-6 && f(x - scale * step).norm() >= value.norm()) scale *= 0.5;
        x -= scale * step;
    }
    return x;
}

/// Solves f(1, x) = 0 from x, f(scale, x) being a net's forces with its bars' stiffness times
/// scale. When `stiffness` (EA, N) is above kSoftStiffness, by continuation: from that stiffness
/// up by thirds of a decade, each stage from the last one's root. (From a start millimetres off,
/// a stiff net's Newton step turns its bars and stretches them by many knot weights, and the
/// damped steps stall above the rounding's floor.)
constexpr double kSoftStiffness = 50;
template <typename F>
Eigen::VectorXd dampedNewtonFromSoft(const F& f, Eigen::VectorXd x, double stiffness) {
    const double ratio = stiffness / kSoftStiffness;
    const int stages = ratio > 1 ? static_cast<int>(std::ceil(3 * std::log10(ratio))) : 0;
    for (int stage = stages; stage >= 0; --stage) {
        const double scale = std::pow(10.0, -stage / 3.0);
        x = dampedNewton([&](const Eigen::VectorXd& y) { return f(scale, y); }, x);
    }
    return x;
}

} // namespace netsculpt::test
