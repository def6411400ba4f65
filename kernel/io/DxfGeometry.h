#pragma once
// Geometry of DXF entities that rails are made of: object coordinate systems, arcs (ARC,
// CIRCLE, polyline bulges) sampled finely, splines.

#include "geometry/Vec3.h"
#include "io/DxfScan.h"
#include "io/ImportDetail.h"

#include <string>
#include <vector>

namespace netsculpt::io {

/// Arcs are sampled with at most this angle between consecutive points (radians): the chord
/// deviates from the arc by at most r (1 - cos(0.25 deg)) ~ 1e-5 r, the length by ~3e-6.
inline constexpr double kArcStep = 0.5 * 3.14159265358979323846 / 180.0;

/// The object coordinate system of an entity with extrusion direction `normal` (the DXF
/// "arbitrary axis algorithm"). toWorld maps OCS coordinates to world coordinates.
struct Ocs {
    Vec3 ax{1, 0, 0}, ay{0, 1, 0}, az{0, 0, 1};
    bool identity = true;
    Vec3 toWorld(const Vec3& p) const { return identity ? p : ax * p.x + ay * p.y + az * p.z; }
};
/// UserError-free: `normal` must be finite and non-zero (checked by the caller).
Ocs ocsOf(const Vec3& normal);

/// Appends the points of the arc about `centre` (OCS plane z = centre.z) of radius r from
/// angle a0 sweeping `sweep` radians (> 0 counter-clockwise), without its first point.
void appendArc(std::vector<Vec3>& out, const Vec3& centre, double r, double a0, double sweep);

/// Appends the points after p1 up to p2 of a polyline segment with `bulge` (tan of a quarter of
/// the included angle; > 0 counter-clockwise; 0 = straight). p1, p2 in OCS.
void appendBulge(std::vector<Vec3>& out, const Vec3& p1, const Vec3& p2, double bulge);

/// A SPLINE as read: degree, flags (1 closed, 2 periodic, 4 rational), control points with
/// their weights, knots; in world coordinates (file units).
struct DxfSpline {
    const DxfEntity* entity = nullptr;
    int degree = 3;
    int flags = 0;
    std::vector<Vec3> control;
    std::vector<double> weights;
    std::vector<double> knots;
};

/// A DXF SPLINE as a rail. Open: as written. Closed (flag 1): either the periodic form whose
/// last `degree` control points repeat the first ones (what ezdxf and most CAD programs write),
/// unwrapped into CurveSpec's closed form; or a clamped spline whose ends coincide, sampled into
/// a closed polyline of 64 points per knot span (CurveSpec has no closed clamped form). UserError
/// for a closed spline that is neither. `name` and `where` are the rail's name and where it is
/// for messages.
SourcedCurve splineCurve(const std::string& file, const DxfSpline& spline, const std::string& name,
                         const std::string& where);

} // namespace netsculpt::io
