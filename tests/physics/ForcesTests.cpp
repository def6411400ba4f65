// Eq. 3 of the paper against hand-computed numbers, and the properties every evaluation has.
#include "model/Error.h"
#include "physics/Forces.h"
#include "physics/ReferenceNets.h"
#include "physics/ThreadPool.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>

using namespace netsculpt;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// Knot 0 fixed at the origin; knot 1 free at (0.3, 0, 0), bar 0 = (0, 1) of rest length 0.2
// (stretched by 0.1: k_s = 100 / 0.2 = 500 N/m, tension 50 N); knot 2 free at (0.3, 0.1, 0),
// bar 1 = (1, 2) of rest length 0.15 (compressed by 0.05: k_c = 0.01 * 100 / 0.15 N/m,
// tension -1/3 N).
MassSpringSystem threeKnots() {
    MassSpringSystem s;
    s.position = {{0, 0, 0}, {0.3, 0, 0}, {0.3, 0.1, 0}};
    s.mass = {0.01, 0.02, 0.03};
    s.fixed = {1, 0, 0};
    s.hold = {RailHold{RailId(1), 0}, {}, {}};
    s.barA = {0, 1};
    s.barB = {1, 2};
    s.restLength = {0.2, 0.15};
    s.kTension = {100 / 0.2, 100 / 0.15};
    s.kCompression = {0.01 * 100 / 0.2, 0.01 * 100 / 0.15};
    s.linearDensity = {0.006, 0.006};
    s.barPiece = {PieceId(1), PieceId(1)};
    return s;
}

void requireNear(const Vec3& actual, const Vec3& expected, double tolerance = 1e-12) {
    CHECK_THAT(actual.x, WithinAbs(expected.x, tolerance));
    CHECK_THAT(actual.y, WithinAbs(expected.y, tolerance));
    CHECK_THAT(actual.z, WithinAbs(expected.z, tolerance));
}

MassSpringSystem perturbedSheet(int rows, int columns) {
    SheetSpec spec;
    spec.rows = rows;
    spec.columns = columns;
    spec.material.stiffness = 100;
    MassSpringSystem s = makeSheet(spec);
    for (std::size_t j = 0; j < s.knotCount(); ++j)
        if (!s.fixed[j])
            s.position[j] +=
                Vec3{0.03 * std::sin(1.7 * j), 0.02 * std::cos(0.3 * j), 0.01 * std::sin(j)};
    return s;
}

/// The system with its bars in another order (bar b of the result is bar order[b] of s).
MassSpringSystem withBarOrder(const MassSpringSystem& s, const std::vector<std::size_t>& order) {
    MassSpringSystem r = s;
    for (std::size_t b = 0; b < order.size(); ++b) {
        r.barA[b] = s.barA[order[b]];
        r.barB[b] = s.barB[order[b]];
        r.restLength[b] = s.restLength[order[b]];
        r.kTension[b] = s.kTension[order[b]];
        r.kCompression[b] = s.kCompression[order[b]];
        r.linearDensity[b] = s.linearDensity[order[b]];
        r.barPiece[b] = s.barPiece[order[b]];
    }
    return r;
}

/// F_j the two-phase way: every bar's force (computeBars over ranges of `group` bars, so SIMD
/// groups and scalar tails fall on other bars than in evaluate()), then knotForce per knot.
std::vector<Vec3> twoPhaseForces(ForceField& field, const std::vector<Vec3>& positions,
                                 std::size_t group) {
    for (std::size_t b = 0; b < field.barCount(); b += group)
        field.computeBars(positions.data(), b, std::min(field.barCount(), b + group));
    std::vector<Vec3> force(field.knotCount());
    for (std::size_t j = 0; j < force.size(); ++j)
        force[j] = field.knotForce(j);
    return force;
}

bool sameBits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

} // namespace

