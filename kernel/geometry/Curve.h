#pragma once
// A rail's curve (DESIGN.md "Rails"): a polyline or a (rational) B-spline, open or closed,
// addressed by a rail position t. Built once from a CurveSpec, then immutable.

#include "geometry/Vec3.h"

#include <memory>
#include <vector>

namespace netsculpt {

/// How rail positions t map to the curve.
enum class Sampling {
    /// t = normalized arc length from the first point (default; what a net machine makes)
    ArcLength,
    /// t = normalized curve parameter (equal parameter steps, as the paper describes)
    Parameter,
};

/// What a user gives to describe a curve. Validated by Curve::build.
/// Indices in error messages (point 3, knot 5, weight 2) count from 0, like rows and columns.
struct CurveSpec {
    /// Polyline points or B-spline control points, in metres. A polyline's consecutive
    /// duplicate points are dropped (no zero-length segments); it needs 2 distinct points.
    std::vector<Vec3> points;
    /// Polyline: must be 1. B-spline: 1 to 7; needs at least degree + 1 control points
    /// (open or closed).
    int degree = 1;
    /// B-spline knot vector, non-decreasing, finite. n = control points, p = degree.
    /// Open: size n + p + 1; the curve is the part over [knots[p], knots[n]] (positive length).
    /// Closed: the knots of the wrapped control points P0..P(n-1), P0..P(p-1): size n + 2p + 1,
    /// periodic (knots[i + n] - knots[i] is the same for every i, to 1e-9 relative), and the
    /// curve is the part over [knots[p], knots[n + p]].
    /// A value may repeat at most p times inside that range (a closed curve's seam is inside),
    /// and every control point must act on the range (knots[i] .. knots[i + p + 1] overlap it).
    /// Empty = clamped uniform (open) or uniform periodic (closed). Polylines take none.
    std::vector<double> knots;
    /// Rational weights, one per control point, finite and > 0. Empty = all 1. Polylines take none.
    std::vector<double> weights;
    /// Closed curve: a polyline's last point joins its first; a closed B-spline is periodic
    /// (its control polygon wraps around; the curve is smooth through the closure).
    bool closed = false;
    Sampling sampling = Sampling::ArcLength;
    /// True when the spec describes a B-spline (control points), false for a polyline.
    bool spline = false;
};

namespace detail {
struct CurveGeometry; // evaluation data and arc-length table (Curve.cpp)
}

/// Copies are cheap: the evaluation data and the arc-length table are immutable and shared
/// between copies. A default-constructed Curve is empty; only build() makes a usable one.
class Curve {
  public:
    /// Validates and builds. Throws UserError naming the bad value and what is allowed:
    /// fewer than two distinct points, NaN/inf coordinates, a degree out of range, a knot vector
    /// of the wrong size or decreasing, non-positive weights, zero length.
    static Curve build(const CurveSpec& spec);

    const CurveSpec& spec() const { return spec_; }
    bool closed() const { return spec_.closed; }
    /// Total arc length, m (closed: including the closing segment or span).
    double length() const { return length_; }

    /// The point at rail position t. Open curves: t in [0, 1] (clamped). Closed curves:
    /// t is taken modulo 1. Interpretation of t follows spec().sampling.
    /// Polylines under Sampling::Parameter: t = (segment index + fraction) / segments.
    /// Throws UserError when t is NaN or infinite (as do the other queries).
    Vec3 pointAt(double t) const;
    /// Rail position t as pointAt takes it: clamped to [0, 1] (open) or wrapped to [0, 1)
    /// (closed). Throws UserError when t is NaN or infinite.
    double normalizedPosition(double t) const;
    /// Arc length from the curve's start to rail position t, m (t normalized first): what a
    /// tape laid along the rail measures. t x length() only under Sampling::ArcLength.
    double distanceAlong(double t) const;
    /// Unit tangent at rail position t (the rail's direction). At a polyline vertex it is the
    /// direction of the segment that starts there (of the last segment at an open end).
    Vec3 tangentAt(double t) const;
    /// Rail position t (in this curve's sampling) of the curve point nearest to p;
    /// in [0, 1) on a closed curve, [0, 1] on an open one.
    double nearestPosition(const Vec3& p) const;
    /// n points at equal spacing starting at t = at with step d (t = at + i*d). n >= 0.
    std::vector<Vec3> samplePoints(double at, double d, int n) const;

  private:
    CurveSpec spec_;
    double length_ = 0;
    double uMin_ = 0, uMax_ = 1; // the curve parameter's range
    std::shared_ptr<const detail::CurveGeometry> geometry_;

    Vec3 evaluate(double u) const;              // point at curve parameter u in [uMin_, uMax_]
    double parameterAt(double t) const;         // rail position t -> curve parameter u
    double positionOfParameter(double u) const; // curve parameter u -> rail position t
};

} // namespace netsculpt
