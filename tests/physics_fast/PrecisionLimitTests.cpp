// The fast path at the limit of double precision: far from the origin, one unit in the last
// place of a knot's coordinates stretches a stiff rope's bars by more than the tolerance allows,
// so no representable position is an equilibrium to 1e-6. The run must say so and stop, not
// creep to its time limit, and what it returns is still the equilibrium up to that rounding.
#include "ShapeDistance.h"
#include "geometry/Circle.h"
#include "model/Compiler.h"
#include "model/Edits.h"
#include "physics/Forces.h"
#include "physics/Relaxer.h"
#include "physics/fast/NewtonRelaxer.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace netsculpt;

namespace {

/// A 12 x 24 tube of real rope (EA 2e5 N, knots 0.1 m apart on the rail) on a circular rail
/// centred at (x, 0, 0).
MassSpringSystem ropeTubeAt(double x) {
    CurveSpec ring;
    ring.closed = true;
    const int columns = 24;
    ring.points = circlePoints({x, 0, 0}, columns * 0.1 / (2 * std::numbers::pi), columns);
    Sculpture s;
    const RailId rail = addRail(s, "ring", ring);
    const PieceId piece = attachToRail(s, {rail, columns, 0, 12, 0.1, 0, false});
    setMaterial(s, piece, Material{2e5, 0.01, 0.002, 0.006});
    refreshAndValidate(s);
    return compileSculpture(s).system;
}

} // namespace

TEST_CASE("fast: a net too far from the origin for the tolerance stops at the precision limit",
          "[fast]") {
    // 30 km out, a unit in the last place is 3.6e-12 m: a 0.1 m bar of EA 2e5 N changes its
    // force by 7e-6 N per unit, about 2e-4 of a knot's weight.
    constexpr double kFar = 3e4;
    MassSpringSystem near = ropeTubeAt(0), far = ropeTubeAt(kFar);
    RelaxOptions options;
    options.maxSeconds = 30;
    FastRelaxer nearRelaxer, farRelaxer;
    const RelaxResult atOrigin = nearRelaxer.relax(near, options);
    const RelaxResult farAway = farRelaxer.relax(far, options);
    REQUIRE(atOrigin.converged);

    CHECK_FALSE(farAway.converged);
    CHECK(farAway.stopReason == "precision limit");
    CHECK(farAway.seconds < 10);       // not the time limit
    INFO("residual " << farAway.residual << " after " << farAway.steps << " steps");
    CHECK(farAway.residual < 1e-2);    // at the rounding's floor, not somewhere on the way
    CHECK(farAway.residual > 1e-6);
    CHECK(farAway.residual == residual(far)); // judged on exactly the positions returned
    // And it is the same equilibrium, moved: within 0.1 micrometre (9e-9 m measured; the soft
    // modes of the hanging tube give way to the rounding's forces by that much).
    for (Vec3& p : far.position)
        p.x -= kFar;
    CHECK(test::maxDistance(far.position, near.position) < 1e-7);

    // With a tolerance above that floor the same net converges.
    MassSpringSystem loose = ropeTubeAt(kFar);
    options.tolerance = 1e-2;
    const RelaxResult looser = FastRelaxer().relax(loose, options);
    CHECK(looser.converged);
    CHECK(looser.stopReason == "converged");
}
