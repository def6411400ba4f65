#pragma once
// A horizontal circle as the vertices of a regular polygon: what a ring rail is drawn from (in
// scripts through ns.circle, in the reference sculptures and the tests).

#include "geometry/Vec3.h"

#include <vector>

namespace netsculpt {

/// The most vertices circlePoints makes: far more than a ring rail needs (its rails have tens
/// to hundreds), and few enough that the Lua table of them stays within a script's memory.
constexpr int kMaxCircleVertices = 100000;

/// The `vertices` corners of the regular polygon inscribed in the horizontal circle of `radius`
/// (m) about `centre`: corner i at the angle 2 pi i / vertices from +x, counter-clockwise seen
/// from above. A closed polyline through them is a ring rail.
/// Throws UserError unless radius is finite and > 0, vertices is 3 to kMaxCircleVertices and
/// centre is finite.
std::vector<Vec3> circlePoints(Vec3 centre, double radius, int vertices);

} // namespace netsculpt
