// The relaxation of a compiled sculpture against references computed independently here:
// the compiler's tube equals the hand-built one of ReferenceNets, and a tube on a circular rail
// relaxes to the solution of the model's axisymmetric reduction (one radius and one height per
// row), solved in this test by Newton's method on 2 (rows - 1) equations: by RK4 for a soft
// rope, and by the fast path at the rope's real stiffness.

#include "../model/TestSculptures.h"
#include "HangGuard.h"
#include "DampedNewton.h"

#include "physics/Forces.h"
#include "physics/ReferenceNets.h"
#include "physics/Relaxer.h"
#include "physics/fast/NewtonRelaxer.h"

#include <catch2/catch.hpp>

#include "physics/EigenDense.h"

#include <algorithm>
#include <array>
#include <numbers>

using namespace netsculpt;
using namespace netsculpt::test;

namespace {

struct TubeCase {
    int columns = 16;
    int rows = 8;
    double radius = 0.3;
    double bar = 0.15;
    Material material{60.0, 0.05, 0.002, 0.006};
    /// How far from zero the reduction's solution must be, N: stiff bars' forces carry the
    /// rounding of their ends' positions times their stiffness.
    double reductionResidual = 1e-11;
};

CompiledSculpture compiledTube(const TubeCase& k) {
    Sculpture s;
    RailId ring = edit(s, [&](Sculpture& m) { return addRail(m, "ring", polygonRail(k.columns, k.radius)); });
    PieceId p = edit(s, [&](Sculpture& m) { return attachToRail(m, {ring, k.columns, 0, k.rows, k.bar, 0, false}); });
    return applyAtomically(s, [&](Sculpture& m) { setMaterial(m, p, k.material); return 0; }).second;
}

/// Force of Eq. 3 summed over a knot's two symmetric bars towards a row at (rho2, z2), in the
/// knot's radial-vertical plane: the tangential parts cancel.
Eigen::Vector2d pairForce(double rho, double z, double rho2, double z2, double alpha, double l0, double ks, double kc) {
    const Eigen::Vector3d d(rho2 * std::cos(alpha) - rho, rho2 * std::sin(alpha), z2 - z);
    const double l = d.norm();
    const double k = l > l0 ? ks : kc;
    const double t = k * (l - l0) / l;
    return Eigen::Vector2d(2 * t * d.x(), 2 * t * d.z());
}

/// Row radii and heights solving the axisymmetric equilibrium, from a starting guess (a stiff
/// rope's through softer tubes first).
std::vector<std::array<double, 2>> solveAxisymmetric(const TubeCase& k, std::vector<std::array<double, 2>> rows) {
    const double alpha = std::numbers::pi / k.columns;
    const int n = k.rows - 1; // free rows
    const auto residualAt = [&](double scale, const Eigen::VectorXd& x) {
        const double ks = scale * k.material.stiffness / k.bar;
        const double kc = k.material.compressionRatio * ks;
        Eigen::VectorXd f(2 * n);
        const auto rho = [&](int r) { return r == 0 ? k.radius : x[2 * (r - 1)]; };
        const auto z = [&](int r) { return r == 0 ? 0.0 : x[2 * (r - 1) + 1]; };
        for (int r = 1; r <= n; ++r) {
            const bool last = r == k.rows - 1;
            const double mass = k.material.knotMass + 0.5 * k.material.linearDensity * k.bar * (last ? 2 : 4);
            Eigen::Vector2d force(0, -9.81 * mass);
            force += pairForce(rho(r), z(r), rho(r - 1), z(r - 1), alpha, k.bar, ks, kc);
            if (!last) force += pairForce(rho(r), z(r), rho(r + 1), z(r + 1), alpha, k.bar, ks, kc);
            f.segment<2>(2 * (r - 1)) = force;
        }
        return f;
    };
    Eigen::VectorXd x(2 * n);
    for (int r = 1; r <= n; ++r) x.segment<2>(2 * (r - 1)) << rows[r][0], rows[r][1];
    x = dampedNewtonFromSoft(residualAt, x, k.material.stiffness);
    REQUIRE(residualAt(1.0, x).lpNorm<Eigen::Infinity>() < k.reductionResidual);
    for (int r = 1; r <= n; ++r) rows[r] = {x[2 * (r - 1)], x[2 * (r - 1) + 1]};
    return rows;
}

} // namespace

TEST_CASE("The compiler's tube is the hand-built reference tube", "[compiled]") {
    TubeCase k;
    const CompiledSculpture compiled = compiledTube(k);
    TubeSpec spec;
    spec.rows = k.rows;
    spec.columns = k.columns;
    spec.radius = k.radius;
    spec.barLength = k.bar;
    spec.material = {k.material.stiffness, k.material.compressionRatio, k.material.knotMass, k.material.linearDensity};
    const MassSpringSystem reference = makeTube(spec);
    REQUIRE(compiled.system.knotCount() == reference.knotCount());
    REQUIRE(compiled.system.barCount() == reference.barCount());
    // Every compiled knot has a reference knot at the same place (the numbering may differ).
    double worst = 0;
    for (const Vec3& p : compiled.system.position) {
        double nearest = 1e9;
        for (const Vec3& q : reference.position) nearest = std::min(nearest, distance(p, q));
        worst = std::max(worst, nearest);
    }
    CHECK(worst < 1e-12);
    CHECK(totalWeight(compiled.system) == Approx(totalWeight(reference)).epsilon(1e-12));
}

