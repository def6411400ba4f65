#pragma once
// Internals shared by the rail readers (Import.cpp, RailText.cpp, DxfImport.cpp).

#include "io/Import.h"

#include <algorithm>
#include <string>
#include <vector>

namespace netsculpt::io {

/// A rail read from a file, with where it came from for messages ("line 12", "SPLINE 2F on
/// layer RAILS at line 2074").
struct SourcedCurve {
    NamedCurve rail;
    std::string where;
    std::size_t order = 0; ///< sort key: the line the rail starts at
};

/// Rails must lie within this distance of the origin, m, in every coordinate: a site's
/// coordinates (an easting, a northing, even geocentric ones) are far inside, and lengths and
/// the joining of ends stay exact to well under a micrometre there.
inline constexpr double kMaxCoordinate = 1e8;

/// The diagonal of the bounding box of `points`, file units (0 for none): 1e-6 of it is the
/// tolerance within which a polyline's ends (DxfCollector.cpp) and pieces' ends (Chains.h) meet.
inline double extent(const std::vector<Vec3>& points) {
    if (points.empty())
        return 0;
    Vec3 lo = points[0], hi = lo;
    for (const Vec3& p : points) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    return distance(lo, hi);
}

/// Why coordinate `c` (file units, `metres` each) is refused: "2e+08 m, too large: rails must
/// lie within 1e+08 m of the origin in x, y and z" (with the file's units when not metres); ""
/// when it is within kMaxCoordinate, or nan (which has a message of its own).
std::string farCoordinate(double c, double metres);

/// UserError "<file>: <where>: ..." naming the coordinate and the allowed range unless every
/// coordinate of `points` (file units, `metres` each) is finite and within kMaxCoordinate.
void checkCoordinates(const std::string& file, const std::string& where,
                      const std::vector<Vec3>& points, double metres);

/// Checks the coordinates, scales the points by `metres` per file unit, checks every curve
/// with Curve::build and returns the rails; UserError "<file>: <where>: <reason>" for the
/// first bad one.
std::vector<NamedCurve> finishRails(const std::string& file, std::vector<SourcedCurve> curves,
                                    double metres);

/// A polyline spec from points; a last point equal to the first closes it (and is dropped).
CurveSpec polylineSpec(std::vector<Vec3> points, bool closed = false);

/// CSV rails (RailText.cpp), in file units; `metres` per unit for the coordinate check, which
/// names the line of a coordinate beyond kMaxCoordinate (finishRails could name only the rail's).
std::vector<SourcedCurve> readCsv(const std::filesystem::path& path, double metres);
/// OBJ rails (RailText.cpp), in file units; `metres` per unit for the coordinate check.
std::vector<SourcedCurve> readObj(const std::filesystem::path& path, double metres);

/// DXF rails (DxfImport.cpp).
std::vector<NamedCurve> importDxf(const std::filesystem::path& path, const ImportOptions& options);

} // namespace netsculpt::io
