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
