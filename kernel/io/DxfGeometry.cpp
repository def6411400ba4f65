#include "io/DxfGeometry.h"

#include "geometry/Curve.h"
#include "io/IoText.h"
#include "model/Error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace netsculpt::io {

Ocs ocsOf(const Vec3& normal) {
    Ocs ocs;
    // Scaled to its largest component first, so that the norm of a direction written with huge
    // or tiny numbers (1e300, 1e-300) neither overflows nor underflows.
    const double largest = std::max({std::abs(normal.x), std::abs(normal.y), std::abs(normal.z)});
    const Vec3 scaled = normal / largest;
    const Vec3 n = scaled / scaled.norm();
    if (n == Vec3{0, 0, 1})
        return ocs;
    constexpr double limit = 1.0 / 64.0;
    Vec3 ax = (std::abs(n.x) < limit && std::abs(n.y) < limit) ? Vec3{0, 1, 0}.cross(n)
                                                               : Vec3{0, 0, 1}.cross(n);
    ax = ax / ax.norm();
    Vec3 ay = n.cross(ax);
    ay = ay / ay.norm();
    ocs.ax = ax;
    ocs.ay = ay;
    ocs.az = n;
    ocs.identity = false;
    return ocs;
}

void appendArc(std::vector<Vec3>& out, const Vec3& centre, double r, double a0, double sweep) {
    const int n = std::max(2, int(std::ceil(std::abs(sweep) / kArcStep)));
    for (int i = 1; i <= n; ++i) {
        const double a = a0 + sweep * (double(i) / n);
        out.push_back({centre.x + r * std::cos(a), centre.y + r * std::sin(a), centre.z});
    }
}

void appendBulge(std::vector<Vec3>& out, const Vec3& p1, const Vec3& p2, double bulge) {
    const double dx = p2.x - p1.x, dy = p2.y - p1.y;
    const double chord = std::hypot(dx, dy);
    if (bulge == 0 || chord == 0) {
        out.push_back(p2);
        return;
    }
    const double angle = 4 * std::atan(bulge); // included angle, signed
    // Each sample is reached from p1 along its own chord, turned from p1 -> p2 by half the angle
    // still to sweep, without the centre: for a nearly straight segment (a bulge of 1e-17, as
    // CAD programs round) the centre lies chord / (4 bulge) away, and arc points taken from it
    // would carry its rounding, more than the segment's own length.
    const double heading = std::atan2(dy, dx);
    const int n = std::max(2, int(std::ceil(std::abs(angle) / kArcStep)));
    for (int i = 1; i <= n; ++i) {
        const double swept = angle * (double(i) / n);
        const double reach = chord * std::sin(0.5 * swept) / std::sin(0.5 * angle);
        const double towards = heading + 0.5 * (swept - angle);
        out.push_back({p1.x + reach * std::cos(towards), p1.y + reach * std::sin(towards), p1.z});
    }
    out.back() = p2; // the end is the given vertex, not its rounding
}

namespace {

bool near(const Vec3& a, const Vec3& b, double scale) {
    return distance(a, b) <= 1e-9 * scale;
}

} // namespace

SourcedCurve splineCurve(const std::string& file, const DxfSpline& s, const std::string& name,
                         const std::string& where) {
    const DxfEntity& e = *s.entity;
    CurveSpec spec;
    spec.spline = true;
    spec.degree = s.degree;
    spec.points = s.control;
    spec.knots = s.knots;
    if (e.count[41] > 0 &&
        std::any_of(s.weights.begin(), s.weights.end(), [](double w) { return w != 1.0; }))
        spec.weights = s.weights;
    const bool closed = s.flags & 1;
    if (!closed || spec.points.empty())
        return {{name, std::move(spec)}, where};

    const std::size_t n = spec.points.size(), p = std::size_t(std::max(0, s.degree));
    double scale = 0;
    for (const Vec3& c : spec.points)
        scale = std::max(scale, distance(c, spec.points[0]));
    bool wrapped = n > 2 * p;
    for (std::size_t i = 0; wrapped && i < p; ++i)
        wrapped = near(spec.points[i], spec.points[n - p + i], scale) &&
                  (spec.weights.empty() || spec.weights[i] == spec.weights[n - p + i]);
    if (wrapped) {
        spec.points.resize(n - p);
        if (!spec.weights.empty())
            spec.weights.resize(n - p);
        spec.closed = true;
        return {{name, std::move(spec)}, where};
    }
    const auto& k = spec.knots;
    const bool clamped = k.size() == n + p + 1 && k.size() > 2 * p + 2 &&
                         std::all_of(k.begin(), k.begin() + std::ptrdiff_t(p + 1),
                                     [&](double v) { return v == k.front(); }) &&
                         std::all_of(k.end() - std::ptrdiff_t(p + 1), k.end(),
                                     [&](double v) { return v == k.back(); });
    if (!(clamped && near(spec.points.front(), spec.points.back(), scale)))
        throw UserError(
            file + ": " + where + ": is flagged closed, but neither do its last " +
            std::to_string(p) +
            " control points repeat its first ones (a periodic spline) nor is it clamped with "
            "coinciding ends; cannot tell how it closes");
    CurveSpec poly;
    poly.closed = true;
    const int count = 64 * int(n - p);
    spec.sampling = Sampling::Parameter;
    try {
        const Curve byParameter = Curve::build(spec);
        for (int i = 0; i < count; ++i)
            poly.points.push_back(byParameter.pointAt(double(i) / count));
    } catch (const UserError& error) {
        throw UserError(file + ": " + where + ": " + error.what());
    }
    return {{name, std::move(poly)}, where + " (sampled: a closed clamped spline)"};
}

} // namespace netsculpt::io
