// The fast path at the limit of double precision: far from the system's origin, one unit in the
// last place of a knot's coordinates stretches a stiff rope's bars by more than the tolerance
// allows, so no representable position is an equilibrium to 1e-6. The run must say so and stop,
// not creep to its time limit, and what it returns is still the equilibrium up to that rounding.
// A sculpture in site coordinates does not meet that floor: its system is compiled about an
// origin near its rails (MassSpringSystem::origin).
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
/// centred at `centre`.
MassSpringSystem ropeTubeAt(const Vec3& centre) {
    CurveSpec ring;
    ring.closed = true;
    const int columns = 24;
    ring.points = circlePoints(centre, columns * 0.1 / (2 * std::numbers::pi), columns);
    Sculpture s;
    const RailId rail = addRail(s, "ring", ring);
    const PieceId piece = attachToRail(s, {rail, columns, 0, 12, 0.1, 0, false});
    setMaterial(s, piece, Material{2e5, 0.01, 0.002, 0.006});
    refreshAndValidate(s);
    return compileSculpture(s).system;
}

/// The tube about (0, 0, 0), its positions then moved x metres along x in the system itself (its
/// origin left at (0, 0, 0)): a system whose own coordinates are far out.
MassSpringSystem ropeTubeMovedBy(double x) {
    MassSpringSystem system = ropeTubeAt({0, 0, 0});
    for (Vec3& p : system.position)
        p.x += x;
    return system;
}

} // namespace

TEST_CASE("fast: a net too far from its system's origin for the tolerance stops at the precision "
          "limit",
          "[fast]") {
    // 30 km out, a unit in the last place is 3.6e-12 m: a 0.1 m bar of EA 2e5 N changes its
    // force by 7e-6 N per unit, about 2e-4 of a knot's weight.
    constexpr double kFar = 3e4;
    MassSpringSystem near = ropeTubeAt({0, 0, 0}), far = ropeTubeMovedBy(kFar);
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
    MassSpringSystem loose = ropeTubeMovedBy(kFar);
    options.tolerance = 1e-2;
    const RelaxResult looser = FastRelaxer().relax(loose, options);
    CHECK(looser.converged);
    CHECK(looser.stopReason == "converged");
}

TEST_CASE("fast: a sculpture in site coordinates is relaxed about its own origin, to the "
          "tolerance",
          "[fast]") {
    MassSpringSystem near = ropeTubeAt({0, 0, 0});
    const RelaxResult atOrigin = FastRelaxer().relax(near, {});
    REQUIRE(atOrigin.converged);
    CHECK(near.origin == Vec3{0, 0, 0});
    // 30 km out along x, and at an easting and northing in metres as a surveyor's drawing has them
    // (there a unit in the last place of the northing is 9.3e-10 m).
    for (const Vec3 site : {Vec3{3e4, 0, 0}, Vec3{512345.678, 5412345.678, 231.5}}) {
        MassSpringSystem far = ropeTubeAt(site);
        CHECK(far.origin == Vec3{std::round(site.x), std::round(site.y), std::round(site.z)});
        const RelaxResult r = FastRelaxer().relax(far, {});
        INFO("site " << site.x << ", " << site.y << ", " << site.z << ": " << r.stopReason
                     << ", residual " << r.residual << " after " << r.steps << " steps");
        CHECK(r.converged);
        CHECK(r.residual < 1e-6);
        CHECK(r.residual == residual(far)); // judged on the positions kept
        // The same equilibrium, moved: the rail's points differ from the centred ones by the
        // rounding of the site's coordinates (up to 4.7e-10 m), the shape by about as much.
        std::vector<Vec3> moved(far.knotCount());
        for (std::size_t j = 0; j < far.knotCount(); ++j)
            moved[j] = far.worldPosition(j) - site;
        CHECK(test::maxDistance(moved, near.position) < 1e-8);
    }
}
