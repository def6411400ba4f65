#include "model/Sculpture.h"

#include "model/Compiler.h"
#include "model/Error.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace netsculpt {

namespace {

constexpr int kMaxRows = 100000;
constexpr int kMaxColumns = 1000000;
constexpr double kMaxKnots = 20.0e6; // beyond this a sculpture would not fit in memory comfortably

bool hangsFrom(const Piece& p, PieceId parent) {
    if (p.onRail()) return false;
    const auto& parents = p.parentTop().parents;
    return std::find(parents.begin(), parents.end(), parent) != parents.end();
}

void renormalizeColumnProfile(Piece& p, int oldColumns) {
    if (p.bar.axis != BarAxis::Column || oldColumns == p.columns) return;
    const double first = p.bar.at(0);
    const double last = p.bar.at(oldColumns - 1);
    p.bar = BarProfile{BarAxis::Column, first, last, 0, std::max(0, p.columns - 1)};
    if (first == last) p.bar.to = 0;
}

void checkRailEdge(const Sculpture& s, const Piece& p, const RailEdge& e, const char* which) {
    const Rail& rail = s.rail(e.rail);
    if (!(e.step > 0) || !std::isfinite(e.step) || !std::isfinite(e.at))
        throw UserError(toString(p.id) + ": " + which + " rail spacing must be a positive number, got " +
                        formatNumber(e.step));
    if (p.closed && !rail.curve().closed())
        throw UserError(toString(p.id) + " is a closed tube; its " + which + " edge needs a closed rail, and " +
                        toString(rail.id) + " (" + rail.name + ") is open");
    if (!rail.curve().closed()) {
        const double span = (p.columns - 1) * e.step;
        const double t0 = e.reverse ? e.at - e.offset * e.step : e.at + e.offset * e.step;
        const double t1 = e.reverse ? t0 - span : t0 + span;
        const double tolerance = 1e-9;
        if (std::min(t0, t1) < -tolerance || std::max(t0, t1) > 1 + tolerance)
            throw UserError(toString(p.id) + ": its " + which + " row would run off the end of open " +
                            toString(rail.id) + " (rail positions " + formatNumber(std::min(t0, t1)) +
                            " to " + formatNumber(std::max(t0, t1)) + "; allowed 0 to 1: the row " +
                            "needs " + formatNumber(span * rail.curve().length()) + " m of rail " +
                            "from there, the rail is " + formatNumber(rail.curve().length()) +
                            " m long)");
    }
}

void refreshParentTop(const Sculpture& s, Piece& p) {
    ParentEdge& edge = std::get<ParentEdge>(p.top);
    if (edge.parents.empty()) throw UserError(toString(p.id) + ": its top has no parent piece");
    for (PieceId parent : edge.parents) (void)s.piece(parent);
    const int n = int(sourceRow(s, edge).size());
    int virtualColumns = 0;
    try {
        virtualColumns = gearedColumns(n, edge.ringClosed, edge.gear);
    } catch (const UserError& e) { // name the child whose gear the parent's row no longer fits
        throw UserError(toString(p.id) + ", hanging below " + toString(edge.parents.front()) +
                        ": " + e.what());
    }
    if (edge.whole) {
        const int old = p.columns;
        p.columns = virtualColumns;
        p.closed = edge.ringClosed;
        renormalizeColumnProfile(p, old);
        return;
    }
    p.closed = false;
    const int limit = edge.ringClosed ? virtualColumns : virtualColumns - 1;
    if (edge.offset < 0 || edge.offset + p.columns - 1 > limit)
        throw UserError(toString(p.id) + " is a split part hanging from columns " + std::to_string(edge.offset) +
                        " to " + std::to_string(edge.offset + p.columns - 1) + " of a row that now has " +
                        std::to_string(virtualColumns) +
                        " columns; this change would break its join (change the parent before splitting)");
}

void checkMaterial(const Piece& p) {
    const Material& m = p.material;
    if (!(m.stiffness > 0 && m.stiffness <= kMaxStiffness))
        throw UserError(toString(p.id) +
                        ": stiffness (EA) must be a number of newtons above 0 and at most " +
                        formatNumber(kMaxStiffness) + ", got " + formatNumber(m.stiffness));
    if (!(m.compressionRatio >= 0 && m.compressionRatio <= 1))
        throw UserError(toString(p.id) + ": compression_ratio must be between 0 and 1, got " +
                        formatNumber(m.compressionRatio));
    if (!(m.knotMass >= 0 && m.knotMass <= kMaxKnotMass))
        throw UserError(toString(p.id) + ": knot_mass must be a number of kilograms from 0 to " +
                        formatNumber(kMaxKnotMass) + ", got " + formatNumber(m.knotMass));
    if (!(m.linearDensity >= 0 && m.linearDensity <= kMaxLinearDensity))
        throw UserError(toString(p.id) + ": linear_density must be a number of kg/m from 0 to " +
                        formatNumber(kMaxLinearDensity) + ", got " + formatNumber(m.linearDensity));
    if (!(m.knotMass > 0 || m.linearDensity > 0))
        throw UserError(toString(p.id) +
                        ": knot_mass and linear_density are both 0; a net must weigh something");
    if (m.breakingLoad && !(*m.breakingLoad > 0 && std::isfinite(*m.breakingLoad)))
        throw UserError(toString(p.id) + ": breaking_load must be a finite number of newtons " +
                        "above 0 (or none), got " + formatNumber(*m.breakingLoad));
}

void checkPiece(const Sculpture& s, const Piece& p) {
    if (p.rows < 1 || p.rows > kMaxRows)
        throw UserError(toString(p.id) + ": rows must be between 1 and " + std::to_string(kMaxRows) + ", got " +
                        std::to_string(p.rows));
    const int minColumns = p.closed ? 3 : 2;
    if (p.columns < minColumns || p.columns > kMaxColumns)
        throw UserError(toString(p.id) + ": columns must be between " + std::to_string(minColumns) + " and " +
                        std::to_string(kMaxColumns) + (p.closed ? " for a closed tube" : " for an open sheet") +
                        ", got " + std::to_string(p.columns));
    for (int i : {p.bar.from, p.bar.to, 0, (p.bar.axis == BarAxis::Column ? p.columns : p.rows) - 1}) {
        const double l = p.bar.at(i);
        if (!(l > 0 && l <= kMaxBarLength))
            throw UserError(toString(p.id) + ": bar length must be a number of metres above 0 and at most " +
                            formatNumber(kMaxBarLength) + ", got " + formatNumber(l));
    }
    checkMaterial(p);
    if (p.onRail()) checkRailEdge(s, p, p.railTop(), "top");
    if (p.bottom && p.rows < 2)
        throw UserError(toString(p.id) + " has 1 row, so its last row is its top row, which " +
                        "already hangs where it is attached; a piece tied to a rail by its last "
                        "row needs at least 2 rows");
    if (p.bottom) checkRailEdge(s, p, *p.bottom, "last");
}

void checkSeams(const Sculpture& s) {
    std::set<PieceId> lefts, rights;
    for (const Seam& seam : s.seams) {
        const Piece& left = s.piece(seam.left);
        const Piece& right = s.piece(seam.right);
        if (!lefts.insert(seam.left).second || !rights.insert(seam.right).second)
            throw UserError("a piece can have one seam on each side; " + toString(seam.left) + " / " +
                            toString(seam.right) + " has more");
        if (left.bar.axis != BarAxis::Column || right.bar.axis != BarAxis::Column) continue;
        const double a = left.bar.at(left.columns - 1);
        const double b = right.bar.at(0);
        if (std::abs(a - b) > 1e-12 * std::max(a, b))
            throw UserError("the seam between " + toString(seam.left) + " and " + toString(seam.right) +
                            " would have two bar lengths (" + formatNumber(a) + " m and " + formatNumber(b) +
                            " m); at a seam both pieces have the same bar length");
    }
}

/// Split parts with as many rows, both tied by their last rows, share that row's seam knot: they
/// must hold it at one place. The only knots two rail edges hold (split parts' tops come from
/// one edge); checked here, so that a journal's replay, which compiles only at its end, names
/// the command that does it.
void checkSeamHolds(const Sculpture& s) {
    for (const Seam& seam : s.seams) {
        const Piece& left = s.piece(seam.left);
        const Piece& right = s.piece(seam.right);
        if (!left.bottom || !right.bottom || left.rows != right.rows)
            continue;
        const RailEdge& a = *left.bottom;
        const RailEdge& b = *right.bottom;
        const Vec3 pa = s.rail(a.rail).curve().pointAt(railPosition(a, left.columns - 1));
        const Vec3 pb = s.rail(b.rail).curve().pointAt(railPosition(b, 0));
        const double apart = distance(pa, pb);
        if (a.rail == b.rail && apart <= kSameHoldDistance)
            continue;
        throw UserError(toString(seam.right) + ": the knot at row " +
                        std::to_string(right.rows - 1) + ", column 0 is shared with " +
                        toString(seam.left) + " (a seam), which " + "holds it on " +
                        toString(a.rail) + " (" + s.rail(a.rail).name + "); " + toString(b.rail) +
                        " (" + s.rail(b.rail).name + ") would hold it " + formatNumber(apart) +
                        " m from there. Pieces that share a knot hold it " +
                        "at one place: tie both to the same rail, in line");
    }
}

} // namespace

