#pragma once
// Rails drawn in pieces (DXF LINEs and ARCs of one layer within model space or within one block
// reference, OBJ `l` elements of one object) joined end to end into whole rails.

#include "geometry/Vec3.h"
#include "io/ImportDetail.h"

#include <string>
#include <string_view>
#include <vector>

namespace netsculpt::io {

/// One piece: its points in order (at least 2), what to call a rail that starts with it, and
/// where it is for messages ("LINE 2F on layer R (line 12)", "line 7").
struct ChainPart {
    std::vector<Vec3> points;
    std::string name;
    std::string where;
    std::size_t order = 0; ///< the rail's sort key when the chain starts with this part
};

/// Ends within this distance meet: 1e-6 of the extent of all the parts' points (the diagonal of
/// their bounding box).
double joinTolerance(const std::vector<ChainPart>& parts);

/// Joins the parts end to end where ends lie within joinTolerance: each chain becomes one rail,
/// closed when its ends meet (the repeated point dropped), named after its first part in the
/// given order and running in that part's direction. A part whose points all lie within the
/// tolerance of its first point (a LINE of 5 um among rails of metres: a snapping slip) is left
/// out, unless every part is that short: the ends that meet it at either side are joined
/// directly, even when they lie further apart than the tolerance. UserError naming the parts
/// when three or more ends meet: a rail cannot branch; `advice` says how to keep branches apart
/// ("put the branches on different layers").
std::vector<SourcedCurve> joinChains(const std::string& file, std::vector<ChainPart> parts,
                                     std::string_view advice);

} // namespace netsculpt::io
