#pragma once
// The fast path's reference nets, built through the model's edits so that each starts at the
// Eq. 2 geometry a user's sculpture of the same shape would have: the benchmarks relax them
// (tools/bench/BenchScenes.h) and the fast path's tests too (tests/physics_fast/TestNets.h).
// Rail knots are kReferenceSpacing apart and bars kReferenceBar long unless said otherwise.

#include "model/Material.h"
#include "model/Sculpture.h"

namespace netsculpt {

inline constexpr double kReferenceBar = 0.1;     ///< m, the bar length of the tube and sheet
inline constexpr double kReferenceSpacing = 0.1; ///< m between the knots held by the top rail

/// A tube of rows x columns hanging from a circular rail (the paper's Fig. 10).
Sculpture tubeOnCircularRail(int rows, int columns, const Material& material);

/// A sheet of rows x columns hanging from a straight rail, its last row connected to a second,
/// parallel rail 0.3 H aside and 0.5 H below, H the sheet's unloaded height: 0.58 H away, so the
/// sheet hangs slack between the two (Fig. 11's kind of join).
Sculpture sheetBetweenParallelRails(int rows, int columns, const Material& material);

/// A banner of rows x columns hanging from an open, wavy B-spline rail about 5 m long (control
/// points (0, 0, 12.5), (1, 0.8, 13), (2, 0, 12.5), (3, 0.8, 13), (4, 0, 12.5)), free at its
/// sides and bottom, its bars 0.1 m at the top row and 0.14 m at the last. Its free edges
/// collapse into vertical strands of knots that swing, twist and creep to their equilibrium at
/// the rope's stiffness (docs/performance.md).
Sculpture bannerOnWavyRail(int rows, int columns, const Material& material);

} // namespace netsculpt
