#pragma once
// Nets the fast path's tests relax: the reference sculptures (model/ReferenceSculptures.h: a tube
// below a circular rail, a sheet hanging slack between two parallel rails, a banner on a wavy
// rail) in a rope of the given stiffness.
#include "model/ReferenceSculptures.h"
#include "model/TestSculptures.h"

namespace netsculpt::test {

inline Material rope(double stiffness) { return Material{stiffness, 0.01, 0.002, 0.006}; }

/// A tube of `rows` x `columns` below a circular rail, knots 0.1 m apart on the rail.
inline Sculpture tube(int rows, int columns, double stiffness) {
    return tubeOnCircularRail(rows, columns, rope(stiffness));
}

/// A sheet on an open rail whose last row is held by a parallel rail 0.58 of the sheet's
/// height away (0.3 H aside, 0.5 H below): it hangs slack between them.
inline Sculpture slackSheet(int rows, int columns, double stiffness) {
    return sheetBetweenParallelRails(rows, columns, rope(stiffness));
}

/// A banner of `rows` x `columns` on a wavy rail 5 m long, its bars 0.1 m in the top row and
/// 0.14 m in the bottom one: its lower part hangs in strands whose free edges creep to their
/// equilibrium at the rope's stiffness (docs/performance.md).
inline Sculpture banner(int rows, int columns, double stiffness) {
    return bannerOnWavyRail(rows, columns, rope(stiffness));
}

} // namespace netsculpt::test
