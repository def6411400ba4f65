// A system of independent parts (kernel/physics/fast/Components.h): found as connected components
// of the free knots, each relaxed as a system of its own by FastRelaxer, with the same forces and
// the same equilibrium as in the whole system, and a part an edit did not touch left as it was.
#include "geometry/Circle.h"
#include "model/Compiler.h"
#include "model/Edits.h"
#include "physics/Forces.h"
#include "physics/fast/Components.h"
#include "physics/fast/NewtonRelaxer.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <mutex>
#include <thread>
#include <set>

using namespace netsculpt;

namespace {

CurveSpec ring(int n, double radius, Vec3 centre) {
    CurveSpec spec;
    spec.closed = true;
    spec.points = circlePoints(centre, radius, n);
    return spec;
}

CurveSpec segment(Vec3 a, Vec3 b) {
    CurveSpec spec;
    spec.points = {a, b};
    return spec;
}

/// Three independent parts at the rope's stiffness: a sheet hanging slack between two rails, a
/// tube with a piece below it (gear 1/2), and a small tube.
struct ThreeParts {
    Sculpture s;
    PieceId sheet, tube, below, small;
};

ThreeParts threeParts() {
    ThreeParts t;
    Sculpture& s = t.s;
    const RailId top = addRail(s, "top", segment({0, 0, 0}, {0.9, 0, 0}));
    const RailId bottom = addRail(s, "bottom", segment({0, 0.15, -0.3}, {0.9, 0.15, -0.3}));
    t.sheet = attachToRail(s, {top, 10, 0, 8, 0.1, 0, false});
    connectToRail(s, t.sheet, bottom, 0.0, false);
    const RailId halo = addRail(s, "halo", ring(12, 12 * 0.1 / (2 * std::numbers::pi), {3, 0, 0}));
    t.tube = attachToRail(s, {halo, 12, 0, 6, 0.1, 0, false});
    t.below = attachToPiece(s, {t.tube, Gear{1, 2}, 4, 0.12});
    const RailId ring2 = addRail(s, "ring", ring(8, 8 * 0.1 / (2 * std::numbers::pi), {6, 0, 1}));
    t.small = attachToRail(s, {ring2, 8, 0, 5, 0.1, 0, false});
    for (PieceId p : {t.sheet, t.tube, t.below, t.small})
        setMaterial(s, p, Material{2e5, 0.01, 0.002, 0.006});
    refreshAndValidate(s);
    return t;
}

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

/// The component holding knot j (an index into freeComponents()), or -1.
int componentOf(const std::vector<std::vector<std::uint32_t>>& components, std::uint32_t j) {
    for (std::size_t c = 0; c < components.size(); ++c)
        if (std::binary_search(components[c].begin(), components[c].end(), j))
            return static_cast<int>(c);
    return -1;
}

/// Progress reports of a system of parts: several, each with the whole net's knots, their steps
/// never going back, the last one at the run's steps.
void checkWholeReports(const std::vector<RelaxProgress>& reports, std::size_t knots,
                       std::int64_t steps) {
    REQUIRE(reports.size() > 3);
    for (std::size_t i = 0; i < reports.size(); ++i) {
        CHECK(reports[i].positions.size() == knots);
        if (i > 0)
            CHECK(reports[i].steps >= reports[i - 1].steps);
    }
    CHECK(reports.back().steps == steps);
}

} // namespace

