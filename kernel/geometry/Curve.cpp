// Rail curves: polylines and (rational) B-splines, with an arc-length table that maps rail
// positions to curve parameters (Curve.h, DESIGN.md "Rails").

#include "geometry/Curve.h"

#include "geometry/CurveChecks.h"

#include "model/Error.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <string>

namespace netsculpt {
namespace detail {

/// A control point in homogeneous form (w·P, w): rational curves then go through the same
/// de Boor recursion as plain ones, and the point is weighted / w.
struct Homogeneous {
    Vec3 weighted;
    double w = 1;
};

/// Everything derived from a CurveSpec. Immutable once built and shared by copies of a Curve,
/// which keeps copying a Curve (undo, model snapshots) cheap.
struct CurveGeometry {
    // B-spline (control is empty for a polyline). A closed spline holds its wrapped control
    // points (the first `degree` repeated at the end) and the knots of those.
    int degree = 1;
    std::vector<double> knots;
    std::vector<Homogeneous> control;
    // Polyline: vertices without zero-length segments; a closed one repeats its first vertex
    // at the end. The curve parameter is segment index + fraction.
    std::vector<Vec3> vertices;
    // Arc-length table, increasing in u: curve parameter, cumulative arc length (m), point.
    // Polylines: one entry per vertex. Splines: dense, adaptive (see appendPiece).
    std::vector<double> tableU, tableS;
    std::vector<Vec3> tableP;

