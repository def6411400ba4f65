#pragma once
// Compiles a sculpture into its flat mass-spring system (DESIGN.md "Net piece", "How pieces are
// joined", "Physics"): one knot per distinct knot of the model (shared knots of gear junctions,
// seams and g = 1 joins are one knot), one bar per distinct pair, initial positions from
// Eq. 1 and 2 of the paper, masses and stiffnesses from each piece's material.

#include "model/Sculpture.h"
#include "physics/MassSpringSystem.h"

#include <functional>
#include <optional>
#include <map>

namespace netsculpt {

/// Where a piece's knots went in the system: index[row * columns + column].
struct PieceKnots {
    int rows = 0;
    int columns = 0;
    std::vector<std::uint32_t> index;
    std::uint32_t at(int row, int column) const { return index[std::size_t(row) * columns + column]; }
};

struct CompiledSculpture {
    MassSpringSystem system;
    std::map<PieceId, PieceKnots> pieces;
    /// Knot index of a piece's (row, column). Throws UserError when out of range.
    std::uint32_t knotOf(PieceId piece, int row, int column) const;
};

/// Compiles `s` (already refreshed and validated). Throws UserError when the initial geometry
/// does not exist: a bar length not above half the spacing of the two knots it hangs from.
CompiledSculpture compileSculpture(const Sculpture& s);

/// Within this distance of (0, 0, 0) a coordinate's unit in the last place is at most 7.1e-15 m,
/// a force of 1.4e-8 N on a 0.1 m bar of EA 2e5 N (half a millionth of a 2.9 g knot's weight),
/// so a sculpture there is relaxed where it stands (m).
constexpr double kOriginFreeRadius = 32;

/// The system origin of `s` (MassSpringSystem::origin): per axis, the whole metre nearest the
/// centre of the points of the rails that hold pieces, where that centre is more than
/// kOriginFreeRadius from 0, else 0. Whole metres, so that moving a shape between two systems'
/// origins is exact; rails that hold nothing (a site drawing's other lines) do not move it, unless
/// none holds a piece yet (then all the rails place it: the studio draws them from it).
Vec3 chooseOrigin(const Sculpture& s);

/// Two holds of one seam knot closer than this are one place (rounding between the pieces'
/// rail positions); farther apart they are two places, which a knot cannot be at.
constexpr double kSameHoldDistance = 1e-6; // m

/// Rail position t of column c of a rail edge.
double railPosition(const RailEdge& edge, int column);

/// A warm start after an edit: free knots of `next` that stand for the same (piece, row, column)
/// as in `previous` take its (relaxed) position (moved to next's origin), for pieces whose column
/// count is unchanged;
/// knots of rows added below move with the last old row, except in a piece tied to a rail below,
/// where the free rows from the old rail row down are spread evenly between the last row kept and
/// the rail. Returns how many knots were carried.
/// `renamed`, when given, names a knot of `next` as `previous` had it, for an edit that renamed
/// knots without moving them (a split: the right part's (row, c) was the piece's (row, c + k));
/// nullopt when it had no other name.
using KnotRenaming = std::function<std::optional<KnotRef>(const KnotRef&)>;
std::size_t carryPositions(const CompiledSculpture& previous, CompiledSculpture& next,
                           const KnotRenaming& renamed = {});
/// The renaming of a split of `piece` at `column` into `piece` and `right`: `columns` and
/// `closed` are the piece's before it.
KnotRenaming splitRenaming(PieceId piece, PieceId right, int column, int columns);

} // namespace netsculpt