TEST_CASE("parts: the free knots fall into one component per independent net", "[fast]") {
    const ThreeParts t = threeParts();
    const CompiledSculpture c = compileSculpture(t.s);
    const auto components = freeComponents(c.system);
    REQUIRE(components.size() == 3);
    std::set<std::uint32_t> seen;
    for (const auto& component : components) {
        CHECK(std::is_sorted(component.begin(), component.end()));
        seen.insert(component.begin(), component.end());
    }
    const auto freeCount = std::count(c.system.fixed.begin(), c.system.fixed.end(), 0);
    CHECK(seen.size() == static_cast<std::size_t>(freeCount));
    // The sheet's free knots (its first and last rows are on rails) together, the tube and the
    // piece below it together, the small tube alone: in the order of their first knots.
    CHECK(componentOf(components, c.knotOf(t.sheet, 1, 0)) == 0);
    CHECK(componentOf(components, c.knotOf(t.sheet, 6, 9)) == 0);
    CHECK(componentOf(components, c.knotOf(t.sheet, 0, 0)) == -1);
    CHECK(componentOf(components, c.knotOf(t.tube, 1, 0)) == 1);
    CHECK(componentOf(components, c.knotOf(t.below, 3, 5)) == 1);
    CHECK(componentOf(components, c.knotOf(t.small, 4, 7)) == 2);
    CHECK(components[0].size() == 6 * 10);
    CHECK(components[2].size() == 4 * 8);
}

TEST_CASE("parts: a part's knots feel the same forces, bit for bit, as in the whole system",
          "[fast]") {
    const ThreeParts t = threeParts();
    MassSpringSystem whole = compileSculpture(t.s).system;
    for (std::size_t j = 0; j < whole.knotCount(); ++j) // off the Eq. 2 start, so forces differ
        if (!whole.fixed[j])
            whole.position[j] += Vec3{0.01 * std::sin(j), 0.02 * std::cos(3.0 * j), 0};
    const std::vector<Vec3> wholeForce = knotForces(whole);
    std::vector<std::int64_t> scratch;
    std::size_t bars = 0;
    for (const auto& component : freeComponents(whole)) {
        const Part part = extractPart(whole, component, scratch);
        bars += part.barOf.size();
        CHECK(std::is_sorted(part.knotOf.begin(), part.knotOf.end()));
        CHECK(std::is_sorted(part.barOf.begin(), part.barOf.end()));
        const std::vector<Vec3> partForce = knotForces(part.system);
        int free = 0;
        for (std::size_t k = 0; k < part.knotOf.size(); ++k) {
            if (part.system.fixed[k])
                continue;
            ++free;
            CHECK(sameBits(partForce[k], wholeForce[part.knotOf[k]]));
        }
        CHECK(free == static_cast<int>(component.size()));
    }
    // No bar joins two fixed knots here, so every bar is in exactly one part.
    CHECK(bars == whole.barCount());
}

TEST_CASE("parts: relaxed one by one to the whole system's equilibrium", "[fast]") {
    const ThreeParts t = threeParts();
    const MassSpringSystem start = compileSculpture(t.s).system;
    MassSpringSystem whole = start;
    std::vector<RelaxProgress> reports;
    RelaxOptions options;
    options.progressInterval = 0;
    options.progress = [&](const RelaxProgress& p) { reports.push_back(p); };
    FastRelaxer kept;
    const RelaxResult result = kept.relax(whole, options);
    REQUIRE(result.converged);
    CHECK(result.residual == residual(whole));
    CHECK(result.residual < 1e-6);
    Vec3 carried{0, 0, 0};
    for (const Vec3& r : reactions(whole))
        carried += r;
    CHECK(std::abs(carried.z - totalWeight(whole)) < 1e-6 * totalWeight(whole));
    CHECK(std::abs(carried.x) + std::abs(carried.y) < 1e-6 * totalWeight(whole));
    // Each part alone, by a relaxer of its own, takes the same steps to the same bits.
    std::vector<std::int64_t> scratch;
    std::int64_t steps = 0;
    for (const auto& component : freeComponents(start)) {
        Part part = extractPart(start, component, scratch);
        const RelaxResult alone = relaxFast(part.system, RelaxOptions{});
        REQUIRE(alone.converged);
        steps += alone.steps;
        for (std::size_t k = 0; k < part.knotOf.size(); ++k)
            CHECK(sameBits(part.system.position[k], whole.position[part.knotOf[k]]));
    }
    CHECK(result.steps == steps);
    CHECK(kept.statistics().iterations == steps);
    CHECK(kept.statistics().parts == 3);
    // Progress reports show the whole net, their steps counted across the parts.
    checkWholeReports(reports, start.knotCount(), result.steps);
}

