#pragma once
// Nets and helpers shared by the benchmarks (fast_bench.cpp, bullet_compare.cpp, live_bench.cpp):
// the reference sculptures of model/ReferenceSculptures.h (built through the model's edits, so
// each starts at the Eq. 2 geometry a user's sculpture of the same shape would have), compiled
// (model/Compiler.h).

#include "model/Material.h"
#include "physics/MassSpringSystem.h"

#include <chrono>
#include <vector>

namespace netsculpt::bench {

/// The realistic rope: EA 2e5 N, compression ratio 0.01, knot 2 g, 6 g/m.
Material realisticRope();

/// netsculpt::tubeOnCircularRail, compiled.
MassSpringSystem tubeOnCircularRail(int rows, int columns, const Material& material);

/// netsculpt::sheetBetweenParallelRails, compiled.
MassSpringSystem sheetBetweenParallelRails(int rows, int columns, const Material& material);

/// netsculpt::bannerOnWavyRail, compiled.
MassSpringSystem bannerOnWavyRail(int rows, int columns, const Material& material);

/// Wall seconds since `start`.
double secondsSince(std::chrono::steady_clock::time_point start);

/// The largest distance between matching knots of two shapes of the same net, m.
double largestDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

} // namespace netsculpt::bench
