// The checks a rail's CurveSpec passes before its curve is built (CurveChecks.h).

#include "geometry/CurveChecks.h"

#include "model/Error.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace netsculpt::curve_checks {

// ---- messages ----

[[noreturn]] void fail(const std::string& what) {
    throw UserError("rail: " + what);
}

std::string num(double value) {
    return formatNumber(value);
}
std::string num(std::size_t value) {
    return std::to_string(value);
}
std::string num(int value) {
    return std::to_string(value);
}
std::string num(const Vec3& p) {
    std::string text = "("; // appended piecewise: GCC 12 warns falsely on "(" + std::string&&
    text += num(p.x) + ", " + num(p.y) + ", " + num(p.z) + ")";
    return text;
}

void checkFinite(double value, const char* what) {
    if (!std::isfinite(value))
        fail(std::string(what) + " is " + num(value) + "; it must be a finite number");
}

// ---- validation ----

void checkFiniteCoordinates(const CurveSpec& spec) {
    const std::string noun = spec.spline ? "control point " : "point ";
    for (std::size_t i = 0; i < spec.points.size(); ++i) {
        const Vec3& p = spec.points[i];
        for (double coordinate : {p.x, p.y, p.z})
            if (!std::isfinite(coordinate))
                fail(noun + num(i) + " has a non-finite coordinate (" + num(coordinate) +
                     "); coordinates must be finite numbers");
    }
}

void checkPolylineSpec(const CurveSpec& spec) {
    if (spec.degree != 1)
        fail("a polyline has degree 1, got " + num(spec.degree) +
             "; a higher degree needs a B-spline (control points)");
    if (!spec.knots.empty())
        fail("a polyline takes no knot vector, got " + num(spec.knots.size()) +
             " knots; knots belong to a B-spline");
    if (!spec.weights.empty())
        fail("a polyline takes no weights, got " + num(spec.weights.size()) +
             " weights; weights belong to a B-spline");
}

std::size_t wrappedCount(const CurveSpec& spec) {
    return spec.points.size() + (spec.closed ? std::size_t(spec.degree) : 0);
}

