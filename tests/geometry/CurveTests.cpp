// Tests for kernel/geometry/Curve: polylines and B-splines, arc-length and parameter sampling.
// Expected values are computed here by hand or from closed forms (circle, Bezier, uniform
// B-spline knot weights), never by calling the code under test a second way.

#include "geometry/Curve.h"
#include "model/Error.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

using namespace netsculpt;
using Catch::Contains;

namespace {

constexpr double pi = std::numbers::pi;

CurveSpec polyline(std::vector<Vec3> points, bool closed = false,
                   Sampling sampling = Sampling::ArcLength) {
    CurveSpec spec;
    spec.points = std::move(points);
    spec.closed = closed;
    spec.sampling = sampling;
    return spec;
}

CurveSpec bspline(std::vector<Vec3> control, int degree, bool closed = false,
                  Sampling sampling = Sampling::ArcLength, std::vector<double> knots = {},
                  std::vector<double> weights = {}) {
    CurveSpec spec;
    spec.spline = true;
    spec.points = std::move(control);
    spec.degree = degree;
    spec.closed = closed;
    spec.sampling = sampling;
    spec.knots = std::move(knots);
    spec.weights = std::move(weights);
    return spec;
}

/// Checks |a - b| <= tolerance, printing both points on failure.
void checkNear(const Vec3& a, const Vec3& b, double tolerance) {
    INFO("(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z
             << ")");
    CHECK(distance(a, b) <= tolerance);
}

std::vector<double> chordLengths(const std::vector<Vec3>& points) {
    std::vector<double> chords;
    for (std::size_t i = 0; i + 1 < points.size(); ++i)
        chords.push_back(distance(points[i], points[i + 1]));
    return chords;
}

/// (max - min) / mean of a list of lengths.
double relativeSpread(const std::vector<double>& values) {
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    double mean = 0;
    for (double v : values)
        mean += v / double(values.size());
    return (*hi - *lo) / mean;
}

// The standard 9-point rational quadratic circle: corners of the square around the circle
// carry weight sqrt(2)/2, double knots at the quarters make each quarter a conic arc.
const Vec3 circleCentre{1, -2, 3};
constexpr double circleRadius = 2.5;

std::vector<Vec3> circleControl(int count) {
    const double xs[] = {1, 1, 0, -1, -1, -1, 0, 1, 1};
    const double ys[] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
    std::vector<Vec3> control;
    for (int i = 0; i < count; ++i)
        control.push_back(circleCentre + Vec3{xs[i], ys[i], 0} * circleRadius);
    return control;
}

std::vector<double> circleWeights(int count) {
    std::vector<double> weights;
    for (int i = 0; i < count; ++i)
        weights.push_back(i % 2 == 0 ? 1.0 : std::sqrt(2.0) / 2);
    return weights;
}

Vec3 onCircle(double angle) {
    return circleCentre + Vec3{std::cos(angle), std::sin(angle), 0} * circleRadius;
}

// A cubic whose control polygon is very uneven, so equal parameter steps are unequal in length.
std::vector<Vec3> unevenControl() {
    return {{0, 0, 0},    {0.3, 0.1, 0}, {0.6, 0.5, 0.1}, {4, 3, 0},
            {8, -1, 0.5}, {12, 2, 0},    {12.5, 2.2, 0}};
}

// Square control polygon: rotating by +90 degrees about z maps control point i to i + 1.
std::vector<Vec3> squareControl() {
    return {{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}};
}
Vec3 rotate90(const Vec3& p) {
    return {-p.y, p.x, p.z};
}

} // namespace