    bool isSpline() const { return !control.empty(); }
};

} // namespace detail

namespace {

using detail::CurveGeometry;
using detail::Homogeneous;
using namespace curve_checks;

constexpr int kPiecesPerSpan = 16; // initial table pieces per knot span, before refinement
constexpr int kMaxRefineDepth = 30;
constexpr double kPieceTolerance = 1e-13; // relative disagreement of a piece and its halves
constexpr double kMaxTurnCosine = 0.98;   // a table piece turns by at most ~11 degrees
constexpr double kRoundingFloor = 2e-14;  // ~90 ulp of the control points' size: see appendPiece

// ---- B-spline construction ----

/// p + 1 zeros, uniform interior knots, p + 1 ones: the curve runs from the first control
/// point to the last over u in [0, 1].
std::vector<double> clampedUniformKnots(int n, int p) {
    std::vector<double> knots(std::size_t(p) + 1, 0.0);
    const int spans = n - p;
    for (int i = 1; i < spans; ++i)
        knots.push_back(double(i) / spans);
    knots.insert(knots.end(), std::size_t(p) + 1, 1.0);
    return knots;
}

/// Unit spacing over the n + p wrapped control points, shifted so the range is [0, n].
std::vector<double> periodicUniformKnots(int n, int p) {
    std::vector<double> knots;
    for (int i = 0; i <= n + 2 * p; ++i)
        knots.push_back(double(i - p));
    return knots;
}

std::vector<Homogeneous> homogeneousControl(const CurveSpec& spec) {
    const std::size_t n = spec.points.size();
    std::vector<Homogeneous> control;
    for (std::size_t i = 0; i < wrappedCount(spec); ++i) {
        const double w = spec.weights.empty() ? 1.0 : spec.weights[i % n];
        control.push_back({spec.points[i % n] * w, w});
    }
    return control;
}

// ---- evaluation ----

/// A curve point and the derivative dC/du there.
struct CurveSample {
    Vec3 point;
    Vec3 derivative;
};

Homogeneous lerp(const Homogeneous& a, const Homogeneous& b, double alpha) {
    return {a.weighted * (1 - alpha) + b.weighted * alpha, a.w * (1 - alpha) + b.w * alpha};
}

/// The span k (knots[k] <= u < knots[k + 1], non-empty) that holds u, for u in the range.
std::size_t findSpan(const CurveGeometry& g, double u) {
    const std::size_t p = std::size_t(g.degree), last = g.control.size() - 1;
    const auto begin = g.knots.begin();
    std::size_t k =
        std::size_t(std::upper_bound(begin + long(p) + 1, begin + long(last) + 1, u) - begin) - 1;
    while (k > p && !(g.knots[k] < g.knots[k + 1]))
        --k; // u at the end of the range
    return k;
}

/// One level r of de Boor's triangle for span k: c[r..p] become the level-r points.
void deBoorLevel(const CurveGeometry& g, std::size_t k, std::size_t r, double u,
                 std::array<Homogeneous, kMaxDegree + 1>& c) {
    const std::size_t p = std::size_t(g.degree);
    for (std::size_t j = p; j >= r; --j) {
        const double left = g.knots[j + k - p], right = g.knots[j + 1 + k - r];
        c[j] = lerp(c[j - 1], c[j], (u - left) / (right - left));
    }
}

// de Boor's algorithm in homogeneous coordinates. The two points of level p - 1 also give the
// derivative: by the blossom's multi-affinity, A'(u) = p (c[p] - c[p-1]) / (knots[k+1] - knots[k]).
CurveSample evaluateSpline(const CurveGeometry& g, double u) {
    const std::size_t p = std::size_t(g.degree), k = findSpan(g, u);
    std::array<Homogeneous, kMaxDegree + 1> c;
    for (std::size_t j = 0; j <= p; ++j)
        c[j] = g.control[k - p + j];
    for (std::size_t r = 1; r < p; ++r)
        deBoorLevel(g, k, r, u, c);
    const double scale = double(p) / (g.knots[k + 1] - g.knots[k]);
    const Homogeneous dA{(c[p].weighted - c[p - 1].weighted) * scale,
                         (c[p].w - c[p - 1].w) * scale};
    deBoorLevel(g, k, p, u, c);
    const Vec3 point = c[p].weighted / c[p].w;
    // Quotient rule for C = A / w.
    return {point, (dA.weighted - point * dA.w) / c[p].w};
}

CurveSample evaluatePolyline(const CurveGeometry& g, double u) {
    const long segments = long(g.vertices.size()) - 1;
    const long i = std::clamp(long(std::floor(u)), 0L, segments - 1);
    const Vec3& a = g.vertices[std::size_t(i)];
    const Vec3& b = g.vertices[std::size_t(i) + 1];
    return {a + (b - a) * (u - double(i)), b - a};
}

CurveSample evaluateAt(const CurveGeometry& g, double u) {
    return g.isSpline() ? evaluateSpline(g, u) : evaluatePolyline(g, u);
}

// ---- arc length ----

/// 5-point Gauss-Legendre rule on [-1, 1] (exact for polynomials of degree 9).
struct GaussRule {
    std::array<double, 5> node, weight;
};

const GaussRule& gaussRule() {
    static const GaussRule rule = [] {
        const double inner = std::sqrt(5 - 2 * std::sqrt(10.0 / 7)) / 3;
        const double outer = std::sqrt(5 + 2 * std::sqrt(10.0 / 7)) / 3;
        const double wInner = (322 + 13 * std::sqrt(70.0)) / 900;
        const double wOuter = (322 - 13 * std::sqrt(70.0)) / 900;
        return GaussRule{{-outer, -inner, 0, inner, outer},
                         {wOuter, wInner, 128.0 / 225, wInner, wOuter}};
    }();
    return rule;
}

/// Arc length between curve parameters a and b: the integral of the speed |C'(u)|.
double gaussLength(const CurveGeometry& g, double a, double b) {
    const GaussRule& rule = gaussRule();
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    double sum = 0;
    for (std::size_t i = 0; i < rule.node.size(); ++i)
        sum += rule.weight[i] * evaluateAt(g, mid + half * rule.node[i]).derivative.norm();
    return sum * half;
}

void appendTableEntry(CurveGeometry& g, double u, double pieceLength) {
    g.tableU.push_back(u);
    g.tableS.push_back(g.tableS.back() + pieceLength);
    g.tableP.push_back(evaluateAt(g, u).point);
}

bool turnsLittle(const CurveGeometry& g, double a, double b) {
    const Vec3 da = evaluateAt(g, a).derivative, db = evaluateAt(g, b).derivative;
    return da.dot(db) >= kMaxTurnCosine * da.norm() * db.norm();
}

// Appends entries covering (a, b], halving until Gauss-Legendre on the piece agrees with its
// two halves and the tangent turns little: the table is exact to ~1e-13 relative and dense
// where the curve bends or changes speed, which nearestPosition's coarse search relies on.
// `noise` (per unit of u): what rounding leaves of a length where coordinates are large for the
// curve (far from the origin, a spike); asking for more would halve pieces to kMaxRefineDepth.
// A length beyond a double ends the halving too: checkLength then refuses the curve.
void appendPiece(CurveGeometry& g, double a, double b, double pieceLength, double noise,
                 int depth) {
    const double mid = 0.5 * (a + b);
    const double left = gaussLength(g, a, mid), right = gaussLength(g, mid, b);
    const bool agrees =
        std::abs(left + right - pieceLength) <= kPieceTolerance * (left + right) + noise * (b - a);
    if (depth >= kMaxRefineDepth || !std::isfinite(left + right) ||
        (agrees && turnsLittle(g, a, b))) {
        appendTableEntry(g, mid, left);
        appendTableEntry(g, b, right);
        return;
    }
    appendPiece(g, a, mid, left, noise, depth + 1);
    appendPiece(g, mid, b, right, noise, depth + 1);
}

void buildSplineTable(CurveGeometry& g) {
    const std::size_t p = std::size_t(g.degree), wrapped = g.control.size();
    const double uMin = g.knots[p];
    g.tableU = {uMin};
    g.tableS = {0.0};
    g.tableP = {evaluateAt(g, uMin).point};
    double weighted = 0, w = INFINITY; // the points de Boor's algorithm forms are |weighted| / w
    for (const Homogeneous& c : g.control) {
        weighted = std::max(weighted, c.weighted.norm());
        w = std::min(w, c.w);
    }
    for (std::size_t k = p; k < wrapped; ++k) {
        const double k0 = g.knots[k], k1 = g.knots[k + 1];
        if (!(k0 < k1))
            continue;
        const double noise = kRoundingFloor * weighted / w * double(p) / (k1 - k0);
        for (int i = 0; i < kPiecesPerSpan; ++i) {
            const double a = k0 + (k1 - k0) * i / kPiecesPerSpan;
            const double b =
                i + 1 == kPiecesPerSpan ? k1 : k0 + (k1 - k0) * (i + 1) / kPiecesPerSpan;
            appendPiece(g, a, b, gaussLength(g, a, b), noise, 0);
        }
    }
}

CurveGeometry splineGeometry(const CurveSpec& spec) {
    checkSplineSpec(spec);
    CurveGeometry g;
    g.degree = spec.degree;
    const int n = int(spec.points.size());
    g.knots = !spec.knots.empty() ? spec.knots
              : spec.closed       ? periodicUniformKnots(n, spec.degree)
                                  : clampedUniformKnots(n, spec.degree);
    g.control = homogeneousControl(spec);
    buildSplineTable(g);
    return g;
}

// Whether a closed polyline's distinct vertices leave the line through its first vertex and the
// one farthest from it by more than 1e-9 of that distance: a loop of points on one line goes
// there and back, enclosing nothing (its "length" twice the line's).
bool enclosesAnything(const std::vector<Vec3>& vertices) {
    const Vec3& a = vertices.front();
    Vec3 far = a;
    for (const Vec3& v : vertices)
        if (distance(v, a) > distance(far, a)) far = v;
    const double span = distance(far, a);
    const Vec3 along = (far - a) / span;
    for (const Vec3& v : vertices) {
        const Vec3 d = v - a;
        if ((d - along * d.dot(along)).norm() > 1e-9 * span) return true;
    }
    return false;
}

// Distance 0 (not ==) decides a duplicate, so a segment too short to measure is dropped too.
std::vector<Vec3> polylineVertices(const CurveSpec& spec) {
    std::vector<Vec3> vertices;
    for (const Vec3& p : spec.points)
        if (vertices.empty() || distance(vertices.back(), p) > 0)
            vertices.push_back(p);
    if (spec.closed && vertices.size() > 1 && !(distance(vertices.back(), vertices.front()) > 0))
        vertices.pop_back();
    if (vertices.size() < 2)
        fail("a polyline needs at least 2 distinct points, got " + num(vertices.size()) +
             " distinct among " + num(spec.points.size()) + " points");
    if (spec.closed && !enclosesAnything(vertices))
        fail("a closed polyline needs at least 3 distinct points not on one line (a loop that "
             "encloses something), got " + num(vertices.size()) + " distinct among " +
             num(spec.points.size()) + " points, all on one line");
    if (spec.closed)
        vertices.push_back(vertices.front());
    return vertices;
}

CurveGeometry polylineGeometry(const CurveSpec& spec) {
    checkPolylineSpec(spec);
    CurveGeometry g;
    g.vertices = polylineVertices(spec);
    g.tableS = {0.0};
    for (std::size_t i = 0; i < g.vertices.size(); ++i) {
        g.tableU.push_back(double(i));
        g.tableP.push_back(g.vertices[i]);
        if (i > 0)
            g.tableS.push_back(g.tableS.back() + distance(g.vertices[i - 1], g.vertices[i]));
    }
    return g;
}

/// The table interval j (tableU[j] <= u <= tableU[j + 1]) that holds u.
std::size_t tableIntervalOfParameter(const CurveGeometry& g, double u) {
    const auto j = std::upper_bound(g.tableU.begin(), g.tableU.end(), u) - g.tableU.begin() - 1;
    return std::size_t(std::clamp(long(j), 0L, long(g.tableU.size()) - 2));
}

std::size_t tableIntervalOfLength(const CurveGeometry& g, double s) {
    const auto j = std::upper_bound(g.tableS.begin(), g.tableS.end(), s) - g.tableS.begin() - 1;
    return std::size_t(std::clamp(long(j), 0L, long(g.tableS.size()) - 2));
}

/// Arc length from the start of the curve to curve parameter u.
double arcLengthAt(const CurveGeometry& g, double u) {
    const std::size_t j = tableIntervalOfParameter(g, u);
    if (!g.isSpline()) // exact: constant speed along a segment
        return g.tableS[j] + (g.tableS[j + 1] - g.tableS[j]) * (u - g.tableU[j]);
    return g.tableS[j] + gaussLength(g, g.tableU[j], u);
}

// Inside table interval j, solves arcLength(u) = s by Newton's method on u (the derivative of
// arc length is the speed), kept inside a shrinking bracket and falling back to bisection.
double solveArcLength(const CurveGeometry& g, std::size_t j, double s) {
    double lo = g.tableU[j], hi = g.tableU[j + 1];
    const double s0 = g.tableS[j], ds = g.tableS[j + 1] - s0;
    double u = ds > 0 ? lo + (hi - lo) * (s - s0) / ds : lo;
    const double tolerance = 1e-14 * g.tableS.back();
    for (int iteration = 0; iteration < 60; ++iteration) {
        const double error = s0 + gaussLength(g, g.tableU[j], u) - s;
        if (std::abs(error) <= tolerance)
            break;
        (error > 0 ? hi : lo) = u;
        const double speed = evaluateAt(g, u).derivative.norm();
        double next = u - error / speed;
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        if (next == u)
            break;
        u = next;
    }
    return u;
}

/// Curve parameter at arc length s from the start, s in [0, length].
double parameterAtArcLength(const CurveGeometry& g, double s) {
    if (s <= 0)
        return g.tableU.front();
    if (s >= g.tableS.back())
        return g.tableU.back();
    const std::size_t j = tableIntervalOfLength(g, s);
    if (!g.isSpline())
        return g.tableU[j] + (s - g.tableS[j]) / (g.tableS[j + 1] - g.tableS[j]);
    return solveArcLength(g, j, s);
}

// ---- nearest point ----

/// u in [a, b] where |C(u) - p| is least, assuming one minimum in so short a piece: the root
/// of (C(u) - p)·C'(u), found by regula falsi (Illinois), or an end of the piece.
double nearestInPiece(const CurveGeometry& g, const Vec3& p, double a, double b) {
    auto slope = [&](double u) {
        const CurveSample c = evaluateAt(g, u);
        return (c.point - p).dot(c.derivative);
    };
    double fa = slope(a), fb = slope(b);
    if (fa >= 0 || fb <= 0) // no minimum inside: the nearer end
        return distance(evaluateAt(g, a).point, p) <= distance(evaluateAt(g, b).point, p) ? a : b;
    int lastMoved = 0;
    double u = a;
    for (int iteration = 0; iteration < 100 && b - a > 1e-15 * (std::abs(a) + std::abs(b));
         ++iteration) {
        u = (a * fb - b * fa) / (fb - fa);
        if (!(u > a && u < b))
            u = 0.5 * (a + b);
        const double fu = slope(u);
        if (fu == 0)
            break;
        if (fu > 0) { // the root is left of u
            b = u, fb = fu;
            if (lastMoved == -1)
                fa *= 0.5; // Illinois: stop the same end from sticking
            lastMoved = -1;
        } else {
            a = u, fa = fu;
            if (lastMoved == 1)
                fb *= 0.5;
            lastMoved = 1;
        }
    }
    return u;
}

double nearestParameterOnPolyline(const CurveGeometry& g, const Vec3& p) {
    double bestU = 0, bestDistance = INFINITY;
    for (std::size_t i = 0; i + 1 < g.vertices.size(); ++i) {
        const Vec3 a = g.vertices[i], ab = g.vertices[i + 1] - a;
        const double f = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        const double d = distance(a + ab * f, p);
        if (d < bestDistance)
            bestDistance = d, bestU = double(i) + f;
    }
    return bestU;
}

// Coarse search over the table, then refinement in every table interval that could hold a
// nearer point: no point of interval j is nearer than min(d_j, d_j+1) - (its arc length) / 2.
double nearestParameterOnSpline(const CurveGeometry& g, const Vec3& p) {
    std::vector<double> d(g.tableP.size());
    for (std::size_t j = 0; j < d.size(); ++j)
        d[j] = distance(g.tableP[j], p);
    const std::size_t nearest = std::size_t(std::min_element(d.begin(), d.end()) - d.begin());
    double bestU = g.tableU[nearest], bestDistance = d[nearest];
    for (std::size_t j = 0; j + 1 < d.size(); ++j) {
        const double halfArc = 0.5 * (g.tableS[j + 1] - g.tableS[j]);
        if (std::min(d[j], d[j + 1]) - halfArc > bestDistance)
            continue;
        const double u = nearestInPiece(g, p, g.tableU[j], g.tableU[j + 1]);
        const double du = distance(evaluateAt(g, u).point, p);
        if (du < bestDistance)
            bestDistance = du, bestU = u;
    }
    return bestU;
}

// ---- tangent ----

// Where the speed vanishes (repeated control points at a clamped end, a cusp) the direction of
// travel is the limit of the chords around u.
Vec3 chordDirection(const CurveGeometry& g, double u, double uMin, double uMax) {
    for (double h : {1e-9, 1e-6, 1e-3}) {
        const double step = h * (uMax - uMin);
        const Vec3 chord = evaluateAt(g, std::min(u + step, uMax)).point -
                           evaluateAt(g, std::max(u - step, uMin)).point;
        if (chord.norm() > 0)
            return chord / chord.norm();
    }
    assert(false && "a curve of positive length moves near every parameter");
    return {1, 0, 0};
}

} // namespace

// ---- Curve ----

Curve Curve::build(const CurveSpec& spec) {
    checkFiniteCoordinates(spec);
    auto geometry = std::make_shared<CurveGeometry>(spec.spline ? splineGeometry(spec)
                                                                : polylineGeometry(spec));
    checkLength(geometry->tableS.back());
    Curve curve;
    curve.spec_ = spec;
    curve.length_ = geometry->tableS.back();
    curve.uMin_ = geometry->tableU.front();
    curve.uMax_ = geometry->tableU.back();
    curve.geometry_ = std::move(geometry);
    return curve;
}

Vec3 Curve::evaluate(double u) const {
    assert(geometry_ && "use Curve::build");
    return evaluateAt(*geometry_, u).point;
}

double Curve::normalizedPosition(double t) const {
    checkFinite(t, "rail position");
    if (!closed())
        return std::clamp(t, 0.0, 1.0);
    const double wrapped = t - std::floor(t);
    return wrapped < 1 ? wrapped : 0.0; // a tiny negative t rounds up to 1, which is 0
}

double Curve::parameterAt(double t) const {
    assert(geometry_ && "use Curve::build");
    const double position = normalizedPosition(t);
    if (spec_.sampling == Sampling::Parameter)
        return std::clamp(uMin_ + position * (uMax_ - uMin_), uMin_, uMax_);
    return parameterAtArcLength(*geometry_, position * length_);
}

double Curve::positionOfParameter(double u) const {
    const double t = spec_.sampling == Sampling::Parameter ? (u - uMin_) / (uMax_ - uMin_)
                                                           : arcLengthAt(*geometry_, u) / length_;
    if (closed())
        return t >= 1 ? 0.0 : std::max(t, 0.0);
    return std::clamp(t, 0.0, 1.0);
}

double Curve::distanceAlong(double t) const {
    const double position = normalizedPosition(t);
    if (spec_.sampling == Sampling::ArcLength)
        return position * length_;
    return std::min(arcLengthAt(*geometry_, parameterAt(position)), length_);
}

Vec3 Curve::pointAt(double t) const {
    return evaluate(parameterAt(t));
}

Vec3 Curve::tangentAt(double t) const {
    const double u = parameterAt(t);
    const Vec3 derivative = evaluateAt(*geometry_, u).derivative;
    const double speed = derivative.norm();
    // Relative to the mean speed, so a numerically vanishing derivative does not give noise.
    if (speed > 1e-12 * length_ / (uMax_ - uMin_))
        return derivative / speed;
    return chordDirection(*geometry_, u, uMin_, uMax_);
}

double Curve::nearestPosition(const Vec3& p) const {
    assert(geometry_ && "use Curve::build");
    if (!p.isFinite())
        fail("the point " + num(p) +
             " has a non-finite coordinate; coordinates must be finite numbers");
    const double u = geometry_->isSpline() ? nearestParameterOnSpline(*geometry_, p)
                                           : nearestParameterOnPolyline(*geometry_, p);
    return positionOfParameter(u);
}

std::vector<Vec3> Curve::samplePoints(double at, double d, int n) const {
    if (n < 0)
        fail("sample count " + num(n) + " is negative; it must be >= 0");
    checkFinite(at, "first rail position");
    checkFinite(d, "rail position step");
    std::vector<Vec3> points;
    points.reserve(std::size_t(n));
    for (int i = 0; i < n; ++i)
        points.push_back(pointAt(at + i * d));
    return points;
}

} // namespace netsculpt
