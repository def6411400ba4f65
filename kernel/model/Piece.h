#pragma once
// A net piece (DESIGN.md "Net piece" and "How pieces are joined"): a rows x columns grid of
// knots in staggered rows, with the join of its top edge and, optionally, of its last row.

#include "model/Ids.h"
#include "model/Material.h"

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace netsculpt {

/// A gear between a parent's last row and a child's top row: child columns = num/den x parent.
/// Allowed: 3/1, 2/1, 1/1, 1/2, 1/3.
struct Gear {
    int num = 1;
    int den = 1;
    bool operator==(const Gear&) const = default;
    double value() const { return double(num) / den; }
};

/// Knots of a row held at equally spaced rail positions: column c at
/// t = at + (offset + c) * step, or at - (offset + c) * step when reversed.
/// The integer offset keeps positions bit-identical when a piece is split.
struct RailEdge {
    RailId rail;
    double at = 0;      ///< rail position of virtual column 0
    double step = 0;    ///< rail position step per column (> 0)
    int offset = 0;     ///< virtual column of this piece's column 0
    bool reverse = false;
    bool operator==(const RailEdge&) const = default;
};

/// The top row hangs from the last rows of parent pieces, concatenated in order (a split parent
/// lists all its parts), through a gear. The child's column c is virtual column offset + c of
/// the geared row. `whole` children span the whole geared row and their column count follows
/// the parent; split parts (whole = false) keep their range.
struct ParentEdge {
    std::vector<PieceId> parents;
    Gear gear;
    bool ringClosed = false; ///< the parents' last rows form a closed ring
    int offset = 0;
    bool whole = true;
    bool operator==(const ParentEdge&) const = default;
};

/// Which way the bar length varies across a piece.
enum class BarAxis { Column, Row };

/// Bar length at index i (column or row) = lerp(first, last) over [from, to]; from == to means
/// constant. Integer end indices keep split parts bit-identical to the original piece.
struct BarProfile {
    BarAxis axis = BarAxis::Column;
    double first = 0.25; ///< m, at index `from`
    double last = 0.25;  ///< m, at index `to`
    int from = 0;
    int to = 0;
    bool operator==(const BarProfile&) const = default;

    double at(int index) const {
        if (from == to) return first;
        return first + (last - first) * (double(index - from) / double(to - from));
    }
    /// Varies by row from one length to another (a profile by row of one length does not).
    bool gradedByRow() const { return axis == BarAxis::Row && first != last; }
};

struct Piece {
    PieceId id;
    std::string name;
    int rows = 1;
    int columns = 2;
    bool closed = false; ///< a tube: column indices wrap around
    BarProfile bar;
    Material material;
    Colour colour;
    std::variant<RailEdge, ParentEdge> top;
    std::optional<RailEdge> bottom; ///< last row connected to a rail
    bool operator==(const Piece&) const = default;

    bool onRail() const { return std::holds_alternative<RailEdge>(top); }
    const RailEdge& railTop() const { return std::get<RailEdge>(top); }
    const ParentEdge& parentTop() const { return std::get<ParentEdge>(top); }
    /// Bar length of a bar between (row r, column c) and (row r2, column c2): the mean of the
    /// two ends' lengths along the profile's axis.
    double barLength(int r, int c, int r2, int c2) const {
        if (bar.axis == BarAxis::Column) return 0.5 * (bar.at(c) + bar.at(c2));
        return 0.5 * (bar.at(r) + bar.at(r2));
    }
};

/// left's last column and right's column 0 are the same knots (rows 0 .. min(rows) - 1).
struct Seam {
    PieceId left;
    PieceId right;
    bool operator==(const Seam&) const = default;
};

} // namespace netsculpt