const Rail& Sculpture::rail(RailId id) const {
    auto it = rails.find(id);
    if (it == rails.end()) {
        if (id.value == 0) throw UserError("no rail given (null rail id)");
        if (id.value < nextRailId) throw UserError(toString(id) + " was removed");
        throw UserError("there is no " + toString(id));
    }
    return it->second;
}

const Piece& Sculpture::piece(PieceId id) const {
    auto it = pieces.find(id);
    if (it == pieces.end()) {
        if (id.value == 0) throw UserError("no piece given (null piece id)");
        if (id.value < nextPieceId) throw UserError(toString(id) + " was removed");
        throw UserError("there is no " + toString(id));
    }
    return it->second;
}

Piece& Sculpture::piece(PieceId id) {
    return const_cast<Piece&>(static_cast<const Sculpture&>(*this).piece(id));
}

std::vector<PieceId> Sculpture::childrenOf(PieceId id) const {
    std::vector<PieceId> out;
    for (const auto& [pid, p] : pieces)
        if (hangsFrom(p, id)) out.push_back(pid);
    return out;
}

std::vector<PieceId> Sculpture::subtreeOf(PieceId id) const {
    std::vector<PieceId> out{id};
    std::set<PieceId> seen{id};
    for (std::size_t i = 0; i < out.size(); ++i)
        for (PieceId child : childrenOf(out[i]))
            if (seen.insert(child).second) out.push_back(child);
    return out;
}