TEST_CASE("A relaxed tube matches the axisymmetric reduction of the model", "[compiled][relax]") {
    TubeCase k;
    CompiledSculpture compiled = compiledTube(k);
    MassSpringSystem& sys = compiled.system;
    const PieceId piece(1);
    RelaxOptions options;
    options.tolerance = 1e-9;
    options.maxSeconds = kHangGuardSeconds; // under 1 s in Release
    const RelaxResult result = relaxRk4(sys, options);
    REQUIRE(result.converged);
    // Newton on the reduced equations, started from the relaxed rows: the reduction is derived
    // independently above, so a relaxed shape that is not its solution shows as a correction.
    std::vector<std::array<double, 2>> start(k.rows);
    for (int r = 0; r < k.rows; ++r) {
        const Vec3 p = sys.position[compiled.knotOf(piece, r, 0)];
        start[r] = {std::hypot(p.x, p.y), p.z};
    }
    const auto expected = solveAxisymmetric(k, start);
    // The residual bounds the force error per knot by tol * m g; the softest mode of the tube
    // (radial breathing, stiffness ~ tension / bar ~ 0.1 N/m) turns it into < 1e-8 m.
    for (int r = 1; r < k.rows; ++r) {
        double minRadius = 1e9, maxRadius = 0;
        for (int c = 0; c < k.columns; ++c) {
            const Vec3 p = sys.position[compiled.knotOf(piece, r, c)];
            const double radius = std::hypot(p.x, p.y);
            minRadius = std::min(minRadius, radius);
            maxRadius = std::max(maxRadius, radius);
            CHECK(p.z == Approx(expected[r][1]).margin(1e-7));
        }
        INFO("row " << r);
        CHECK(maxRadius - minRadius < 1e-9 * k.radius);
        CHECK(minRadius == Approx(expected[r][0]).margin(1e-7));
        if (r > 1) CHECK(expected[r][0] < expected[r - 1][0]); // the rows contract downwards
    }
    // Force balance: the ring carries the whole weight.
    Vec3 sum;
    for (const Vec3& f : reactions(sys)) sum += f;
    CHECK(sum.z == Approx(totalWeight(sys)).epsilon(1e-7));
    CHECK(std::abs(sum.x) < 1e-9);
    CHECK(std::abs(sum.y) < 1e-9);
}

// The same reduction at the rope's real stiffness (EA 2e5 N, which RK4 cannot reach), relaxed by
// the fast path from the compiler's Eq. 2 start through its soft stages.
TEST_CASE("At the rope's real stiffness a relaxed tube matches the axisymmetric reduction",
          "[compiled][relax][fast]") {
    TubeCase k;
    k.material = Material{2e5, 0.01, 0.002, 0.006};
    k.reductionResidual = 1e-8;
    CompiledSculpture compiled = compiledTube(k);
    MassSpringSystem& sys = compiled.system;
    const PieceId piece(1);
    RelaxOptions options;
    options.tolerance = 1e-7;
    REQUIRE(relaxFast(sys, options).converged);
    std::vector<std::array<double, 2>> start(k.rows);
    for (int r = 0; r < k.rows; ++r) {
        const Vec3 p = sys.position[compiled.knotOf(piece, r, 0)];
        start[r] = {std::hypot(p.x, p.y), p.z};
    }
    const auto expected = solveAxisymmetric(k, start);
    // Every knot within F / lambda of the reduction's rows, F the force left per knot and lambda
    // the softest mode's stiffness (radial breathing, ~0.1 N/m, as above; the rope's tension is
    // the soft tube's, the same weight hanging from it): the relaxation's 1e-7 of a knot's
    // 0.037 N gives 4e-8 m, the reduction's 1e-8 N 1e-7 m (its floor: the stiff bars' forces
    // carry their ends' rounding). Measured: 3e-10 m.
    for (int r = 1; r < k.rows; ++r)
        for (int c = 0; c < k.columns; ++c) {
            INFO("row " << r << ", column " << c);
            const Vec3 p = sys.position[compiled.knotOf(piece, r, c)];
            CHECK(std::abs(p.z - expected[r][1]) < 3e-7);
            CHECK(std::abs(std::hypot(p.x, p.y) - expected[r][0]) < 3e-7);
        }
    Vec3 sum;
    for (const Vec3& f : reactions(sys)) sum += f;
    CHECK(sum.z == Approx(totalWeight(sys)).epsilon(1e-7));
}
