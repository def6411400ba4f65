// DragPath (kernel/interaction/DragPath.h): a drag's next shape predicted from the last ones by
// the polynomial through them, checked on paths whose polynomial is known.

#include "interaction/DragPath.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace netsculpt;

namespace {

constexpr double kTolerance = 1e-3;

/// Two knots, the first held: the second at (p(t), 2 p(t), -p(t)) for a polynomial p.
std::vector<Vec3> shapeAt(double (*p)(double), double t) {
    return {Vec3{5, 6, 7}, Vec3{p(t), 2 * p(t), -p(t)}};
}

double cubic(double t) {
    return 0.3 - 0.7 * t + 0.25 * t * t + 0.125 * t * t * t;
}

/// A rest-length change of `size` along one edit (three bars).
std::vector<double> change(double size) {
    return {size, -2 * size, 0.5 * size};
}

/// The path of `p` through steps of the given sizes, from t = 0.
DragPath walk(double (*p)(double), const std::vector<double>& sizes) {
    DragPath path;
    double t = 0;
    for (double size : sizes) {
        path.add(shapeAt(p, t), shapeAt(p, t + size), change(size), kTolerance);
        t += size;
    }
    return path;
}

} // namespace

TEST_CASE("drag path: an edit repeats another when it is a multiple of it, at most twice it") {
    CHECK(repeatRatio(change(0.02), change(0.01), kTolerance) == Approx(2).epsilon(1e-15));
    CHECK(repeatRatio(change(0.005), change(0.01), kTolerance) == Approx(0.5).epsilon(1e-15));
    CHECK_FALSE(
        repeatRatio(change(0.03), change(0.01), kTolerance)); // three times: not a drag step
    CHECK_FALSE(repeatRatio(change(-0.01), change(0.01), kTolerance));        // back: another edit
    CHECK_FALSE(repeatRatio({0.01, -0.02, 0.006}, change(0.01), kTolerance)); // 1 % of it off
    CHECK_FALSE(repeatRatio(change(0.01), {0, 0, 0}, kTolerance));
    CHECK_FALSE(repeatRatio(change(0.01), {0.01, -0.02}, kTolerance)); // other bars
}

TEST_CASE("drag path: the polynomial of each degree through uneven steps, and a new path after "
          "another edit") {
    // Steps of 0.1, 0.15, 0.12 and 0.2 (each within twice the last) along a cubic path.
    const std::vector<double> sizes = {0.1, 0.15, 0.12, 0.2};
    const DragPath path = walk(cubic, sizes);
    REQUIRE(path.degrees() == 3);
    const double last = 0.57, next = last + 0.16; // the next step: 0.8 times the last
    const std::vector<std::uint8_t> fixed = {1, 0};
    std::vector<Vec3> predicted;

    path.predict(0.8, 3, fixed, predicted); // a cubic through four of its points is the cubic
    REQUIRE(predicted.size() == 2);
    CHECK(predicted[0].x == 5); // a held knot stays where it is
    CHECK(predicted[1].x == Approx(cubic(next)).epsilon(1e-13));
    CHECK(predicted[1].y == Approx(2 * cubic(next)).epsilon(1e-13));
    CHECK(predicted[1].z == Approx(-cubic(next)).epsilon(1e-13));

    // Degree 1: the secant, the last step's motion times the ratio of the edits.
    path.predict(0.8, 1, fixed, predicted);
    const double secant = cubic(last) + 0.8 * (cubic(last) - cubic(last - 0.2));
    CHECK(predicted[1].x == Approx(secant).epsilon(1e-13));
    // Degree 2 misses the cubic by its third-order term, the secant by more.
    path.predict(0.8, 2, fixed, predicted);
    const double quadraticMiss = std::abs(predicted[1].x - cubic(next));
    CHECK(quadraticMiss > 1e-6);
    CHECK(quadraticMiss < std::abs(secant - cubic(next)));

    // A step of another edit starts a new path: only the secant is left.
    DragPath other = walk(cubic, sizes);
    other.add(shapeAt(cubic, 0.57), shapeAt(cubic, 0.6), {0.03, 0.03, 0.03}, kTolerance);
    CHECK(other.degrees() == 1);
    CHECK_FALSE(other.ratio(change(0.01), kTolerance));
    // So does a step that does not start where the path ends.
    DragPath moved = walk(cubic, sizes);
    moved.add(shapeAt(cubic, 0.5), shapeAt(cubic, 0.6), change(0.1), kTolerance);
    CHECK(moved.degrees() == 1);
    DragPath none;
    CHECK(none.degrees() == 0);
    CHECK_FALSE(none.ratio(change(0.01), kTolerance));
}