std::vector<PieceId> Sculpture::piecesOnRail(RailId id) const {
    std::vector<PieceId> out;
    for (const auto& [pid, p] : pieces)
        if ((p.onRail() && p.railTop().rail == id) || (p.bottom && p.bottom->rail == id)) out.push_back(pid);
    return out;
}

std::vector<PieceId> Sculpture::topologicalOrder() const {
    std::vector<PieceId> order;
    std::set<PieceId> placed;
    while (order.size() < pieces.size()) {
        const std::size_t before = order.size();
        for (const auto& [pid, p] : pieces) {
            if (placed.count(pid)) continue;
            bool ready = p.onRail();
            if (!ready) {
                ready = true;
                for (PieceId parent : p.parentTop().parents)
                    if (!placed.count(parent)) ready = false;
            }
            if (ready) {
                order.push_back(pid);
                placed.insert(pid);
            }
        }
        if (order.size() == before) throw UserError("pieces hang from each other in a loop");
    }
    return order;
}

PieceId Sculpture::rightPartner(PieceId id) const {
    for (const Seam& seam : seams)
        if (seam.left == id) return seam.right;
    return {};
}

PieceId Sculpture::leftPartner(PieceId id) const {
    for (const Seam& seam : seams)
        if (seam.right == id) return seam.left;
    return {};
}

