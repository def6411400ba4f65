#pragma once
// A small damped Newton solver for the tests' independent reference problems (reductions of a
// net to a few unknowns): central-difference Jacobian, full-pivot LU, step halving until the
// residual norm decreases. (A one-sided difference carries the second-order stretch of the bars
// it turns, which swamps a stiff rope's soft directions: Newton then stalls.)

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
            const double h = 1e-7 * std::max(1.0, std::abs(x[j]));
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

} // namespace netsculpt::test
