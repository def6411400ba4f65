#pragma once
// Internals shared by the rail readers (Import.cpp, DxfImport.cpp).

#include "io/Import.h"

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

/// Scales the points by `metres` per file unit, checks every curve with Curve::build and
/// returns the rails; UserError "<file>: <where>: <reason>" for the first bad one.
std::vector<NamedCurve> finishRails(const std::string& file, std::vector<SourcedCurve> curves,
                                    double metres);

/// A polyline spec from points; a last point equal to the first closes it (and is dropped).
CurveSpec polylineSpec(std::vector<Vec3> points, bool closed = false);

/// DXF rails (DxfImport.cpp). `file` is the name for messages.
std::vector<NamedCurve> importDxf(const std::filesystem::path& path, const ImportOptions& options);

} // namespace netsculpt::io