TEST_CASE("Eq. 3 on three knots: k_s for the stretched bar, k_c for the compressed one",
          "[forces]") {
    const MassSpringSystem s = threeKnots();
    const double g = 9.81, compression = -0.01 * 100 / 0.15 * 0.05;

    const std::vector<double> tension = barTensions(s);
    REQUIRE(tension.size() == 2);
    CHECK_THAT(tension[0], WithinRel(50.0, 1e-12));
    CHECK_THAT(tension[1], WithinRel(compression, 1e-12));

    const std::vector<Vec3> force = knotForces(s);
    requireNear(force[0], {50, 0, -0.01 * g});
    requireNear(force[1], {-50, compression, -0.02 * g});
    requireNear(force[2], {0, -compression, -0.03 * g});

    const std::vector<double> r = knotResiduals(s);
    CHECK(r[0] == 0.0); // fixed
    CHECK_THAT(r[1], WithinRel(force[1].norm() / (0.02 * g), 1e-14));
    CHECK_THAT(r[2], WithinRel(force[2].norm() / (0.03 * g), 1e-14));
    CHECK(residual(s) == std::max(r[1], r[2]));

    const std::vector<Vec3> reaction = reactions(s);
    requireNear(reaction[0], -force[0]);
    requireNear(reaction[1], {});
    CHECK_THAT(totalWeight(s), WithinRel(0.06 * g, 1e-14));
}

TEST_CASE("The stiffness scale multiplies both spring constants", "[forces]") {
    const MassSpringSystem s = threeKnots();
    ForceField field(s);
    field.setLoad(std::nullopt, 0.25);
    std::vector<double> tension(2);
    field.computeBars(s.position.data(), 0, 2, tension.data());
    CHECK_THAT(tension[0], WithinRel(12.5, 1e-12));
    CHECK_THAT(tension[1], WithinRel(-0.25 * 0.01 * 100 / 0.15 * 0.05, 1e-12));
    CHECK_THROWS_AS(field.setLoad(std::nullopt, 0.0), UserError);
}

TEST_CASE("Wind loads each bar by q L times the wind's part normal to it, half per end",
          "[forces]") {
    const MassSpringSystem s = threeKnots();
    const Wind wind{{3, 3, 0}, 2.0}; // direction normalized to (1, 1, 0) / sqrt 2
    const std::vector<Vec3> calm = knotForces(s), windy = knotForces(s, wind);
    const double c = 1 / std::sqrt(2.0);
    // Bar 0 lies along x (length 0.3): (0, c, 0) * 2 * 0.3, half to knots 0 and 1.
    // Bar 1 lies along y (length 0.1): (c, 0, 0) * 2 * 0.1, half to knots 1 and 2.
    requireNear(windy[0] - calm[0], {0, 0.3 * c, 0});
    requireNear(windy[1] - calm[1], {0.1 * c, 0.3 * c, 0});
    requireNear(windy[2] - calm[2], {0.1 * c, 0, 0});

    CHECK_THROWS_AS(knotForces(s, Wind{{0, 0, 0}, 1}), UserError);
    CHECK_THROWS_AS(knotForces(s, Wind{{1, 0, 0}, -1}), UserError);
    CHECK_THROWS_AS(knotForces(s, Wind{{NAN, 0, 0}, 1}), UserError);
}

TEST_CASE("The wind's change with the knots' moves is the derivative of its load, and a frozen "
          "wind stays where it was taken",
          "[forces]") {
    const MassSpringSystem s = perturbedSheet(5, 6);
    const Wind wind{{1, 0.4, -0.2}, 0.7};
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::vector<Vec3> move(s.knotCount());
    for (std::size_t j = 0; j < s.knotCount(); ++j)
        move[j] = s.fixed[j] ? Vec3{} : Vec3{unit(random), unit(random), unit(random)};
    // The wind's load alone: the forces with it less those without.
    const auto windLoad = [&](double along) {
        MassSpringSystem moved = s;
        for (std::size_t j = 0; j < s.knotCount(); ++j)
            moved.position[j] += move[j] * along;
        const std::vector<Vec3> windy = knotForces(moved, wind), calm = knotForces(moved);
        std::vector<Vec3> load(s.knotCount());
        for (std::size_t j = 0; j < s.knotCount(); ++j)
            load[j] = windy[j] - calm[j];
        return load;
    };
    ForceField field(s);
    field.setLoad(wind);
    std::vector<Vec3> change(s.knotCount());
    field.windChange(s.position, move, change);
    const double h = 1e-6;
    const std::vector<Vec3> ahead = windLoad(h), behind = windLoad(-h);
    double largest = 0;
    for (std::size_t j = 0; j < s.knotCount(); ++j) {
        const Vec3 centred = (ahead[j] - behind[j]) / (2 * h);
        CHECK((change[j] - centred).norm() < 1e-7);
        largest = std::max(largest, centred.norm());
    }
    CHECK(largest > 0.01); // the moves do change the load

    // Frozen at the start, the load is the start's wherever the knots are evaluated.
    const std::vector<Vec3> startLoad = windLoad(0);
    field.freezeWind(s.position);
    MassSpringSystem moved = s;
    for (std::size_t j = 0; j < s.knotCount(); ++j)
        moved.position[j] += move[j] * 0.1;
    std::vector<Vec3> frozen(s.knotCount());
    field.evaluate(moved.position, frozen);
    const std::vector<Vec3> calm = knotForces(moved);
    for (std::size_t j = 0; j < s.knotCount(); ++j) {
        CHECK((frozen[j] - calm[j] - startLoad[j]).norm() < 1e-12);
        CHECK((field.knotWind(j) - startLoad[j]).norm() < 1e-12);
    }
    field.thawWind();
    field.evaluate(moved.position, frozen);
    const std::vector<Vec3> thawed = knotForces(moved, wind);
    for (std::size_t j = 0; j < s.knotCount(); ++j)
        CHECK((frozen[j] - thawed[j]).norm() < 1e-12);
}

