#pragma once
// Carrying a relaxed shape across an edit: where new rows start, and the tensions the shape had
// before the edit, which the fast path turns into a predictor step (RelaxOptions::startTensions).
// Used by the studio's live preview (interaction/LiveRelaxer.h) and by Document::relax after an
// edit of a relaxed sculpture. Knots are matched by their first (piece, row, column).

#include "physics/MassSpringSystem.h"

#include <cstddef>
#include <vector>

namespace netsculpt {

/// Knots of `next` that `previous` did not have, in rows added below a piece whose column count
/// is unchanged, placed where the rows above them lead: p(r, c) = p(r-1, c) + p(r-2, c) -
/// p(r-3, c) (rows alternate their half-column shift, so the step two rows up has the new row's).
/// A hung net is narrower and more stretched at the bottom than the Eq. 2 geometry that the
/// document's warm start offsets new rows by, which starts their bars up to tens of per cent
/// from their length; after this they start near the strain of the rows above. Knots matched by
/// their first (piece, row, column). Not in a piece tied to a rail below, whose new rows the
/// document's warm start places between its kept rows and the rail. Returns how many were placed.
/// Free knots of `next` that `previous` also had take `previous`'s positions: a shape relaxed
/// under an older law, carried across the edits since (the studio's refine starts from its last
/// refined shape, not from the soft preview's). Returns how many were carried.
std::size_t carryMatchedPositions(const MassSpringSystem& previous, MassSpringSystem& next);
/// Whether each knot of `next` that `previous` also had (the same first (piece, row, column)) is
/// the same knot of the net, so that a shape of `previous` carried to it (carryMatchedPositions)
/// is where it hangs: false when a piece in both has another column count (columns and gears
/// respace a row), when a piece tied to a rail below has another row count (the document's
/// warm start spreads its rows anew between the rows it kept and the rail), or when a knot held
/// in both is held somewhere else (another sculpture whose pieces have the same numbers, or a
/// rail moved).
bool sameKnotsWhereMatched(const MassSpringSystem& previous, const MassSpringSystem& next);
/// Whether every knot held in both systems (matched as above) is held at the same place: false
/// for another sculpture whose pieces have the same numbers, or after a rail moved.
bool heldAtTheSamePlaces(const MassSpringSystem& previous, const MassSpringSystem& next);
std::size_t continueNewRows(const MassSpringSystem& previous, MassSpringSystem& next);
/// A row drag's next step (rows added or removed again as in the step from `before` to
/// `previous`, both relaxed), its new rows placed by continueNewRows: `positions` (next's) of free
/// knots that `previous` had become previous + (previous - before), the motion they had in that
/// step; knots that `before` or `previous` lacked (the rows either step added) move as the knot
/// above them in their column. Matched by their first (piece, row, column); nothing moves when
/// the three are measured from other origins. Returns how many moved.
std::size_t continueRowDrag(const MassSpringSystem& before, const MassSpringSystem& previous,
                            const MassSpringSystem& next, std::vector<Vec3>& positions);
/// The warm-start hint for relaxing `next` after `previous` (RelaxOptions::startTensions): for
/// every bar of `next` that joins the same two (piece, row, column) knots as a bar of
/// `previous`, that bar's tension under `previous`'s rest length and stiffness at `next`'s
/// positions (N): the tension the shape had before the edit. A bar new in `next` takes the mean
/// positive hint of the bars at its knots (new rows carry load like the row above; rows further
/// down take the hints of the new rows above them), or its own elastic tension when none has one.
/// Empty (no hint) when fewer than half of `next`'s bars existed in `previous`.
std::vector<double> startTensions(const MassSpringSystem& previous, const MassSpringSystem& next);

} // namespace netsculpt