TEST_CASE("open L-shaped polyline: length, positions, clamping", "[curve][polyline]") {
    // Legs of 3 m along x and 4 m along y: 7 m in all.
    const std::vector<Vec3> points{{0, 0, 0}, {3, 0, 0}, {3, 4, 0}};
    const Curve arc = Curve::build(polyline(points));
    CHECK(arc.length() == Approx(7.0).epsilon(1e-15));
    checkNear(arc.pointAt(0.5), {3, 0.5, 0}, 1e-14);   // 3.5 m along
    checkNear(arc.pointAt(3.0 / 7), {3, 0, 0}, 1e-14); // the corner
    checkNear(arc.pointAt(2.0 / 7), {2, 0, 0}, 1e-14);
    checkNear(arc.pointAt(1.0), {3, 4, 0}, 0);
    // Open curves clamp t to [0, 1].
    checkNear(arc.pointAt(-0.5), {0, 0, 0}, 0);
    checkNear(arc.pointAt(1.5), {3, 4, 0}, 0);
    checkNear(arc.tangentAt(0.2), {1, 0, 0}, 1e-15);
    checkNear(arc.tangentAt(0.9), {0, 1, 0}, 1e-15);
    checkNear(arc.tangentAt(1.0), {0, 1, 0}, 1e-15);
    // (4, 2) is nearest to (3, 2), 5 m along.
    CHECK(arc.nearestPosition({4, 2, 0}) == Approx(5.0 / 7).epsilon(1e-14));
    CHECK(arc.nearestPosition({-1, -1, 0}) == 0.0);
    CHECK(arc.nearestPosition({3, 9, 0}) == 1.0);

    // Parameter sampling: each segment takes half of t, whatever its length.
    const Curve param = Curve::build(polyline(points, false, Sampling::Parameter));
    checkNear(param.pointAt(0.25), {1.5, 0, 0}, 1e-15);
    checkNear(param.pointAt(0.5), {3, 0, 0}, 1e-15);
    checkNear(param.pointAt(0.75), {3, 2, 0}, 1e-15);
    CHECK(param.nearestPosition({4, 2, 0}) == Approx(0.75).epsilon(1e-15));
    CHECK(param.length() == Approx(7.0).epsilon(1e-15));
    // What a tape along the rail measures: 1.5 m to t = 0.25 and 5 m to t = 0.75 (3 + 2).
    CHECK(param.distanceAlong(0.25) == Approx(1.5).epsilon(1e-15));
    CHECK(param.distanceAlong(0.75) == Approx(5.0).epsilon(1e-15));
    CHECK(arc.distanceAlong(0.75) == Approx(5.25).epsilon(1e-15));
    CHECK(param.distanceAlong(1.5) == Approx(7.0).epsilon(1e-15)); // open: clamped to the end
}

TEST_CASE("distance along a spline rail under either sampling") {
    // Quadratic Bezier on the x axis through (0), (1), (4): x(u) = 2u + 2u^2, 4 m long.
    const std::vector<Vec3> control{{0, 0, 0}, {1, 0, 0}, {4, 0, 0}};
    const Curve param = Curve::build(bspline(control, 2, false, Sampling::Parameter));
    const Curve arc = Curve::build(bspline(control, 2, false, Sampling::ArcLength));
    CHECK(param.distanceAlong(0.5) == Approx(1.5).epsilon(1e-12)); // x(0.5)
    CHECK(param.distanceAlong(0.25) == Approx(0.625).epsilon(1e-12));
    CHECK(param.distanceAlong(1.0) == Approx(4.0).epsilon(1e-12));
    CHECK(arc.distanceAlong(0.5) == Approx(2.0).epsilon(1e-12));
    // A closed 1 x 3 rectangle (8 m round), each side a quarter of t under parameter sampling:
    // t = 0.9 is 1 + 3 + 1 + 0.6 x 3 = 6.8 m along it, by arc length 7.2 m; t = -0.1 wraps to it.
    const std::vector<Vec3> rectangle{{0, 0, 0}, {1, 0, 0}, {1, 3, 0}, {0, 3, 0}};
    const Curve byParameter = Curve::build(polyline(rectangle, true, Sampling::Parameter));
    const Curve byLength = Curve::build(polyline(rectangle, true, Sampling::ArcLength));
    CHECK(byParameter.distanceAlong(0.9) == Approx(6.8).epsilon(1e-14));
    CHECK(byParameter.distanceAlong(-0.1) == Approx(6.8).epsilon(1e-14));
    CHECK(byLength.distanceAlong(0.9) == Approx(7.2).epsilon(1e-14));
}