namespace {

constexpr double kPeriodTolerance = 1e-9; // closed-spline knot periodicity, relative

void checkDegreeAndCount(const CurveSpec& spec) {
    if (spec.degree < 1 || spec.degree > kMaxDegree)
        fail("B-spline degree " + num(spec.degree) + " is out of range; allowed degrees are 1 to " +
             num(kMaxDegree));
    const std::size_t needed = std::size_t(spec.degree) + 1;
    if (spec.points.size() < needed)
        fail(std::string("a ") + (spec.closed ? "closed " : "") + "B-spline of degree " +
             num(spec.degree) + " needs at least " + num(needed) + " control points, got " +
             num(spec.points.size()));
}

void checkWeights(const CurveSpec& spec) {
    if (spec.weights.empty())
        return;
    if (spec.weights.size() != spec.points.size())
        fail(num(spec.weights.size()) + " weights given for " + num(spec.points.size()) +
             " control points; give one weight per control point, or none");
    for (std::size_t i = 0; i < spec.weights.size(); ++i)
        if (!(std::isfinite(spec.weights[i]) && spec.weights[i] > 0))
            fail("weight " + num(i) + " is " + num(spec.weights[i]) +
                 "; weights must be finite and > 0");
}

void checkDistinctControlPoints(const CurveSpec& spec) {
    const Vec3& first = spec.points.front();
    if (std::all_of(spec.points.begin(), spec.points.end(),
                    [&](const Vec3& p) { return p == first; }))
        fail("all " + num(spec.points.size()) + " control points are equal " + num(first) +
             "; a B-spline needs at least 2 distinct control points");
}

void checkKnotCount(const CurveSpec& spec) {
    const std::size_t wrapped = wrappedCount(spec);
    const std::size_t needed = wrapped + std::size_t(spec.degree) + 1;
    if (spec.knots.size() == needed)
        return;
    std::string what = "knot vector has " + num(spec.knots.size()) + " values; a " +
                       (spec.closed ? "closed " : "") + "degree-" + num(spec.degree) +
                       " B-spline with " + num(spec.points.size()) + " control points needs " +
                       num(needed);
    if (spec.closed)
        what += " (the knots of its " + num(wrapped) + " wrapped control points)";
    fail(what);
}

void checkKnotValues(const std::vector<double>& knots) {
    for (std::size_t i = 0; i < knots.size(); ++i)
        if (!std::isfinite(knots[i]))
            fail("knot " + num(i) + " is not finite (" + num(knots[i]) +
                 "); knots must be finite numbers");
    for (std::size_t i = 1; i < knots.size(); ++i)
        if (knots[i] < knots[i - 1])
            fail("knot " + num(i) + " (" + num(knots[i]) + ") is less than knot " + num(i - 1) +
                 " (" + num(knots[i - 1]) + "); knots must not decrease");
}

void checkKnotRange(const std::vector<double>& knots, std::size_t p, std::size_t wrapped) {
    if (knots[wrapped] > knots[p])
        return;
    fail("the knot vector's valid range [knots[" + num(p) + "], knots[" + num(wrapped) + "]] = [" +
         num(knots[p]) + ", " + num(knots[wrapped]) + "] is empty; it must have positive length");
}

// A value repeated more than p times inside the range would break the curve apart there. A
// closed curve's seam (the start of its range) is inside: the curve runs through it.
void checkKnotMultiplicity(const std::vector<double>& knots, std::size_t p, std::size_t wrapped,
                           bool closed) {
    const double lo = knots[p], hi = knots[wrapped];
    for (std::size_t i = 0; i < knots.size();) {
        std::size_t j = i;
        while (j < knots.size() && knots[j] == knots[i])
            ++j;
        const double v = knots[i];
        const bool inside = closed ? (v >= lo && v < hi) : (v > lo && v < hi);
        if (inside && j - i > p)
            fail("knot value " + num(v) + " is repeated " + num(j - i) + " times; a degree-" +
                 num(p) + " B-spline allows at most " + num(p) + " inside its valid range [" +
                 num(lo) + ", " + num(hi) + "]");
        i = j;
    }
}

// Control point i acts on [knots[i], knots[i + p + 1]]; one whose knots miss the valid range
// would be silently ignored. A closed curve's first p points also act through their copies.
void checkKnotInfluence(const std::vector<double>& knots, std::size_t n, std::size_t p,
                        std::size_t wrapped) {
    const double lo = knots[p], hi = knots[wrapped];
    auto acts = [&](std::size_t i) {
        return std::max(knots[i], lo) < std::min(knots[i + p + 1], hi);
    };
    for (std::size_t i = 0; i < n; ++i) {
        if (acts(i) || (i + n < wrapped && acts(i + n)))
            continue;
        fail("control point " + num(i) + " has no influence on the curve: its knots [knots[" +
             num(i) + "], knots[" + num(i + p + 1) + "]] = [" + num(knots[i]) + ", " +
             num(knots[i + p + 1]) + "] do not overlap the valid range [" + num(lo) + ", " +
             num(hi) + "]");
    }
}

// The wrapped control points repeat with period n, so the knots must too for the curve to
// meet itself smoothly: knots[i + n] = knots[i] + (knots[n + p] - knots[p]).
void checkKnotPeriodic(const std::vector<double>& knots, std::size_t n, std::size_t p) {
    const double period = knots[n + p] - knots[p];
    for (std::size_t i = 0; i + n < knots.size(); ++i) {
        const double shift = knots[i + n] - knots[i];
        if (std::abs(shift - period) > kPeriodTolerance * period)
            fail("the knots of a closed B-spline must repeat with period " + num(period) +
                 " (knots[" + num(n + p) + "] - knots[" + num(p) + "]), but knots[" + num(i + n) +
                 "] - knots[" + num(i) + "] = " + num(shift));
    }
}

void checkKnots(const CurveSpec& spec) {
    checkKnotCount(spec);
    checkKnotValues(spec.knots);
    const std::size_t p = std::size_t(spec.degree), wrapped = wrappedCount(spec);
    checkKnotRange(spec.knots, p, wrapped);
    if (spec.closed)
        checkKnotPeriodic(spec.knots, spec.points.size(), p);
    checkKnotMultiplicity(spec.knots, p, wrapped, spec.closed);
    checkKnotInfluence(spec.knots, spec.points.size(), p, wrapped);
}

} // namespace

void checkLength(double length) {
    if (!std::isfinite(length))
        fail("the curve's length is not finite (" + num(length) + "); coordinates are too large");
    if (!(length > 0))
        fail("the curve has zero length (" + num(length) +
             "); its points must be apart by a measurable distance");
}

void checkSplineSpec(const CurveSpec& spec) {
    checkDegreeAndCount(spec);
    checkWeights(spec);
    if (!spec.knots.empty())
        checkKnots(spec);
    checkDistinctControlPoints(spec);
}

} // namespace netsculpt::curve_checks