std::vector<KnotKey> sourceRow(const Sculpture& s, const ParentEdge& edge) {
    std::vector<KnotKey> row;
    const Piece* previous = nullptr;
    for (PieceId id : edge.parents) {
        const Piece& p = s.piece(id);
        const bool sharesFirst =
            previous && s.rightPartner(previous->id) == id && previous->rows == p.rows;
        for (int c = sharesFirst ? 1 : 0; c < p.columns; ++c) row.push_back({id, p.rows - 1, c});
        previous = &p;
    }
    if (edge.ringClosed && edge.parents.size() > 1) {
        const Piece& first = s.piece(edge.parents.front());
        if (s.rightPartner(previous->id) == first.id && previous->rows == first.rows) row.pop_back();
    }
    return row;
}

const std::vector<Gear>& allowedGears() {
    static const std::vector<Gear> gears{{3, 1}, {2, 1}, {1, 1}, {1, 2}, {1, 3}};
    return gears;
}

std::string toString(Gear g) {
    return g.den == 1 ? std::to_string(g.num) : std::to_string(g.num) + "/" + std::to_string(g.den);
}

int gearedColumns(int n, bool ringClosed, Gear gear) {
    if (std::find(allowedGears().begin(), allowedGears().end(), gear) == allowedGears().end())
        throw UserError("gear " + toString(gear) + " is not allowed; allowed gears are 3, 2, 1, 1/2, 1/3");
    const int intervals = ringClosed ? n : n - 1;
    if ((intervals * gear.num) % gear.den != 0) {
        std::string allowed;
        for (Gear g : allowedGears())
            if ((intervals * g.num) % g.den == 0)
                allowed += (allowed.empty() ? "" : ", ") + toString(g);
        throw UserError("gear " + toString(gear) + " does not divide a row of " + std::to_string(n) +
                        (ringClosed ? " knots around a tube" : " knots") + " (" + std::to_string(intervals) +
                        " intervals); allowed gears here: " + allowed);
    }
    const int childIntervals = intervals * gear.num / gear.den;
    return ringClosed ? childIntervals : childIntervals + 1;
}

double topSpacing(const Sculpture& s, PieceId id) {
    const Piece& p = s.piece(id);
    if (p.onRail()) return p.railTop().step * s.rail(p.railTop().rail).curve().length();
    const ParentEdge& edge = p.parentTop();
    return topSpacing(s, edge.parents.front()) / edge.gear.value();
}

void checkGravity(const Vec3& g) {
    const double magnitude = std::hypot(g.x, g.y, g.z);
    if (!(magnitude >= kMinGravity && magnitude <= kMaxGravity))
        throw UserError("gravity must be a vector of magnitude " + formatNumber(kMinGravity) + " to " +
                        formatNumber(kMaxGravity) + " m/s^2, got (" + formatNumber(g.x) + ", " +
                        formatNumber(g.y) + ", " + formatNumber(g.z) + ") m/s^2");
}

void refreshAndValidate(Sculpture& s) {
    checkGravity(s.gravity);
    double knots = 0;
    for (PieceId id : s.topologicalOrder()) {
        Piece& p = s.pieces.at(id);
        if (!p.onRail()) refreshParentTop(s, p);
        checkPiece(s, p);
        knots += double(p.rows) * p.columns;
    }
    checkSeamHolds(s);
    if (knots > kMaxKnots)
        throw UserError("the sculpture would have " + formatNumber(knots) + " knots; at most " +
                        formatNumber(kMaxKnots) + " are supported");
    checkSeams(s);
}

} // namespace netsculpt
