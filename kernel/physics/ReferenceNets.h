#pragma once
// Hand-built mass-spring systems of simple nets, independent of the sculpture model: a chain, a
// sheet below a straight rail and a tube below a circular rail, with the staggered rows and the
// initial geometry of DESIGN.md (Eq. 1, 2). They serve the solver tests and benchmarks and as
// cross-checks of the sculpture compiler.

#include "geometry/Vec3.h"
#include "physics/MassSpringSystem.h"

#include <optional>

namespace netsculpt {

/// The rope and knots of a net (DESIGN.md "Physics").
struct NetMaterial {
    double stiffness = 2e5;         ///< EA, N; k_s = EA / l_eq
    double compressionRatio = 0.01; ///< k_c / k_s, >= 0
    double knotMass = 0.002;        ///< kg per knot
    double linearDensity = 0.006;   ///< kg per metre of rope
};

/// A chain of `links` bars from `from` to `to` (both ends fixed), knots starting on the
/// parabola through the ends that sags `sag` metres (downwards, -z) in the middle.
MassSpringSystem makeChain(const Vec3& from, const Vec3& to, int links, double barLength,
                           const NetMaterial& material, double sag = 0);

struct SheetSpec {
    int rows = 10;          ///< >= 2; row 0 is fixed on the rail
    int columns = 10;       ///< knots per row, >= 2
    double barLength = 0.1; ///< l_eq, m; must exceed spacing / 2
    double spacing = 0.1;   ///< distance of the rail's knots, m
    NetMaterial material;
    /// When set, the last row is fixed too, on a second rail: the top rail moved by this offset
    /// (m); each last-row knot held where it starts (Eq. 1, 2) horizontally, on that rail.
    std::optional<Vec3> bottomRailOffset;
};

/// A sheet (open piece) hanging below a straight rail along +x at z = 0 (rail 1; bottom rail 2).
/// Throws UserError for bad numbers (bar length <= spacing / 2: no Eq. 2 height).
MassSpringSystem makeSheet(const SheetSpec& spec);

struct TubeSpec {
    int rows = 10;          ///< >= 2; row 0 is fixed on the rail
    int columns = 12;       ///< knots per row around the tube, >= 3
    double barLength = 0.1; ///< l_eq, m; must exceed half the rail chord
    double radius = 0.2;    ///< of the circular rail, m, centred on the z axis at z = 0
    NetMaterial material;
};

/// A tube (closed piece) hanging below a circular rail (rail 1). Throws UserError for bad
/// numbers.
MassSpringSystem makeTube(const TubeSpec& spec);

} // namespace netsculpt
