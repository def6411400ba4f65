// The derivatives of a bar's length along a curved step (kernel/physics/fast/PathLength.h),
// which the bent steps undo, against finite differences of the length itself.
#include "physics/fast/PathLength.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace netsculpt;
using namespace netsculpt::newton;

namespace {

double lengthAt(const Vec3& d, const Vec3& dp, const Vec3& dc, double a) {
    return (d + dp * a + dc * (0.5 * a * a)).norm();
}

} // namespace

TEST_CASE("path length: second and third derivatives match finite differences", "[fast]") {
    const Vec3 d{0.03, -0.02, -0.095}, dp{0.004, 0.007, -0.001}, dc{-0.002, 0.0015, 0.003};
    const double h = 1e-2;
    // Central differences, exact to O(h^2): the fourth derivative is of order |dp|^4 / l^3.
    const double l0 = lengthAt(d, dp, dc, 0);
    const double straight2 =
        (lengthAt(d, dp, {}, h) - 2 * l0 + lengthAt(d, dp, {}, -h)) / (h * h);
    CHECK(lengthSecondDerivative(d, dp) == Approx(straight2).epsilon(1e-4));
    const double third = (lengthAt(d, dp, dc, 2 * h) - 2 * lengthAt(d, dp, dc, h) +
                          2 * lengthAt(d, dp, dc, -h) - lengthAt(d, dp, dc, -2 * h)) /
                         (2 * h * h * h);
    CHECK(lengthThirdDerivative(d, dp, dc) == Approx(third).epsilon(1e-3));
    CHECK(std::abs(lengthThirdDerivative(d, dp, dc)) > 1e-5); // not trivially zero here
    // Along the bar, a straight step changes the length linearly: no curvature.
    CHECK(lengthSecondDerivative(d, d * 0.1) == Approx(0).margin(1e-15));
    CHECK(lengthThirdDerivative(Vec3{}, dp, dc) == 0);
}

TEST_CASE("path length: a shortened bent path passes through the old one's points", "[fast]") {
    const Vec3 p0{0.02, -0.01, 0.005}, c0{-0.003, 0.004, 0.001}, e0{0.0005, -0.0002, 0.0007};
    // Its moves, written out: a p + a^2 / 2 c + a^3 / 6 e.
    CHECK(pathMove(p0, c0, e0, 2.0).x == Approx(0.04 - 0.006 + 0.0005 * 8 / 6).epsilon(1e-12));
    Vec3 p = p0, c = c0, e = e0;
    const double f = 0.3;
    shortenPath(p, c, e, f);
    for (double a : {0.5, 1.0, 4.0, 64.0}) {
        const Vec3 shortened = pathMove(p, c, e, a), original = pathMove(p0, c0, e0, f * a);
        CHECK((shortened - original).norm() <= 1e-12 * (1 + original.norm()));
    }
    // Not the same path as a straight scaling of the whole move.
    CHECK((pathMove(p, c, e, 1.0) - pathMove(p0, c0, e0, 1.0) * f).norm() > 1e-5);
}
