#pragma once
// The sculpture: what commands edit (rails, pieces, joins). Plain data, cheap to copy; the
// compiled mass-spring system is always rebuilt from it (model/Compiler.h).

#include "geometry/Vec3.h"
#include "model/Piece.h"
#include "model/Rail.h"

#include <map>
#include <vector>

namespace netsculpt {

struct Sculpture {
    std::map<RailId, Rail> rails;     ///< ordered by id: iteration order is deterministic
    std::map<PieceId, Piece> pieces;  ///< ordered by id
    std::vector<Seam> seams;
    std::uint32_t nextRailId = 1;     ///< ids are never reused within one line of edits
    std::uint32_t nextPieceId = 1;
    Vec3 gravity{0, 0, -9.81};        ///< m/s^2

    // ---- look-ups that throw UserError naming the id ("piece 7 was removed") ----
    const Rail& rail(RailId id) const;
    const Piece& piece(PieceId id) const;
    Piece& piece(PieceId id);
    bool hasRail(RailId id) const { return rails.count(id) != 0; }
    bool hasPiece(PieceId id) const { return pieces.count(id) != 0; }

    /// Pieces whose top hangs from `id` (directly).
    std::vector<PieceId> childrenOf(PieceId id) const;
    /// `id` and everything hanging below it, parents before children.
    std::vector<PieceId> subtreeOf(PieceId id) const;
    /// Pieces whose top or last row is held by rail `id`.
    std::vector<PieceId> piecesOnRail(RailId id) const;
    /// All pieces, each after the pieces it hangs from.
    std::vector<PieceId> topologicalOrder() const;
    /// The seam partner on the right of `id` (its last column), or null.
    PieceId rightPartner(PieceId id) const;
    /// The seam partner on the left of `id` (its column 0), or null.
    PieceId leftPartner(PieceId id) const;
};

/// A knot of the model: a piece's (row, column).
struct KnotKey {
    PieceId piece;
    int row = 0;
    int column = 0;
    bool operator==(const KnotKey&) const = default;
};

/// The parents' last-row knots a ParentEdge hangs from, in order, each shared knot once
/// (consecutive parts of a split parent share their seam knot when their rows are equal).
std::vector<KnotKey> sourceRow(const Sculpture& s, const ParentEdge& edge);

/// Column count of a whole child for a source row of n knots through `gear`; throws UserError
/// when the gear does not divide (message lists what would be allowed).
int gearedColumns(int sourceKnots, bool ringClosed, Gear gear);

/// Horizontal knot spacing of a piece's top row, m (rail arc length per column, or the
/// parent's spacing divided by the gear). Used for connect_to_rail on open rails.
double topSpacing(const Sculpture& s, PieceId id);

/// The physical ranges a sculpture's numbers must lie in: wide enough for any net a net maker
/// can tie (on Earth or in a scaled test), narrow enough that weights, forces and lengths stay
/// far from overflow and underflow (a gravity of 1e300 made every load in the report infinite).
inline constexpr double kMaxBarLength = 1000.0;    // m
inline constexpr double kMaxStiffness = 1e12;      // N (EA; a 10 cm steel bar is about 1.6e9)
inline constexpr double kMaxKnotMass = 1000.0;     // kg
inline constexpr double kMaxLinearDensity = 1000.0; // kg/m
inline constexpr double kMinGravity = 1e-3;        // m/s^2, magnitude
inline constexpr double kMaxGravity = 1e3;         // m/s^2, magnitude (about 100 g)

/// Throws UserError naming the vector and the allowed range unless `gravity` is finite with a
/// magnitude from kMinGravity to kMaxGravity.
void checkGravity(const Vec3& gravity);

/// Recomputes what follows from the joins (whole children's column counts and closedness,
/// bar profile ranges) in topological order, then checks every invariant. Throws UserError on
/// the first violation; callers work on a copy, so the original sculpture is untouched.
void refreshAndValidate(Sculpture& s);

/// Allowed gears, for messages: "3, 2, 1, 1/2, 1/3".
const std::vector<Gear>& allowedGears();
std::string toString(Gear g);

} // namespace netsculpt