TEST_CASE("polyline: consecutive duplicate points add no segment", "[curve][polyline]") {
    const Curve curve =
        Curve::build(polyline({{0, 0, 0}, {0, 0, 0}, {3, 0, 0}, {3, 0, 0}, {3, 4, 0}, {3, 4, 0}},
                              false, Sampling::Parameter));
    CHECK(curve.length() == Approx(7.0).epsilon(1e-15));
    checkNear(curve.pointAt(0.5), {3, 0, 0}, 1e-15); // still two segments
    checkNear(curve.pointAt(0.25), {1.5, 0, 0}, 1e-15);
}

TEST_CASE("closed square polyline: length, wrap-around, samples, nearest", "[curve][polyline]") {
    const Curve square = Curve::build(polyline({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, true));
    CHECK(square.closed());
    CHECK(square.length() == Approx(8.0).epsilon(1e-15)); // includes the closing side
    checkNear(square.pointAt(0.125), {1, 0, 0}, 1e-15);
    checkNear(square.pointAt(0.375), {2, 1, 0}, 1e-15);
    checkNear(square.pointAt(0.875), {0, 1, 0}, 1e-15); // on the closing side
    // Wrap-around: t is taken modulo 1.
    checkNear(square.pointAt(1.0), {0, 0, 0}, 0);
    checkNear(square.pointAt(-0.125), {0, 1, 0}, 1e-15);
    checkNear(square.pointAt(2.375), {2, 1, 0}, 1e-15);
    checkNear(square.pointAt(-1e-20), {0, 0, 0}, 1e-15);
    checkNear(square.tangentAt(0.9), {0, -1, 0}, 1e-15);

    const std::vector<Vec3> samples = square.samplePoints(0.0625, 0.25, 5);
    REQUIRE(samples.size() == 5);
    checkNear(samples[0], {0.5, 0, 0}, 1e-15);
    checkNear(samples[1], {2, 0.5, 0}, 1e-15);
    checkNear(samples[2], {1.5, 2, 0}, 1e-15);
    checkNear(samples[3], {0, 1.5, 0}, 1e-15);
    checkNear(samples[4], {0.5, 0, 0}, 1e-15); // wrapped once round
    CHECK(square.samplePoints(0, 0.1, 0).empty());

    CHECK(square.nearestPosition({1, -1, 0}) == Approx(0.125).epsilon(1e-15));
    CHECK(square.nearestPosition({-1, 1, 5}) == Approx(0.875).epsilon(1e-15));
    CHECK(square.nearestPosition({-1, -1, 0}) == 0.0); // the seam is 0, never 1

    // Repeating the first point at the end closes the same square.
    const Curve explicitClose = Curve::build(polyline(
        {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 0}}, true, Sampling::Parameter));
    CHECK(explicitClose.length() == Approx(8.0).epsilon(1e-15));
    checkNear(explicitClose.pointAt(0.875), {0, 1, 0}, 1e-15); // 4 segments, not 5
}