TEST_CASE("drag path: a step cut short is carried into the next one, which goes on from the last "
          "shape") {
    // Steps of 0.1, 0.15, 0.12 along the cubic, then one of 0.1 cut short (its run stopped
    // somewhere off the path) and one of 0.08: together 1.5 times the last step.
    DragPath path = walk(cubic, {0.1, 0.15, 0.12});
    path.skip(change(0.1), kTolerance);
    const std::optional<double> rho = path.ratio(change(0.08), kTolerance);
    REQUIRE(rho);
    CHECK(*rho == Approx(1.5).epsilon(1e-12));
    const std::vector<std::uint8_t> fixed = {1, 0};
    std::vector<Vec3> predicted;
    path.predict(*rho, 3, fixed, predicted);
    CHECK(predicted[1].x == Approx(cubic(0.55)).epsilon(1e-13));

    // The step settles where it was predicted, from wherever the cut-short run stopped: the
    // path goes on through it, still exact for the cubic.
    path.add(shapeAt(cubic, 0.4), shapeAt(cubic, 0.55), change(0.08), kTolerance);
    REQUIRE(path.degrees() == 3);
    const std::optional<double> next = path.ratio(change(0.09), kTolerance);
    REQUIRE(next);
    CHECK(*next == Approx(0.5).epsilon(1e-12)); // of the last step, 0.18 with the skipped one
    path.predict(*next, 3, fixed, predicted);
    CHECK(predicted[1].x == Approx(cubic(0.64)).epsilon(1e-13));

    // A step from a shape that is no equilibrium (a run cut short far from it) starts a new path
    // at the step's end alone: the next step has nothing to predict from, the one after a secant.
    DragPath fresh = walk(cubic, {0.1, 0.15});
    fresh.add({}, shapeAt(cubic, 0.4), {0.03, 0.03, 0.03}, kTolerance);
    CHECK(fresh.degrees() == 0);
    fresh.add(shapeAt(cubic, 0.4), shapeAt(cubic, 0.43), {0.03, 0.03, 0.03}, kTolerance);
    CHECK(fresh.degrees() == 1);
    const std::optional<double> same = fresh.ratio({0.03, 0.03, 0.03}, kTolerance);
    REQUIRE(same);
    fresh.predict(*same, 1, fixed, predicted);
    CHECK(predicted[1].x == Approx(2 * cubic(0.43) - cubic(0.4)).epsilon(1e-13));

    // Another edit cut short ends the path; so do skipped steps beyond kMaxAhead of the last.
    DragPath other = walk(cubic, {0.1, 0.15, 0.12});
    other.skip({0.03, 0.03, 0.03}, kTolerance);
    CHECK(other.degrees() == 0);
    DragPath far = walk(cubic, {0.1, 0.15, 0.12});
    for (int i = 0; i < 4; ++i)
        far.skip(change(0.12), kTolerance);
    CHECK(far.degrees() == 3);
    CHECK_FALSE(far.ratio(change(0.12), kTolerance)); // five times the last step
    far.skip(change(0.12), kTolerance);
    CHECK(far.degrees() == 0);
}