TEST_CASE("parts: after an edit of one part the others keep their bits and take no step",
          "[fast]") {
    ThreeParts t = threeParts();
    MassSpringSystem system = compileSculpture(t.s).system;
    FastRelaxer kept;
    REQUIRE(kept.relax(system, RelaxOptions{}).converged);
    const std::vector<Vec3> before = system.position;
    // A law edit of the tube's part: its bars 1 % longer.
    const auto components = freeComponents(system);
    std::vector<std::int64_t> scratch;
    const Part tubePart = extractPart(system, components[1], scratch);
    for (std::uint32_t b : tubePart.barOf) {
        system.restLength[b] *= 1.01;
        system.kTension[b] /= 1.01;
        system.kCompression[b] /= 1.01;
    }
    Part edited = extractPart(system, components[1], scratch);
    const RelaxResult result = kept.relax(system, RelaxOptions{});
    REQUIRE(result.converged);
    CHECK(kept.statistics().reusedAnalysis);
    const RelaxResult alone = FastRelaxer().relax(edited.system, RelaxOptions{});
    CHECK(result.steps == alone.steps);
    CHECK(alone.steps > 0);
    int moved = 0;
    for (std::size_t j = 0; j < system.knotCount(); ++j) {
        const bool inTube = componentOf(components, static_cast<std::uint32_t>(j)) == 1;
        if (!inTube)
            CHECK(sameBits(system.position[j], before[j]));
        moved += inTube && !sameBits(system.position[j], before[j]) ? 1 : 0;
    }
    CHECK(moved == static_cast<int>(components[1].size()));
}

TEST_CASE("parts: a step limit stops the parts in order - the ones not reached keep their start",
          "[fast]") {
    const ThreeParts t = threeParts();
    const MassSpringSystem start = compileSculpture(t.s).system;
    MassSpringSystem system = start;
    RelaxOptions options;
    options.maxSteps = 5;
    const RelaxResult result = FastRelaxer().relax(system, options);
    CHECK_FALSE(result.converged);
    CHECK(result.stopReason == "step limit");
    CHECK(result.steps == 5);
    CHECK(result.residual == residual(system));
    const auto components = freeComponents(start);
    int firstMoved = 0, othersMoved = 0;
    for (std::size_t j = 0; j < system.knotCount(); ++j) {
        const bool moved = !sameBits(system.position[j], start.position[j]);
        const int c = componentOf(components, static_cast<std::uint32_t>(j));
        firstMoved += c == 0 && moved ? 1 : 0;
        othersMoved += c > 0 && moved ? 1 : 0;
    }
    CHECK(firstMoved > 0);
    CHECK(othersMoved == 0);
    // Relaxed, then asked again with no steps at all: every part is in equilibrium already.
    REQUIRE(FastRelaxer().relax(system, RelaxOptions{}).converged);
    options.maxSteps = 0;
    const RelaxResult again = FastRelaxer().relax(system, options);
    CHECK(again.converged);
    CHECK(again.steps == 0);
    CHECK(again.stopReason == "converged");
}

