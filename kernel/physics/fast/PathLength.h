#pragma once
// How a bar's length changes along a curved step of its ends: the derivatives, at a = 0, of
// l(a) = |d + a dp + a^2 / 2 dc| (d the bar's vector, dp and dc its ends' relative first- and
// second-order steps). The bent steps of the fast backend (NewtonRun.h) undo the stretch these
// describe; a knot's move along such a path, and the path shortened (a stiffer stage's first
// step, NewtonRun::capStepLength). Internal to kernel/physics/fast.

#include "geometry/Vec3.h"

namespace netsculpt::newton {

/// d^2 l / da^2 at a = 0 along the straight path d + a dp: (|dp|^2 - (u . dp)^2) / l.
/// NewtonRun::bendStep computes the same quantity inline, times k / l, in an order of
/// operations of its own: its rounding fixes the iteration counts docs/performance.md reports.
inline double lengthSecondDerivative(const Vec3& d, const Vec3& dp) {
    const double l = d.norm();
    if (!(l > 0))
        return 0;
    const double along = d.dot(dp) / l;
    return (dp.dot(dp) - along * along) / l;
}

/// d^3 l / da^3 at a = 0 along d + a dp + a^2 / 2 dc. With f(a) = l(a)^2 = l^2 + f1 a +
/// f2 a^2 / 2 + f3 a^3 / 6 + ..., l''' = f3 / 2l - 3 f1 f2 / 4l^3 + 3 f1^3 / 8l^5.
inline double lengthThirdDerivative(const Vec3& d, const Vec3& dp, const Vec3& dc) {
    const double l = d.norm();
    if (!(l > 0))
        return 0;
    const double f1 = 2 * d.dot(dp), f2 = 2 * (d.dot(dc) + dp.dot(dp));
    const double f3 = 6 * dp.dot(dc);
    const double l3 = l * l * l;
    return f3 / (2 * l) - 3 * f1 * f2 / (4 * l3) + 3 * f1 * f1 * f1 / (8 * l3 * l * l);
}

/// A knot's move at length a along a bent step with first-, second- and third-order parts p, c
/// and e: a p + a^2 / 2 c + a^3 / 6 e. NewtonRun::displacement computes the same move inline
/// (without e below the third order): written through this function the 100x200 sheet's run
/// ends with other last bits (residual 3.69e-7 against 3.51e-7, the same 177 iterations).
inline Vec3 pathMove(const Vec3& p, const Vec3& c, const Vec3& e, double a) {
    return p * a + c * (0.5 * a * a) + e * (a * a * a / 6);
}

/// The same path shortened by the factor f: its move at a is the old one's at f a.
inline void shortenPath(Vec3& p, Vec3& c, Vec3& e, double f) {
    p *= f;
    c *= f * f;
    e *= f * f * f;
}

} // namespace netsculpt::newton
