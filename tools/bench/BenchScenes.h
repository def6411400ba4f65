#pragma once
// Nets shared by the benchmarks (fast_bench.cpp, bullet_compare.cpp), each built through the
// model's edits (model/Edits.h) and compiled (model/Compiler.h), so that it starts at the Eq. 2
// geometry a user's sculpture of the same shape would have. Rail knots are kSpacing apart and
// every bar is kBar long.

#include "model/Material.h"
#include "physics/MassSpringSystem.h"

#include <chrono>

namespace netsculpt::bench {

inline constexpr double kBar = 0.1;     ///< m, every bar's rest length
inline constexpr double kSpacing = 0.1; ///< m between the knots held by the top rail

/// The realistic rope: EA 2e5 N, compression ratio 0.01, knot 2 g, 6 g/m.
Material realisticRope();

/// A tube of rows x columns hanging from a circular rail (the paper's Fig. 10).
MassSpringSystem tubeOnCircularRail(int rows, int columns, const Material& material);

/// A sheet of rows x columns hanging from a straight rail, its last row connected to a second,
/// parallel rail 0.3 H aside and 0.5 H below, H the sheet's unloaded height: 0.58 H away, so the
/// sheet hangs slack between the two (Fig. 11's kind of join).
MassSpringSystem sheetBetweenParallelRails(int rows, int columns, const Material& material);

/// The installation's banner, smaller: rows x columns hanging from an open, wavy B-spline rail
/// about 5 m long (control points (0, 0, 12.5), (1, 0.8, 13), (2, 0, 12.5), (3, 0.8, 13),
/// (4, 0, 12.5)), free at its sides and bottom, its bars 0.1 m at the top row and 0.14 m at the
/// last. Its free edges collapse into vertical strands of knots that swing and twist.
MassSpringSystem bannerOnWavyRail(int rows, int columns, const Material& material);

/// Wall seconds since `start`.
double secondsSince(std::chrono::steady_clock::time_point start);

} // namespace netsculpt::bench