TEST_CASE("parts: a part already in equilibrium is left alone, without an analysis", "[fast]") {
    ThreeParts t = threeParts();
    MassSpringSystem system = compileSculpture(t.s).system;
    REQUIRE(FastRelaxer().relax(system, RelaxOptions{}).converged);
    // A fresh relaxer (a document just opened) on the relaxed system: nothing to analyse.
    FastRelaxer opened;
    const RelaxResult again = opened.relax(system, RelaxOptions{});
    CHECK(again.converged);
    CHECK(again.steps == 0);
    CHECK(opened.statistics().partsInEquilibrium == 3);
    CHECK(opened.statistics().reusedAnalysis);
    CHECK(opened.statistics().analysisSeconds == 0);
    // The tube's bars 1 % longer: only its part is analysed and relaxed.
    const auto components = freeComponents(system);
    std::vector<std::int64_t> scratch;
    for (std::uint32_t b : extractPart(system, components[1], scratch).barOf)
        system.restLength[b] *= 1.01;
    FastRelaxer fresh;
    const RelaxResult edited = fresh.relax(system, RelaxOptions{});
    CHECK(edited.converged);
    CHECK(edited.steps > 0);
    CHECK(fresh.statistics().partsInEquilibrium == 2);
    CHECK_FALSE(fresh.statistics().reusedAnalysis);
}

TEST_CASE("parts: relaxed at the same time, one thread each, to the bits they have in turn",
          "[fast]") {
    const ThreeParts t = threeParts();
    const MassSpringSystem start = compileSculpture(t.s).system;
    MassSpringSystem together = start, inTurn = start;
    RelaxOptions options;
    options.threads = 2; // two parts at a time on any machine
    std::vector<RelaxProgress> reports;
    std::mutex reportsMutex; // (reports come one at a time; the lock only makes the test sure)
    options.progressInterval = 0;
    options.progress = [&](const RelaxProgress& p) {
        const std::lock_guard<std::mutex> lock(reportsMutex);
        reports.push_back(p);
    };
    FastRelaxer both;
    const RelaxResult a = both.relax(together, options);
    RelaxOptions oneThread;
    oneThread.threads = 1;
    FastRelaxer single;
    const RelaxResult b = single.relax(inTurn, oneThread);
    REQUIRE(a.converged);
    REQUIRE(b.converged);
    CHECK(both.statistics().partsTogether == 2);
    CHECK(single.statistics().partsTogether == 1);
    for (std::size_t j = 0; j < start.knotCount(); ++j)
        CHECK(sameBits(together.position[j], inTurn.position[j]));
    CHECK(a.steps == b.steps);
    CHECK(a.residual == residual(together));
    CHECK(both.statistics().iterations == single.statistics().iterations);
    CHECK(both.statistics().factorizations == single.statistics().factorizations);
    // Reports show the whole net, the steps of all parts summed.
    checkWholeReports(reports, start.knotCount(), a.steps);

    // The automatic thread count (the whole machine) takes every part at once, also where there
    // are more parts than cores; the bits are still those of the parts in turn.
    MassSpringSystem automatic = start;
    FastRelaxer all;
    const RelaxResult c = all.relax(automatic, RelaxOptions{});
    REQUIRE(c.converged);
    CHECK(all.statistics().partsTogether == (std::thread::hardware_concurrency() > 1 ? 3 : 1));
    for (std::size_t j = 0; j < start.knotCount(); ++j)
        CHECK(sameBits(automatic.position[j], inTurn.position[j]));
    CHECK(c.steps == b.steps);
}

TEST_CASE("parts: a step limit, or a part with most of the knots, relaxes them in turn",
          "[fast]") {
    const ThreeParts t = threeParts();
    MassSpringSystem system = compileSculpture(t.s).system;
    RelaxOptions limited;
    limited.threads = 2;
    limited.maxSteps = 1000;
    FastRelaxer relaxer;
    REQUIRE(relaxer.relax(system, limited).converged);
    CHECK(relaxer.statistics().partsTogether == 1);

    Sculpture big = t.s; // the sheet made the largest part by far
    setRows(big, t.sheet, 60);
    refreshAndValidate(big);
    MassSpringSystem lopsided = compileSculpture(big).system;
    RelaxOptions two;
    two.threads = 2;
    FastRelaxer other;
    REQUIRE(other.relax(lopsided, two).converged);
    CHECK(other.statistics().partsTogether == 1);
}