TEST_CASE("NURBS circle as an open clamped spline: radius, length, arc-length angle",
          "[curve][bspline]") {
    const std::vector<double> knots{0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
    for (Sampling sampling : {Sampling::ArcLength, Sampling::Parameter}) {
        const Curve circle =
            Curve::build(bspline(circleControl(9), 2, false, sampling, knots, circleWeights(9)));
        CHECK(circle.length() == Approx(2 * pi * circleRadius).epsilon(1e-8).margin(0));
        for (double t = 0; t <= 1; t += 1.0 / 997)
            CHECK(std::abs(distance(circle.pointAt(t), circleCentre) - circleRadius) <= 1e-12);
    }
    const Curve circle = Curve::build(
        bspline(circleControl(9), 2, false, Sampling::ArcLength, knots, circleWeights(9)));
    // Arc length on a circle is angle times radius, so t = angle / 2 pi.
    for (double t = 0; t <= 1; t += 1.0 / 101) {
        checkNear(circle.pointAt(t), onCircle(2 * pi * t), 1e-10);
        checkNear(circle.tangentAt(t), {-std::sin(2 * pi * t), std::cos(2 * pi * t), 0}, 1e-10);
    }
    for (double angle : {0.3, 1.9, 3.3, 5.0}) {
        const Vec3 outside =
            circleCentre + Vec3{std::cos(angle), std::sin(angle), 0} * 4 + Vec3{0, 0, 0.5};
        CHECK(circle.nearestPosition(outside) == Approx(angle / (2 * pi)).epsilon(1e-10));
        const Vec3 inside = circleCentre + Vec3{std::cos(angle), std::sin(angle), 0} * 1;
        CHECK(circle.nearestPosition(inside) == Approx(angle / (2 * pi)).epsilon(1e-10));
    }
}

TEST_CASE("NURBS circle as a closed periodic spline with explicit knots", "[curve][bspline]") {
    // 8 control points, wrapped to P0..P7, P0, P1: 13 knots, period 4, double knots at the
    // points the arcs pass through. The range [knots[2], knots[10]] = [1, 5] starts at P0.
    const std::vector<double> knots{0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6};
    const Curve circle = Curve::build(
        bspline(circleControl(8), 2, true, Sampling::ArcLength, knots, circleWeights(8)));
    CHECK(circle.length() == Approx(2 * pi * circleRadius).epsilon(1e-8).margin(0));
    for (double t = -0.5; t <= 1.5; t += 1.0 / 499) {
        CHECK(std::abs(distance(circle.pointAt(t), circleCentre) - circleRadius) <= 1e-12);
        checkNear(circle.pointAt(t), onCircle(2 * pi * t), 1e-10);
    }
    CHECK(circle.nearestPosition(onCircle(5.5)) == Approx(5.5 / (2 * pi)).epsilon(1e-10));
}

TEST_CASE("arc-length sampling of a cubic is equally spaced - parameter sampling is not",
          "[curve][bspline]") {
    const Curve arc = Curve::build(bspline(unevenControl(), 3));
    const Curve param = Curve::build(bspline(unevenControl(), 3, false, Sampling::Parameter));
    CHECK(arc.length() == Approx(param.length()).epsilon(1e-15));

    // Fine sampling: chords are arcs to ~(kappa s)^2 / 24, so they must all be equal.
    const int fine = 40000;
    const std::vector<double> chords = chordLengths(arc.samplePoints(0, 1.0 / fine, fine + 1));
    CHECK(relativeSpread(chords) < 1e-6);
    double chordSum = 0;
    for (double c : chords)
        chordSum += c;
    CHECK(chordSum == Approx(arc.length()).epsilon(1e-7));

    // Coarse sampling: each arc between consecutive samples, measured by 2m fine chords and
    // by m chords, Richardson-extrapolated (chord error ~ h^2): arcs must be equal to ~1e-9,
    // far below the spread of the coarse chords themselves.
    const int coarse = 100, m = 200;
    const double d = 1.0 / coarse;
    std::vector<double> arcs;
    for (int i = 0; i < coarse; ++i) {
        const std::vector<Vec3> p = arc.samplePoints(i * d, d / (2 * m), 2 * m + 1);
        double fineSum = 0, halfSum = 0;
        for (int k = 0; k < 2 * m; ++k)
            fineSum += distance(p[k], p[k + 1]);
        for (int k = 0; k < 2 * m; k += 2)
            halfSum += distance(p[k], p[k + 2]);
        arcs.push_back((4 * fineSum - halfSum) / 3);
    }
    CHECK(relativeSpread(arcs) < 1e-9);
    CHECK(arcs.front() == Approx(arc.length() / coarse).epsilon(1e-9));
    CHECK(relativeSpread(chordLengths(arc.samplePoints(0, d, coarse + 1))) > 1e-5);

    // Equal parameter steps of this curve are visibly unequal in length.
    CHECK(relativeSpread(chordLengths(param.samplePoints(0, 1.0 / 200, 201))) > 0.01);
    // Both samplings run from the first control point to the last (clamped knots).
    checkNear(param.pointAt(0), unevenControl().front(), 1e-15);
    checkNear(param.pointAt(1), unevenControl().back(), 1e-14);
    checkNear(arc.pointAt(1), unevenControl().back(), 1e-14);
}

TEST_CASE("closed uniform cubic on a square: closure, 4-fold symmetry, known points",
          "[curve][bspline]") {
    for (Sampling sampling : {Sampling::ArcLength, Sampling::Parameter}) {
        const Curve curve = Curve::build(bspline(squareControl(), 3, true, sampling));
        // Uniform cubic: at a knot the curve is (P0 + 4 P1 + P2) / 6, mid-span
        // (P0 + 23 P1 + 23 P2 + P3) / 48.
        checkNear(curve.pointAt(0), {-2.0 / 3, 2.0 / 3, 0}, 1e-15);
        checkNear(curve.pointAt(0.125), {-11.0 / 12, 0, 0}, 1e-12);
        checkNear(curve.pointAt(1), curve.pointAt(0), 0);
        checkNear(curve.pointAt(1 - 1e-12), curve.pointAt(0), 1e-11);
        // Smooth through the closure: tangents just before and after average to the one at
        // the seam (the first-order turn cancels; a kink would not).
        checkNear((curve.tangentAt(-1e-6) + curve.tangentAt(1e-6)) / 2, curve.tangentAt(0), 1e-10);
        CHECK(distance(curve.tangentAt(-1e-6), curve.tangentAt(1e-6)) < 1e-4);
        checkNear(curve.tangentAt(0), Vec3{-1, -1, 0} / std::sqrt(2.0), 1e-14);
        for (double t = 0; t < 1; t += 1.0 / 61) {
            checkNear(curve.pointAt(t + 0.25), rotate90(curve.pointAt(t)), 1e-12);
            checkNear(curve.tangentAt(t + 0.25), rotate90(curve.tangentAt(t)), 1e-12);
        }
    }
}

TEST_CASE("B-spline special cases match closed forms", "[curve][bspline]") {
    SECTION("degree 1 with clamped uniform knots is the polyline, in both samplings") {
        const std::vector<Vec3> points{{0, 0, 0}, {3, 0, 0}, {3, 4, 0}, {5, 4, 1}};
        for (Sampling sampling : {Sampling::ArcLength, Sampling::Parameter}) {
            const Curve line = Curve::build(polyline(points, false, sampling));
            const Curve spline = Curve::build(bspline(points, 1, false, sampling));
            CHECK(spline.length() == Approx(7 + std::sqrt(5.0)).epsilon(1e-14));
            for (double t = 0; t <= 1; t += 1.0 / 37)
                checkNear(spline.pointAt(t), line.pointAt(t), 1e-12);
        }
    }
    SECTION("a cubic Bezier (knots 0000 1111, any scale)") {
        const std::vector<Vec3> p{{0, 0, 0}, {1, 2, 0}, {3, 2, 1}, {4, 0, 0}};
        const Curve bezier =
            Curve::build(bspline(p, 3, false, Sampling::Parameter, {2, 2, 2, 2, 5, 5, 5, 5}));
        for (double t : {0.0, 0.3, 0.5, 0.8, 1.0}) {
            const double s = 1 - t;
            const Vec3 expected = p[0] * (s * s * s) + p[1] * (3 * s * s * t) +
                                  p[2] * (3 * s * t * t) + p[3] * (t * t * t);
            checkNear(bezier.pointAt(t), expected, 1e-14);
        }
    }
    SECTION("an unclamped uniform quadratic starts and ends at control-leg midpoints") {
        const std::vector<Vec3> p{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
        const Curve curve =
            Curve::build(bspline(p, 2, false, Sampling::Parameter, {0, 1, 2, 3, 4, 5, 6}));
        checkNear(curve.pointAt(0), {1, 0, 0}, 1e-15);
        checkNear(curve.pointAt(0.5), {2, 1, 0}, 1e-15);
        checkNear(curve.pointAt(1), {1, 2, 0}, 1e-15);
    }
    SECTION("equal weights other than 1 do not change the curve") {
        const Curve plain = Curve::build(bspline(unevenControl(), 3));
        const Curve weighted = Curve::build(bspline(unevenControl(), 3, false, Sampling::ArcLength,
                                                    {}, std::vector<double>(7, 2.5)));
        CHECK(weighted.length() == Approx(plain.length()).epsilon(1e-14));
        for (double t = 0; t <= 1; t += 0.1)
            checkNear(weighted.pointAt(t), plain.pointAt(t), 1e-12);
    }
    SECTION("degree 7 runs from first to last control point with equal arc spacing") {
        std::vector<Vec3> p;
        for (int i = 0; i < 10; ++i)
            p.push_back({double(i), std::sin(i * 1.3) * 2, 0.1 * i * i});
        const Curve curve = Curve::build(bspline(p, 7));
        checkNear(curve.pointAt(0), p.front(), 1e-14);
        checkNear(curve.pointAt(1), p.back(), 1e-13);
        CHECK(relativeSpread(chordLengths(curve.samplePoints(0, 1e-4, 10001))) < 1e-6);
    }
    SECTION("a zero derivative at a clamped end still has a tangent") {
        // P0 = P1: the curve leaves P0 towards P2 (second derivative direction).
        const Curve curve =
            Curve::build(bspline({{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0}}, 3));
        checkNear(curve.tangentAt(0), {1, 0, 0}, 1e-6);
        CHECK(curve.tangentAt(0).norm() == Approx(1.0).epsilon(1e-15));
    }
}

TEST_CASE("tangent and nearest position agree with the points", "[curve][bspline]") {
    const Curve curve = Curve::build(bspline(unevenControl(), 3));
    const double h = 1e-6;
    for (double t = 0.05; t < 0.96; t += 0.05) {
        const Vec3 difference = curve.pointAt(t + h) - curve.pointAt(t - h);
        checkNear(curve.tangentAt(t), difference / difference.norm(), 1e-6);
        CHECK(curve.nearestPosition(curve.pointAt(t)) == Approx(t).epsilon(1e-10));
        // A point off the curve, perpendicular to it, is nearest to the same rail position.
        const Vec3 side = curve.tangentAt(t).cross({0, 0, 1});
        const Vec3 off = curve.pointAt(t) + side / side.norm() * 1e-3;
        CHECK(curve.nearestPosition(off) == Approx(t).epsilon(1e-9));
    }
    CHECK(curve.nearestPosition({-5, -5, 0}) == 0.0);
    CHECK(curve.nearestPosition({20, 2.2, 0}) == 1.0);
}

TEST_CASE("copies of a curve answer the same", "[curve]") {
    const Curve original = Curve::build(bspline(squareControl(), 3, true));
    const Curve copy = original; // NOLINT(performance-unnecessary-copy-initialization)
    CHECK(copy.length() == original.length());
    CHECK(copy.pointAt(0.3) == original.pointAt(0.3));
    CHECK(copy.spec().points.size() == 4);
}

TEST_CASE("bad curve input throws UserError naming the value", "[curve][errors]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const Vec3 a{0, 0, 0};
    const std::vector<Vec3> four{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<Vec3> five{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 2, 0}};
    const std::vector<Vec3> six{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 2, 0}, {1, 2, 0}};

    SECTION("too few distinct polyline points") {
        REQUIRE_THROWS_AS(Curve::build(polyline({})), UserError);
        REQUIRE_THROWS_WITH(Curve::build(polyline({})),
                            Contains("at least 2 distinct points, got 0"));
        REQUIRE_THROWS_WITH(Curve::build(polyline({a})), Contains("got 1 distinct among 1 points"));
        REQUIRE_THROWS_WITH(Curve::build(polyline({a, a, a})), Contains("got 1 distinct among 3"));
        REQUIRE_THROWS_WITH(Curve::build(polyline({a, {0, 0, 1e-320}}, true)),
                            Contains("got 1 distinct"));
    }
    SECTION("a closed polyline that encloses nothing") {
        // There and back along one line: a "loop" of twice the line's length.
        REQUIRE_THROWS_WITH(Curve::build(polyline({{0, 0, 5}, {4, 0, 5}, {0, 0, 5}}, true)),
                            Contains("a closed polyline needs at least 3 distinct points not on "
                                     "one line") &&
                                Contains("got 2 distinct among 3 points"));
        REQUIRE_THROWS_WITH(Curve::build(polyline({{0, 0, 1}, {1, 0, 1}, {3, 0, 1}}, true)),
                            Contains("got 3 distinct among 3 points, all on one line"));
        // Open, the same points are a fine rail; closed, a thin triangle is a loop.
        CHECK(Curve::build(polyline({{0, 0, 1}, {1, 0, 1}, {3, 0, 1}})).length() == 3);
        CHECK(Curve::build(polyline({{0, 0, 1}, {1, 1e-6, 1}, {3, 0, 1}}, true)).length() > 6);
    }
    SECTION("non-finite coordinates") {
        REQUIRE_THROWS_WITH(Curve::build(polyline({a, {0, nan, 0}})),
                            Contains("rail: point 1 has a non-finite coordinate (nan)"));
        std::vector<Vec3> control = five;
        control[3].z = -inf;
        REQUIRE_THROWS_WITH(Curve::build(bspline(control, 3)),
                            Contains("control point 3 has a non-finite coordinate (-inf)"));
    }
    SECTION("degree and control point count") {
        REQUIRE_THROWS_WITH(Curve::build(bspline(four, 0)), Contains("degree 0 is out of range"));
        REQUIRE_THROWS_WITH(Curve::build(bspline(four, 8)), Contains("degree 8 is out of range"));
        REQUIRE_THROWS_WITH(
            Curve::build(bspline({a, {1, 0, 0}}, 3)),
            Contains("a B-spline of degree 3 needs at least 4 control points, got 2"));
        REQUIRE_THROWS_WITH(Curve::build(bspline({a, {1, 0, 0}, {1, 1, 0}}, 3, true)),
                            Contains("needs at least 4 control points, got 3"));
    }
    SECTION("knot vectors") {
        REQUIRE_THROWS_WITH(
            Curve::build(bspline(five, 3, false, Sampling::ArcLength, {0, 0, 0, 0, 1, 1, 1})),
            Contains(
                "knot vector has 7 values; a degree-3 B-spline with 5 control points needs 9"));
        REQUIRE_THROWS_WITH(
            Curve::build(bspline(five, 3, true, Sampling::ArcLength, {0, 1, 2, 3, 4, 5, 6, 7, 8})),
            Contains("needs 12"));
        const std::vector<Vec3> three{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
        REQUIRE_THROWS_WITH(
            Curve::build(bspline(three, 1, false, Sampling::ArcLength, {0, 0, 0.7, 0.5, 1})),
            Contains("knot 3 (0.5) is less than knot 2 (0.7)"));
        REQUIRE_THROWS_WITH(
            Curve::build(bspline(three, 1, false, Sampling::ArcLength, {0, 0, nan, 1, 1})),
            Contains("knot 2 is not finite (nan)"));
        REQUIRE_THROWS_WITH(
            Curve::build(bspline({a, {1, 0, 0}}, 1, false, Sampling::ArcLength, {0, 1, 1, 2})),
            Contains("= [1, 1] is empty"));
        REQUIRE_THROWS_WITH(Curve::build(bspline(six, 2, false, Sampling::ArcLength,
                                                 {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1})),
                            Contains("knot value 0.5 is repeated 3 times"));
        // The range [0, 0.5] ends before control points 3 and 4 begin to count.
        REQUIRE_THROWS_WITH(Curve::build(bspline(five, 2, false, Sampling::ArcLength,
                                                 {0, 0, 0, 0.5, 0.5, 0.5, 1, 1})),
                            Contains("control point 3 has no influence"));
        REQUIRE_THROWS_WITH(
            Curve::build(bspline(four, 2, true, Sampling::ArcLength, {0, 1, 2, 3, 4, 5, 6, 7, 9})),
            Contains("knots[8] - knots[4] = 5"));
    }
    SECTION("weights") {
        REQUIRE_THROWS_WITH(Curve::build(bspline(four, 3, false, Sampling::ArcLength, {}, {1, 1})),
                            Contains("2 weights given for 4 control points"));
        REQUIRE_THROWS_WITH(
            Curve::build(bspline(four, 3, false, Sampling::ArcLength, {}, {1, 0, 1, 1})),
            Contains("weight 1 is 0"));
        REQUIRE_THROWS_WITH(
            Curve::build(bspline(four, 3, false, Sampling::ArcLength, {}, {1, 1, -1.5, 1})),
            Contains("weight 2 is -1.5"));
        REQUIRE_THROWS_WITH(
            Curve::build(bspline(four, 3, false, Sampling::ArcLength, {}, {nan, 1, 1, 1})),
            Contains("weight 0 is nan"));
    }
    SECTION("degenerate geometry") {
        const Vec3 p{1, 2, 3};
        REQUIRE_THROWS_WITH(Curve::build(bspline({p, p, p, p}, 3)),
                            Contains("all 4 control points are equal (1, 2, 3)"));
        // Distinct, but too close for their distance to be represented: zero length.
        REQUIRE_THROWS_WITH(Curve::build(bspline({a, {1e-200, 0, 0}, {0, 1e-200, 0}, a}, 3)),
                            Contains("zero length"));
        REQUIRE_THROWS_WITH(Curve::build(polyline({{-1e308, 0, 0}, {1e308, 0, 0}})),
                            Contains("length is not finite (inf)"));
    }
    SECTION("polyline fields that belong to B-splines") {
        CurveSpec spec = polyline(four);
        spec.degree = 3;
        REQUIRE_THROWS_WITH(Curve::build(spec), Contains("a polyline has degree 1, got 3"));
        spec = polyline(four);
        spec.knots = {0, 1};
        REQUIRE_THROWS_WITH(Curve::build(spec), Contains("takes no knot vector, got 2 knots"));
    }
    SECTION("non-finite rail positions and negative counts") {
        const Curve curve = Curve::build(polyline(four));
        REQUIRE_THROWS_WITH(curve.pointAt(nan), Contains("rail position is nan"));
        REQUIRE_THROWS_WITH(curve.tangentAt(inf), Contains("rail position is inf"));
        REQUIRE_THROWS_WITH(curve.samplePoints(0, 0.1, -1), Contains("sample count -1"));
        REQUIRE_THROWS_WITH(curve.nearestPosition({nan, 0, 0}), Contains("(nan, 0, 0)"));
    }
}

TEST_CASE("B-splines far from the origin, with a spike or beyond a double build at once",
          "[curve][bspline]") {
    // Site coordinates in metres, or one control point far out: rounding in the speed is then
    // larger than 1e-13 of a table piece's length, which must not make every piece halve.
    const std::vector<Vec3> near{{0, 0, 0}, {1, 2, 0},  {3, 2, 0.5},
                                 {4, 0, 1}, {6, -1, 1}, {7, 1, 1}};
    const auto seconds = [](auto build) {
        const auto start = std::chrono::steady_clock::now();
        build();
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    const Curve reference = Curve::build(bspline(near, 3));
    std::vector<Vec3> far = near;
    for (Vec3& p : far)
        p += Vec3{4.5e5, 5.2e6, 300}; // UTM coordinates
    CHECK(seconds([&] {
              const Curve c = Curve::build(bspline(far, 3));
              CHECK(c.length() == Approx(reference.length()).epsilon(1e-8));
              for (double t = 0; t <= 1; t += 1.0 / 16)
                  checkNear(c.pointAt(t) - Vec3{4.5e5, 5.2e6, 300}, reference.pointAt(t), 1e-6);
          }) < 2);
    std::vector<Vec3> spike = near;
    spike[3].z = 1e5;
    double polygon = 0;
    for (double chord : chordLengths(spike))
        polygon += chord;
    CHECK(seconds([&] {
              const Curve c = Curve::build(bspline(spike, 3));
              CHECK(c.length() > 1e5);      // up 0.6 of the spike's height and down again
              CHECK(c.length() <= polygon); // a B-spline is no longer than its control polygon
          }) < 2);
    spike[3].z = 1e200; // the length overflows: refused, at once
    CHECK(seconds([&] {
              CHECK_THROWS_WITH(Curve::build(bspline(spike, 3)),
                                Contains("coordinates are too large"));
          }) < 2);
}
