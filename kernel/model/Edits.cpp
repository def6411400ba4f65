#include "model/Edits.h"

#include "model/Error.h"

#include <algorithm>
#include <cmath>

namespace netsculpt {

namespace {

const Colour kPalette[] = {{0.85, 0.35, 0.20}, {0.20, 0.50, 0.80}, {0.30, 0.65, 0.30}, {0.75, 0.60, 0.15},
                           {0.55, 0.30, 0.70}, {0.15, 0.65, 0.65}, {0.80, 0.30, 0.50}, {0.45, 0.45, 0.45}};

Colour paletteColour(PieceId id) { return kPalette[(id.value - 1) % std::size(kPalette)]; }

void checkName(const std::string& name, const char* what) {
    if (name.find_first_of("\n\r") != std::string::npos)
        throw UserError(std::string(what) + " name must be one line, got \"" + name + "\"");
    if (name.size() > 200) throw UserError(std::string(what) + " name must be at most 200 characters");
}

void checkRows(int rows) {
    if (rows < 1 || rows > 100000)
        throw UserError("rows must be a whole number from 1 to 100000, got " + std::to_string(rows));
}

void checkLength(double length, const char* what) {
    if (!(length > 0 && length <= kMaxBarLength))
        throw UserError(std::string(what) + " must be a number of metres above 0 and at most " +
                        formatNumber(kMaxBarLength) + ", got " + formatNumber(length));
}

void checkPosition(double t) {
    if (!std::isfinite(t)) throw UserError("rail position must be a finite number, got " + formatNumber(t));
}

/// A rail position on `rail` (DESIGN.md: t in [0, 1), the fraction of its length from its first
/// point; 1 is let through as the same point as 0 on a closed rail, the far end on an open one,
/// whose edges are checked where they are laid out).
void checkPositionOn(const Sculpture& s, RailId id, double t) {
    checkPosition(t);
    if (t >= 0 && t <= 1)
        return;
    const std::string& name = s.rail(id).name;
    const std::string rail = name == toString(id) ? name : toString(id) + " (" + name + ")";
    throw UserError("rail position 'at' on " + rail + " must be from 0 to 1 (the fraction of the "
                    "rail's length from its first point), got " + formatNumber(t));
}

Piece newPiece(Sculpture& s, int rows, double bar) {
    Piece p;
    p.id = PieceId(s.nextPieceId++);
    p.name = "piece " + std::to_string(p.id.value);
    p.rows = rows;
    p.bar = BarProfile{BarAxis::Column, bar, bar, 0, 0};
    p.colour = paletteColour(p.id);
    return p;
}

/// The rail positions the piece's columns cover: (t of column 0, t of the last column).
std::pair<double, double> railExtent(const Piece& p, const RailEdge& e) {
    return {railPosition(e, 0), railPosition(e, p.columns - 1)};
}

void respaceRailEdge(RailEdge& e, const Piece& p, int newColumns, const Rail& rail) {
    const bool fullRing = p.closed && rail.curve().closed();
    const auto [t0, t1] = railExtent(p, e);
    e.at = t0;
    e.offset = 0;
    e.step = fullRing ? 1.0 / newColumns : std::abs(t1 - t0) / (newColumns - 1);
}

void setEndLength(Piece& p, bool rightEnd, double length) {
    const double first = rightEnd ? p.bar.at(0) : length;
    const double last = rightEnd ? length : p.bar.at(p.columns - 1);
    p.bar = BarProfile{BarAxis::Column, first, last, 0, first == last ? 0 : p.columns - 1};
}

void replaceParent(Sculpture& s, PieceId old, const std::vector<PieceId>& parts) {
    for (auto& [id, p] : s.pieces) {
        if (p.onRail()) continue;
        auto& parents = std::get<ParentEdge>(p.top).parents;
        auto it = std::find(parents.begin(), parents.end(), old);
        if (it == parents.end()) continue;
        it = parents.erase(it);
        parents.insert(it, parts.begin(), parts.end());
    }
}

} // namespace

RailId addRail(Sculpture& s, const std::string& name, const CurveSpec& spec) {
    checkName(name, "rail");
    Rail rail{RailId(s.nextRailId), name, std::make_shared<const Curve>(Curve::build(spec))};
    if (rail.name.empty()) rail.name = "rail " + std::to_string(rail.id.value);
    ++s.nextRailId;
    s.rails.emplace(rail.id, std::move(rail));
    return RailId(s.nextRailId - 1);
}

void removeRail(Sculpture& s, RailId id) {
    const Rail& rail = s.rail(id);
    const auto users = s.piecesOnRail(id);
    if (!users.empty())
        throw UserError("cannot remove " + toString(id) + " (" + rail.name + "): " + toString(users.front()) +
                        " hangs from it or is connected to it; remove or disconnect that piece first");
    s.rails.erase(id);
}

void renameRail(Sculpture& s, RailId id, const std::string& name) {
    (void)s.rail(id);
    checkName(name, "rail");
    s.rails.at(id).name = name;
}

PieceId attachToRail(Sculpture& s, const AttachToRailArgs& a) {
    const Rail& rail = s.rail(a.rail);
    checkRows(a.rows);
    checkLength(a.bar, "bar length");
    checkPositionOn(s, a.rail, a.at);
    const bool closed = rail.curve().closed();
    int columns = a.columns;
    if (columns == 0) {
        checkLength(a.spacing, "spacing (or columns)");
        const double n = std::round(rail.curve().length() / a.spacing);
        if (n > 1e6) throw UserError("spacing " + formatNumber(a.spacing) + " m gives more than 10^6 columns");
        columns = int(n) + (closed ? 0 : 1);
    } else if (a.spacing != 0) {
        throw UserError("give columns or spacing, not both (columns " + std::to_string(a.columns) + ", spacing " +
                        formatNumber(a.spacing) + ")");
    }
    const int minColumns = closed ? 3 : 2;
    if (columns < minColumns || columns > 1000000)
        throw UserError("columns must be a whole number from " + std::to_string(minColumns) + " to 1000000 on " +
                        (closed ? "a closed" : "an open") + " rail, got " + std::to_string(columns));
    if (!closed && a.at != 0)
        throw UserError("a piece on an open rail spans the whole rail; at must be 0, got " + formatNumber(a.at));
    Piece p = newPiece(s, a.rows, a.bar);
    p.columns = columns;
    p.closed = closed;
    // Reversed on an open rail, column 0 is at its far end (rail position 1) and the row runs back.
    const double start = !closed && a.reverse ? 1.0 : a.at;
    p.top = RailEdge{a.rail, start, closed ? 1.0 / columns : 1.0 / (columns - 1), 0, a.reverse};
    const PieceId id = p.id;
    s.pieces.emplace(id, std::move(p));
    return id;
}

PieceId attachToPiece(Sculpture& s, const AttachToPieceArgs& a) {
    const Piece& parent = s.piece(a.parent);
    checkRows(a.rows);
    checkLength(a.bar, "bar length");
    ParentEdge edge{{a.parent}, a.gear, parent.closed, 0, true};
    const int columns = gearedColumns(parent.columns, parent.closed, a.gear);
    if (columns < (parent.closed ? 3 : 2))
        throw UserError(
            "attach_to_piece: gear " + toString(a.gear) + " below " + toString(a.parent) + "'s " +
            std::to_string(parent.columns) + " columns gives " + std::to_string(columns) +
            (parent.closed ? ", and a closed tube needs 3" : ", and an open sheet needs 2"));
    Piece p = newPiece(s, a.rows, a.bar);
    p.columns = columns;
    p.closed = parent.closed;
    p.top = edge;
    if (a.material)
        p.material = *a.material; // checked with the sculpture (checkMaterial)
    const PieceId id = p.id;
    s.pieces.emplace(id, std::move(p));
    return id;
}

std::string splitRefusal(const Sculpture& s, PieceId id) {
    const Piece& p = s.piece(id);
    if (!p.closed && p.columns < 3)
        return "split: " + toString(id) + " is an open piece of " + std::to_string(p.columns) +
               " columns, which has no column to split at (an open piece needs 3)";
    // Seamed pieces vary their bar length by column (set_bar_length's rule): a profile by row
    // would be rescaled on one side of the seam by the next set_rows of one part.
    if (p.bar.gradedByRow())
        return "split: " + toString(id) +
               " varies its bar length by row, and seamed pieces vary it by column; set its bar "
               "length by column (or to one length) before splitting it";
    return {};
}

std::pair<PieceId, PieceId> split(Sculpture& s, PieceId id, int column) {
    if (const std::string refusal = splitRefusal(s, id); !refusal.empty())
        throw UserError(refusal);
    Piece& a = s.piece(id);
    const int c = a.columns;
    const int last = a.closed ? c - 1 : c - 2;
    if (column < 1 || column > last)
        throw UserError("split: column must be from 1 to " + std::to_string(last) + " for " +
                        toString(id) + " (" + std::to_string(c) + " columns, " +
                        (a.closed ? "closed" : "open") + "), got " + std::to_string(column));
    const bool wasClosed = a.closed;
    Piece b = a;
    b.id = PieceId(s.nextPieceId++);
    b.name = "piece " + std::to_string(b.id.value);
    b.colour = paletteColour(b.id);
    b.columns = wasClosed ? c - column + 1 : c - column;
    b.closed = false;
    if (b.bar.axis == BarAxis::Column) { // a profile by row has one length: the same in both
        b.bar.from -= column;
        b.bar.to -= column;
    }
    if (b.onRail()) std::get<RailEdge>(b.top).offset += column;
    else {
        std::get<ParentEdge>(b.top).offset += column;
        std::get<ParentEdge>(b.top).whole = false;
    }
    if (b.bottom) b.bottom->offset += column;
    a.columns = column + 1;
    a.closed = false;
    if (!a.onRail()) std::get<ParentEdge>(a.top).whole = false;

    for (Seam& seam : s.seams)
        if (seam.left == id) seam.left = b.id;
    s.seams.push_back({id, b.id});
    if (wasClosed) s.seams.push_back({b.id, id});
    replaceParent(s, id, {id, b.id});
    const PieceId bid = b.id;
    s.pieces.emplace(bid, std::move(b));
    return {id, bid};
}

void setRows(Sculpture& s, PieceId id, int rows) {
    Piece& p = s.piece(id);
    checkRows(rows);
    if (p.bar.axis == BarAxis::Row) {
        const double first = p.bar.at(0), last = p.bar.at(p.rows - 1);
        p.bar = BarProfile{BarAxis::Row, first, last, 0, first == last ? 0 : rows - 1};
    }
    p.rows = rows;
}

void setColumns(Sculpture& s, PieceId id, int columns) {
    Piece& p = s.piece(id);
    const int minColumns = p.closed ? 3 : 2;
    if (p.onRail()) {
        if (columns < minColumns || columns > 1000000)
            throw UserError("set_columns: columns must be from " + std::to_string(minColumns) + " to 1000000 for " +
                            toString(id) + ", got " + std::to_string(columns));
        const int old = p.columns;
        respaceRailEdge(std::get<RailEdge>(p.top), p, columns, s.rail(p.railTop().rail));
        if (p.bottom) respaceRailEdge(*p.bottom, p, columns, s.rail(p.bottom->rail));
        const double first = p.bar.at(0), last = p.bar.at(old - 1);
        p.columns = columns;
        if (p.bar.axis == BarAxis::Column) p.bar = BarProfile{BarAxis::Column, first, last, 0, first == last ? 0 : columns - 1};
        return;
    }
    ParentEdge& edge = std::get<ParentEdge>(p.top);
    if (!edge.whole)
        throw UserError("set_columns: " + toString(id) + " is a split part; its columns follow the knots it hangs from");
    const int n = int(sourceRow(s, edge).size());
    Gear best = edge.gear;
    int bestColumns = -1;
    std::string allowed;
    for (Gear g : allowedGears()) {
        int count = 0;
        try {
            count = gearedColumns(n, edge.ringClosed, g);
        } catch (const UserError&) {
            continue;
        }
        allowed += (allowed.empty() ? "" : ", ") + std::to_string(count) + " (gear " + toString(g) + ")";
        if (bestColumns < 0 || std::abs(std::log(double(count) / columns)) < std::abs(std::log(double(bestColumns) / columns))) {
            best = g;
            bestColumns = count;
        }
    }
    if (columns < 1) throw UserError("set_columns: columns must be positive, got " + std::to_string(columns) + "; allowed below " + toString(edge.parents.front()) + ": " + allowed);
    edge.gear = best;
}

void setGear(Sculpture& s, PieceId id, Gear gear) {
    Piece& p = s.piece(id);
    if (p.onRail()) throw UserError("set_gear: " + toString(id) + " hangs from a rail, not from a piece; set its columns instead");
    ParentEdge& edge = std::get<ParentEdge>(p.top);
    if (!edge.whole) throw UserError("set_gear: " + toString(id) + " is a split part; its gear is fixed by the join it shares");
    (void)gearedColumns(int(sourceRow(s, edge).size()), edge.ringClosed, gear);
    edge.gear = gear;
}

void setBarLength(Sculpture& s, PieceId id, std::optional<int> column, double length) {
    Piece& p = s.piece(id);
    checkLength(length, "bar length");
    const PieceId left = s.leftPartner(id), right = s.rightPartner(id);
    if (!column || (!left && !right)) {
        if (column && *column != 0 && *column != p.columns - 1)
            throw UserError("set_bar_length: column must be 0 or " + std::to_string(p.columns - 1) + " for " + toString(id) + ", got " + std::to_string(*column));
        p.bar = BarProfile{BarAxis::Column, length, length, 0, 0};
        if (left) setEndLength(s.piece(left), true, length);
        if (right) setEndLength(s.piece(right), false, length);
        return;
    }
    if (*column != 0 && *column != p.columns - 1)
        throw UserError("set_bar_length: column must be 0 (first column) or " + std::to_string(p.columns - 1) +
                        " (last column) for " + toString(id) + ", got " + std::to_string(*column));
    const bool rightEnd = *column == p.columns - 1;
    setEndLength(p, rightEnd, length);
    if (rightEnd && right) setEndLength(s.piece(right), false, length);
    if (!rightEnd && left) setEndLength(s.piece(left), true, length);
}

void setBarLengthByRow(Sculpture& s, PieceId id, int row, double length) {
    Piece& p = s.piece(id);
    checkLength(length, "bar length");
    if (s.leftPartner(id) || s.rightPartner(id))
        throw UserError("set_bar_length: " + toString(id) + " has a seam; seamed pieces vary their bar length by column, not by row");
    if (row != 0 && row != p.rows - 1)
        throw UserError("set_bar_length: row must be 0 (top) or " + std::to_string(p.rows - 1) + " (last row) for " + toString(id) + ", got " + std::to_string(row));
    const double first = p.bar.axis == BarAxis::Row ? p.bar.at(0) : p.bar.at(0);
    const double last = p.bar.axis == BarAxis::Row ? p.bar.at(p.rows - 1) : p.bar.at(0);
    const double newFirst = row == 0 ? length : first;
    const double newLast = row == p.rows - 1 ? length : last;
    p.bar = BarProfile{BarAxis::Row, newFirst, newLast, 0, newFirst == newLast ? 0 : p.rows - 1};
}

void connectToRail(Sculpture& s, PieceId id, RailId railId, double at, bool reverse) {
    const Piece& p = s.piece(id);
    const Rail& rail = s.rail(railId);
    checkPositionOn(s, railId, at);
    if (p.closed && !rail.curve().closed())
        throw UserError("connect_to_rail: " + toString(id) + " is a closed tube and " + toString(railId) + " (" + rail.name + ") is open; a tube connects to a closed rail");
    const double step = (p.closed && rail.curve().closed()) ? 1.0 / p.columns : topSpacing(s, id) / rail.curve().length();
    s.piece(id).bottom = RailEdge{railId, at, step, 0, reverse};
}

void disconnect(Sculpture& s, PieceId id) {
    Piece& p = s.piece(id);
    if (!p.bottom) throw UserError("disconnect: " + toString(id) + " is not connected to a rail");
    p.bottom.reset();
}

void setMaterial(Sculpture& s, PieceId id, const Material& material) { s.piece(id).material = material; }

void setColour(Sculpture& s, PieceId id, const Colour& c) {
    Piece& p = s.piece(id);
    for (double v : {c.r, c.g, c.b})
        if (!(v >= 0 && v <= 1)) throw UserError("colour components must be from 0 to 1, got " + formatNumber(v));
    p.colour = c;
}

void renamePiece(Sculpture& s, PieceId id, const std::string& name) {
    Piece& p = s.piece(id);
    checkName(name, "piece");
    p.name = name;
}

void removePiece(Sculpture& s, PieceId id) {
    (void)s.piece(id); // an unknown or removed id is an error, not a no-op
    const auto doomed = s.subtreeOf(id);
    for (PieceId d : doomed) s.pieces.erase(d);
    std::erase_if(s.seams, [&](const Seam& seam) {
        return std::find(doomed.begin(), doomed.end(), seam.left) != doomed.end() ||
               std::find(doomed.begin(), doomed.end(), seam.right) != doomed.end();
    });
}

void setGravity(Sculpture& s, const Vec3& gravity) {
    checkGravity(gravity);
    s.gravity = gravity;
}

Gear parseGear(const std::string& text) {
    std::string t = text;
    std::erase(t, ' ');
    if (!t.empty() && (t[0] == 'x' || t[0] == '*')) t = t.substr(1);
    if (!t.empty() && t[0] == '/') t = "1" + t;
    for (Gear g : allowedGears())
        if (toString(g) == t) return g;
    throw UserError("gear \"" + text + "\" is not allowed; allowed gears are 3, 2, 1, 1/2, 1/3");
}

} // namespace netsculpt