TEST_CASE("Bar forces are internal: the knot forces sum to the weight in any state", "[forces]") {
    const MassSpringSystem s = perturbedSheet(7, 9);
    Vec3 sum;
    for (const Vec3& f : knotForces(s))
        sum += f;
    const double weight = totalWeight(s);
    CHECK_THAT(sum.x, WithinAbs(0, 1e-12));
    CHECK_THAT(sum.y, WithinAbs(0, 1e-12));
    CHECK_THAT(sum.z, WithinAbs(-weight, 1e-12));
    CHECK(barTensions(s).size() == s.barCount());
}

TEST_CASE("A bar of zero length exerts no force and makes no NaN", "[forces]") {
    MassSpringSystem s = threeKnots();
    s.position[2] = s.position[1];
    const std::vector<Vec3> force = knotForces(s);
    requireNear(force[2], {0, 0, -0.03 * 9.81});
    CHECK(std::isfinite(residual(s)));
}

TEST_CASE("The force is bit-identical with one or two threads", "[forces][determinism]") {
    const MassSpringSystem s = perturbedSheet(30, 40);
    ForceField field(s);
    field.setLoad(Wind{{1, 0.5, 0}, 0.3}, 0.7);
    std::vector<Vec3> one(s.knotCount()), two(s.knotCount());
    field.evaluate(s.position, one);
    ThreadPool pool(2);
    field.evaluate(s.position, two, &pool);
    REQUIRE(std::memcmp(one.data(), two.data(), one.size() * sizeof(Vec3)) == 0);
}

TEST_CASE("Without wind, evaluate's single pass gives the two-phase forces bit for bit on any "
          "number of threads and any bar order",
          "[forces][determinism]") {
    MassSpringSystem sheet = perturbedSheet(30, 40);
    sheet.position[sheet.barA[100]] = sheet.position[sheet.barB[100]]; // a bar of zero length
    TubeSpec tubeSpec;
    tubeSpec.rows = 25;
    tubeSpec.columns = 33;
    MassSpringSystem tube = makeTube(tubeSpec);
    for (std::size_t j = 0; j < tube.knotCount(); ++j)
        if (!tube.fixed[j])
            tube.position[j] += Vec3{0.004 * std::sin(0.7 * j), 0.003 * std::cos(1.3 * j), 0};
    // Bars of the sheet reversed (the pass walks them in index order, knots still local) and
    // shuffled (no locality at all: threads fall back to the two-phase way).
    std::vector<std::size_t> order(sheet.barCount());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::reverse(order.begin(), order.end());
    const MassSpringSystem reversed = withBarOrder(sheet, order);
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    const MassSpringSystem shuffled = withBarOrder(sheet, order);
    // Knots without bars (fixed, say a loose rail point) at the start, in the middle, at the end.
    MassSpringSystem loose = sheet;
    for (std::size_t j : {std::size_t{0}, std::size_t{600}, loose.knotCount()}) {
        loose.position.insert(loose.position.begin() + static_cast<std::ptrdiff_t>(j),
                              Vec3{1, 2, 3});
        loose.mass.insert(loose.mass.begin() + static_cast<std::ptrdiff_t>(j), 0.5);
        loose.fixed.insert(loose.fixed.begin() + static_cast<std::ptrdiff_t>(j), 1);
        for (auto* end : {&loose.barA, &loose.barB})
            for (std::uint32_t& k : *end)
                k += k >= j ? 1 : 0;
    }

    for (const MassSpringSystem* s : std::initializer_list<const MassSpringSystem*>{
             &sheet, &tube, &reversed, &shuffled, &loose}) {
        ForceField field(*s);
        for (double scale : {1.0, 0.3}) {
            field.setLoad(std::nullopt, scale);
            const std::vector<Vec3> reference = twoPhaseForces(field, s->position, 7);
            CHECK(sameBits(twoPhaseForces(field, s->position, s->barCount()), reference));
            std::vector<Vec3> force(s->knotCount());
            field.evaluate(s->position, force);
            CHECK(sameBits(force, reference));
            for (int threads : {2, 3}) {
                ThreadPool pool(threads);
                std::fill(force.begin(), force.end(), Vec3{NAN, NAN, NAN});
                field.evaluate(s->position, force, &pool);
                CHECK(sameBits(force, reference));
            }
        }
    }
}

