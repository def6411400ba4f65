// RelaxOptions::reuseFactor (kernel/physics/fast/ReusedFactor.cpp): a hinted start near its
// equilibrium takes its step with the factor the relaxer's last run left, to the equilibrium a
// run that factorizes finds; not with a factor of another stiffness, nor from a start far off.

#include "ShapeDistance.h"
#include "TestNets.h"
#include "model/Compiler.h"
#include "model/Edits.h"
#include "physics/Forces.h"
#include "physics/Relaxer.h"
#include "physics/fast/NewtonRelaxer.h"
#include "physics/fast/NewtonRun.h"

#include <catch2/catch.hpp>

#include <atomic>

using namespace netsculpt;
using netsculpt::test::maxDistance;
using netsculpt::test::tube;

namespace {

/// A soft 20 x 40 tube (EA 2e3 N, about the studio's preview of the rope) relaxed by `relaxer`
/// to `tolerance`, then its bars lengthened by `share` of their length: the start after the edit
/// (the relaxed positions) and the tensions they had before it (what the studio hands on).
struct Edited {
    MassSpringSystem start;
    std::vector<double> hint;
};

Edited lengthened(FastRelaxer& relaxer, double share, double tolerance) {
    Sculpture s = tube(20, 40, 2e3);
    const PieceId piece = s.pieces.begin()->first;
    CompiledSculpture before = compileSculpture(s);
    RelaxOptions options;
    options.tolerance = tolerance;
    REQUIRE(relaxer.relax(before.system, options).converged);
    auto [ignored, after] = applyAtomically(s, [&](Sculpture& m) {
        setBarLength(m, piece, std::nullopt, 0.1 * (1 + share));
        return 0;
    });
    REQUIRE(carryPositions(before, after) > 0);
    MassSpringSystem law = before.system;
    law.position = after.system.position;
    return Edited{after.system, barTensions(law)};
}

RelaxOptions hinted(const Edited& edit, double tolerance, bool reuse) {
    RelaxOptions options;
    options.tolerance = tolerance;
    options.startTensions = edit.hint;
    options.reuseFactor = reuse;
    return options;
}

} // namespace

TEST_CASE("fast: with reuseFactor a start near its equilibrium steps with the last run's factor, "
          "to the equilibrium a factorizing run finds",
          "[fast]") {
    constexpr double kTight = 1e-8;
    FastRelaxer relaxer;
    const Edited edit = lengthened(relaxer, 2e-7, kTight);
    const double startResidual = residual(edit.start);
    INFO("start residual " << startResidual);
    REQUIRE(startResidual > 1e-3);
    REQUIRE(startResidual < newton::kReuseBelow);

    MassSpringSystem reused = edit.start;
    const RelaxResult r = relaxer.relax(reused, hinted(edit, kTight, true));
    const NewtonStatistics stats = relaxer.statistics();
    INFO(r.steps << " steps, " << stats.factorizations << " factorizations");
    REQUIRE(r.converged);
    CHECK(residual(reused) < kTight);
    CHECK(stats.reusedFactorSteps == 1);
    CHECK(stats.factorizations < r.steps); // the first step took no factorization

    FastRelaxer fresh; // no earlier run: nothing to reuse, every step factorizes
    MassSpringSystem factorized = edit.start;
    REQUIRE(fresh.relax(factorized, hinted(edit, kTight, true)).converged);
    CHECK(fresh.statistics().reusedFactorSteps == 0);
    CHECK(fresh.statistics().factorizations >= 1);
    // Both within kTight knot weights of one equilibrium of a taut tube: metres apart by far
    // less than a micrometre.
    CHECK(maxDistance(reused.position, factorized.position) < 1e-7);
}

TEST_CASE("fast: reuseFactor leaves alone a factor of another stiffness and a start far off",
          "[fast]") {
    FastRelaxer relaxer;
    // Far off: a drag's first 0.5 % step, about a knot weight out of balance.
    const Edited far = lengthened(relaxer, 5e-3, 1e-6);
    REQUIRE(residual(far.start) > newton::kReuseBelow);
    MassSpringSystem a = far.start;
    REQUIRE(relaxer.relax(a, hinted(far, 1e-3, true)).converged);
    CHECK(relaxer.statistics().reusedFactorSteps == 0);

    // Near, but the last factor is of the tube at a hundred times its stiffness.
    const Edited near = lengthened(relaxer, 2e-7, 1e-8);
    MassSpringSystem stiff = near.start;
    for (std::size_t b = 0; b < stiff.barCount(); ++b) {
        stiff.kTension[b] *= 100;
        stiff.kCompression[b] *= 100;
    }
    REQUIRE(relaxer.relax(stiff, RelaxOptions{}).converged); // leaves its factor
    MassSpringSystem b = near.start;
    REQUIRE(relaxer.relax(b, hinted(near, 1e-3, true)).converged);
    CHECK(relaxer.statistics().reusedFactorSteps == 0);
}

TEST_CASE("fast: a cancel that waits for a state worth keeping takes the step with the last "
          "factor as that state",
          "[fast]") {
    // hintBeforeCancel: a cancel ends the hinted start once it has moved the net to a state worth
    // keeping. A step with the last factor is such a move; no factorized iteration follows it.
    FastRelaxer relaxer;
    const Edited edit = lengthened(relaxer, 2e-7, 1e-8);
    std::atomic<bool> cancel{false};
    RelaxOptions options = hinted(edit, 1e-12, true); // a tolerance the step does not reach
    options.hintBeforeCancel = true;
    options.cancel = &cancel;
    options.progressInterval = 0;
    options.progress = [&](const RelaxProgress&) { cancel = true; }; // arrives during the step
    MassSpringSystem s = edit.start;
    const RelaxResult r = relaxer.relax(s, options);
    CHECK(r.stopReason == "cancelled");
    CHECK(relaxer.statistics().reusedFactorSteps == 1);
    CHECK(relaxer.statistics().factorizations == 0);
    CHECK(residual(s) < residual(edit.start));
}
