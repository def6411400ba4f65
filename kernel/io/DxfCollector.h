#pragma once
// What dxflib reads from a DXF file, per block: the entities rails are made of, in the
// coordinates of model space or of their block, and the block references (INSERT).

#include "geometry/Curve.h"
#include "io/DxfGeometry.h"
#include "io/DxfScan.h"

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace netsculpt::io {

/// An INSERT as written: the block, its insertion point in the INSERT's object coordinate
/// system, scale factors, rotation about the OCS z axis, and the MINSERT grid (1 x 1 for an
/// INSERT).
struct DxfInsert {
    const DxfEntity* entity = nullptr;
    std::string block;
    Vec3 at;
    Vec3 scale{1, 1, 1};
    double degrees = 0;
    Ocs ocs;
    int columns = 1, rows = 1;
};

/// The rail-making content of model space or of one block definition; points in its own
/// coordinates (world coordinates for model space), file units.
struct DxfContent {
    std::vector<std::pair<const DxfEntity*, CurveSpec>> curves; ///< POLYLINE, LWPOLYLINE, CIRCLE
    std::vector<std::pair<const DxfEntity*, std::vector<Vec3>>> parts; ///< LINE, ARC
    std::vector<DxfSpline> splines;
    std::vector<DxfInsert> inserts;
    /// Entities that cannot be rails, with the reason: refused only when one is read (its layer
    /// chosen and, in a block, the block inserted).
    std::vector<std::pair<const DxfEntity*, std::string>> refusals;
    Vec3 base;            ///< a block's base point (group 10 of BLOCK)
    bool defined = false; ///< a BLOCK of this name was read
};

struct DxfDrawing {
    std::optional<int> insunits;
    DxfContent model;
    std::map<std::string, DxfContent> blocks;
};

/// Reads `text` (checked by `scan`) with dxflib. An entity that cannot be a rail (an ELLIPSE, a
/// mesh) is kept in DxfContent::refusals, not refused here.
DxfDrawing collectDxf(const std::string& file, const DxfScan& scan, const std::string& text);

} // namespace netsculpt::io