TEST_CASE("A malformed system is a user error naming the culprit", "[forces]") {
    auto rejects = [](MassSpringSystem s, const char* word) {
        try {
            ForceField field(s);
            FAIL("accepted");
        } catch (const UserError& e) {
            CHECK_THAT(e.what(), Catch::Matchers::Contains(word));
        }
    };
    MassSpringSystem s = threeKnots();
    s.mass[1] = 0;
    rejects(s, "knot 1 has mass 0");
    s = threeKnots();
    s.barB[1] = 7;
    rejects(s, "bar 1 joins knots 1 and 7");
    s = threeKnots();
    s.restLength[0] = -1;
    rejects(s, "bar 0 has rest length -1");
    s = threeKnots();
    s.kTension[1] = 0;
    rejects(s, "bar 1 has kTension 0");
    s = threeKnots();
    s.barA.pop_back();
    s.barB.pop_back();
    s.restLength.pop_back();
    s.kTension.pop_back();
    s.kCompression.pop_back();
    rejects(s, "knot 2 is free and has no bar");
    s = threeKnots();
    s.gravity = {0, 0, 0};
    rejects(s, "gravity");
    s = threeKnots();
    s.kCompression.push_back(1);
    rejects(s, "kCompression has 3 entries, expected 2");
}

TEST_CASE("setLaw gives the field a new system of the same topology would have, and refuses a "
          "bad law as the constructor does",
          "[forces]") {
    const MassSpringSystem s = perturbedSheet(30, 40);
    MassSpringSystem edited = s;
    for (std::size_t b = 0; b < edited.barCount(); ++b) {
        edited.restLength[b] *= 1.0 + 0.01 * static_cast<double>(b % 7);
        edited.kTension[b] *= 0.5;
        edited.kCompression[b] *= 2.0;
    }
    for (double& m : edited.mass)
        m *= 1.25;
    edited.gravity = {0.1, 0, -9.7};
    ForceField updated(s);
    updated.setLaw(edited);
    ForceField built(edited);
    for (double scale : {1.0, 0.3}) {
        updated.setLoad(Wind{{1, 0.5, 0}, 0.3}, scale);
        built.setLoad(Wind{{1, 0.5, 0}, 0.3}, scale);
        std::vector<Vec3> a(s.knotCount()), b(s.knotCount());
        updated.evaluate(s.position, a);
        built.evaluate(s.position, b);
        CHECK(sameBits(a, b));
        CHECK(updated.maxResidual(a) == built.maxResidual(b));
    }
    CHECK(built.maxResidual(std::vector<Vec3>(s.knotCount())) == 0);

    // A refused law names the culprit and leaves the field as it was.
    MassSpringSystem bad = edited;
    bad.restLength[5] = 0;
    bad.mass[9] = -1;
    CHECK_THROWS_WITH(updated.setLaw(bad), Catch::Contains("knot 9 has mass -1"));
    bad.mass[9] = 1;
    CHECK_THROWS_WITH(updated.setLaw(bad), Catch::Contains("bar 5 has rest length 0"));
    updated.setLoad(std::nullopt, 1.0);
    built.setLoad(std::nullopt, 1.0);
    std::vector<Vec3> a(s.knotCount()), b(s.knotCount());
    updated.evaluate(s.position, a);
    built.evaluate(s.position, b);
    CHECK(sameBits(a, b));
    std::vector<double> stiff(s.barCount(), 1e3);
    updated.setCompressionStiffness(stiff);
    MassSpringSystem hard = edited;
    hard.kCompression = stiff;
    ForceField hardField(hard);
    updated.evaluate(s.position, a);
    hardField.evaluate(s.position, b);
    CHECK(sameBits(a, b));
}
