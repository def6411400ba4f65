#pragma once
// The compiled sculpture: a flat mass-spring system (DESIGN.md "Physics"), rebuilt from the
// sculpture whenever it changes. Knots and bars live in parallel arrays indexed by knot or bar
// number (struct of arrays), so solvers walk index ranges without chasing pointers.
// This is setup data plus the positions; solver state (velocities, scratch) lives in solvers.

#include "geometry/Vec3.h"
#include "model/Ids.h"

#include <cstdint>
#include <vector>

namespace netsculpt {

/// One (piece, row, column) a knot stands for. A shared knot (gear junction, seam, g = 1 join)
/// stands for several.
struct KnotRef {
    PieceId piece;
    int row = 0;
    int column = 0;
    bool operator==(const KnotRef&) const = default;
};

/// Where a fixed knot is held: the rail and the rail position t in [0, 1].
struct RailHold {
    RailId rail; ///< null for free knots
    double t = 0;
};

struct MassSpringSystem {
    // ---- knots, index j in [0, knotCount()) ----
    std::vector<Vec3> position;       ///< m, from origin; Eq. 1, 2 geometry until relaxed
    std::vector<double> mass;         ///< kg; knot_mass + 1/2 linear_density * sum of bar rest lengths
    std::vector<std::uint8_t> fixed;  ///< 1 = held by a rail (never moves), 0 = free
    std::vector<RailHold> hold;       ///< the rail holding a fixed knot; null rail for free knots
    std::vector<std::uint32_t> refStart; ///< knotCount()+1 offsets into refs (CSR)
    std::vector<KnotRef> refs;        ///< the (piece, row, column)s of knot j: refs[refStart[j] .. refStart[j+1])

    // ---- bars, index b in [0, barCount()) ----
    std::vector<std::uint32_t> barA, barB; ///< knot indices of the two ends
    std::vector<double> restLength;        ///< m; l_eq, the bar length
    std::vector<double> kTension;          ///< N/m; k_s = EA / l_eq, used when l > l_eq
    std::vector<double> kCompression;      ///< N/m; k_c = compression_ratio * k_s, when l <= l_eq
    std::vector<double> linearDensity;     ///< kg/m of the bar's rope (for wind and reports)
    std::vector<PieceId> barPiece;         ///< the piece the bar belongs to

    Vec3 gravity{0, 0, -9.81}; ///< m/s^2
    /// m; the sculpture's point that is this system's (0, 0, 0): a knot stands at origin +
    /// position[j] in the sculpture's coordinates. A sculpture in site coordinates (kilometres from
    /// its (0, 0, 0)) is relaxed near the system's origin, where a bar's vector keeps the precision
    /// the rope's stiffness needs (docs/performance.md, "The coordinates' precision floor").
    /// Whole metres; (0, 0, 0) for a sculpture about its origin (chooseOrigin in Compiler.h).
    Vec3 origin{0, 0, 0};

    std::size_t knotCount() const { return position.size(); }
    std::size_t barCount() const { return barA.size(); }
    /// Knot j in the sculpture's coordinates (m).
    Vec3 worldPosition(std::size_t j) const { return origin + position[j]; }
};

/// Knot j of `system` measured from `origin` instead of system.origin (m): its own position, bit
/// for bit, when the two are the same; else moved by their difference, which is exact (whole
/// metres), and rounded once to the precision of the result.
inline Vec3 inOrigin(const MassSpringSystem& system, std::size_t j, const Vec3& origin) {
    const Vec3& p = system.position[j];
    return system.origin == origin ? p : p + (system.origin - origin);
}

} // namespace netsculpt
