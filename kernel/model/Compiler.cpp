#include "model/Compiler.h"

#include "model/BarPairs.h"
#include "model/Error.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <numeric>
#include <set>
#include <unordered_map>

namespace netsculpt {

namespace {

constexpr std::uint32_t kUnassigned = 0xffffffffu;

/// Union-find over model knot slots (piece, row, column), merged where knots are shared.
class KnotSlots {
  public:
    explicit KnotSlots(const Sculpture& s) : order_(s.topologicalOrder()) {
        std::size_t base = 0;
        for (PieceId id : order_) {
            const Piece& p = s.pieces.at(id);
            base_[id] = base;
            base += std::size_t(p.rows) * p.columns;
        }
        parent_.resize(base);
        std::iota(parent_.begin(), parent_.end(), std::size_t{0});
    }
    const std::vector<PieceId>& order() const { return order_; }
    std::size_t slot(PieceId id, int row, int column, int columns) const {
        return base_.at(id) + std::size_t(row) * columns + column;
    }
    std::size_t find(std::size_t a) {
        while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
        return a;
    }
    void unite(std::size_t a, std::size_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b); // the earlier slot represents
    }
    std::size_t size() const { return parent_.size(); }

  private:
    std::vector<PieceId> order_;
    std::map<PieceId, std::size_t> base_;
    std::vector<std::size_t> parent_;
};

/// Which source knots a child's row-0 column stands on (DESIGN.md gear rules).
struct TopLink {
    int shared = -1;          ///< index into the source row, when the column is a shared knot
    int left = -1, right = -1; ///< the two nearest shared knots of a new gear-up knot
    double fraction = 0;      ///< where the new knot lies between left and right
};

TopLink topLink(const ParentEdge& edge, int column, int sourceKnots) {
    const int v = edge.offset + column;
    const auto wrap = [&](int i) { return edge.ringClosed ? ((i % sourceKnots) + sourceKnots) % sourceKnots : i; };
    TopLink link;
    if (edge.gear.den > 1) {
        link.shared = wrap(v * edge.gear.den);
    } else if (v % edge.gear.num == 0) {
        link.shared = wrap(v / edge.gear.num);
    } else {
        link.left = wrap(v / edge.gear.num);
        link.right = wrap(v / edge.gear.num + 1);
        link.fraction = double(v % edge.gear.num) / edge.gear.num;
    }
    return link;
}

/// The knots (row - 1, column') a knot (row, column) hangs from, by the staggering rule.
int parentsAbove(const Piece& p, int row, int column, int out[2]) {
    const int c = p.columns;
    int candidates[2];
    if (row % 2 == 1) {
        candidates[0] = column;
        candidates[1] = column + 1;
    } else {
        candidates[0] = column - 1;
        candidates[1] = column;
    }
    int n = 0;
    for (int cand : candidates) {
        if (p.closed) cand = ((cand % c) + c) % c;
        if (cand >= 0 && cand < c) out[n++] = cand;
    }
    return n;
}

/// Eq. 1 and 2: a knot hung from two points by bars of length l sits at their midpoint minus h z.
Vec3 hangBetween(const Vec3& a, const Vec3& b, double fraction, double l, const Piece& p, int row, int column) {
    const double s = distance(a, b);
    if (!(l > 0.5 * s))
        throw UserError(toString(p.id) + ": bar length " + formatNumber(l) + " m at row " + std::to_string(row) +
                        ", column " + std::to_string(column) + " is not above half the spacing of the knots it hangs from (" +
                        formatNumber(s) + " m / 2 = " + formatNumber(0.5 * s) + " m)");
    const double h = std::sqrt(l * l - 0.25 * s * s);
    // The midpoint is formed symmetrically so that the result does not depend on which parent
    // comes first (a seam knot meets its parents from either piece).
    const Vec3 along = fraction == 0.5 ? (a + b) * 0.5 : a + (b - a) * fraction;
    return along - Vec3{0, 0, h};
}

/// A knot hung so far below its parents that its height is beyond what a double holds: named
/// here, before a NaN spacing shows up a row further down. Bar lengths are at most
/// kMaxBarLength, so this guards against rails placed at the edge of the doubles' range.
void checkPlaced(const Vec3& knot, double l, const Piece& p, int row, int column) {
    if (knot.isFinite()) return;
    throw UserError(toString(p.id) + ": bar length " + formatNumber(l) +
                    " m is too long: the knot at row " + std::to_string(row) + ", column " +
                    std::to_string(column) + " would hang at z = " + formatNumber(knot.z) +
                    " m, beyond the range of numbers");
}

class Builder {
  public:
    explicit Builder(const Sculpture& s) : s_(s), slots_(s) {}

    CompiledSculpture build() {
        uniteSharedKnots();
        assignIndices();
        buildBars();
        out_.system.origin = chooseOrigin(s_);
        placeKnots();
        finishMasses();
        out_.system.gravity = s_.gravity;
        return std::move(out_);
    }

  private:
    const Sculpture& s_;
    KnotSlots slots_;
    CompiledSculpture out_;
    std::vector<std::uint32_t> indexOfRoot_;
    /// A knot that another hangs from, with the bar's rest length; fraction >= 0 marks the left
    /// shared knot of a gear-up knot (which lies that far towards the right one).
    struct Upper {
        std::uint32_t knot;
        double length;
        double fraction;
    };
    /// The (at most two) knots a knot hangs from, in the order the bars were added.
    struct Uppers {
        std::array<Upper, 2> items;
        std::uint8_t count = 0;
        const Upper* begin() const { return items.data(); }
        const Upper* end() const { return items.data() + count; }
        std::size_t size() const { return count; }
        bool empty() const { return count == 0; }
        const Upper& operator[](std::size_t i) const { return items[i]; }
        void push_back(const Upper& u) { items[count++] = u; }
    };
    std::vector<Uppers> uppers_;
    std::vector<PieceId> massOwner_;

    std::size_t slot(const Piece& p, int row, int column) const { return slots_.slot(p.id, row, column, p.columns); }
    std::size_t slot(const KnotKey& k) const { return slot(s_.pieces.at(k.piece), k.row, k.column); }

    void uniteSharedKnots() {
        for (PieceId id : slots_.order()) {
            const Piece& p = s_.pieces.at(id);
            if (p.onRail()) continue;
            const auto source = sourceRow(s_, p.parentTop());
            for (int c = 0; c < p.columns; ++c) {
                const TopLink link = topLink(p.parentTop(), c, int(source.size()));
                if (link.shared >= 0) slots_.unite(slot(p, 0, c), slot(source[link.shared]));
            }
        }
        for (const Seam& seam : s_.seams) {
            const Piece& left = s_.pieces.at(seam.left);
            const Piece& right = s_.pieces.at(seam.right);
            for (int r = 0; r < std::min(left.rows, right.rows); ++r)
                slots_.unite(slot(left, r, left.columns - 1), slot(right, r, 0));
        }
    }

    void assignIndices() {
        indexOfRoot_.assign(slots_.size(), kUnassigned);
        MassSpringSystem& sys = out_.system;
        // Every (piece, row, column) with its knot, in visiting order; then grouped by knot.
        std::vector<std::pair<std::uint32_t, KnotRef>> visits;
        std::uint32_t n = 0;
        for (PieceId id : slots_.order()) {
            const Piece& p = s_.pieces.at(id);
            PieceKnots& pk = out_.pieces[id];
            pk.rows = p.rows;
            pk.columns = p.columns;
            pk.index.resize(std::size_t(p.rows) * p.columns);
            for (int r = 0; r < p.rows; ++r)
                for (int c = 0; c < p.columns; ++c) {
                    const std::size_t root = slots_.find(slot(p, r, c));
                    if (indexOfRoot_[root] == kUnassigned) {
                        indexOfRoot_[root] = n++;
                        massOwner_.push_back(id);
                    }
                    const std::uint32_t k = indexOfRoot_[root];
                    pk.index[std::size_t(r) * p.columns + c] = k;
                    visits.push_back({k, KnotRef{id, r, c}});
                }
        }
        sys.position.assign(n, Vec3{});
        sys.mass.assign(n, 0.0);
        sys.fixed.assign(n, 0);
        sys.hold.assign(n, RailHold{});
        sys.refStart.assign(std::size_t(n) + 1, 0);
        for (const auto& visit : visits) ++sys.refStart[visit.first + 1];
        for (std::size_t k = 0; k < n; ++k) sys.refStart[k + 1] += sys.refStart[k];
        sys.refs.resize(visits.size());
        std::vector<std::uint32_t> next(sys.refStart.begin(), sys.refStart.end() - 1);
        for (const auto& visit : visits) sys.refs[next[visit.first]++] = visit.second;
        uppers_.assign(n, {});
    }

    void fixOnRail(std::uint32_t k, const RailEdge& edge, int column) {
        MassSpringSystem& sys = out_.system;
        const Curve& rail = s_.rail(edge.rail).curve();
        const double t = rail.normalizedPosition(railPosition(edge, column)); // closed: in [0, 1)
        const Vec3 place = rail.pointAt(t) - sys.origin;
        if (sys.fixed[k]) { // a seam knot that two rows hold: at one place (checkSeamHolds)
            assert(sys.hold[k].rail == edge.rail &&
                   distance(sys.position[k], place) <= kSameHoldDistance);
            return;
        }
        sys.position[k] = place;
        sys.fixed[k] = 1;
        sys.hold[k] = RailHold{edge.rail, t};
    }

    void fixRailRows() {
        for (PieceId id : slots_.order()) {
            const Piece& p = s_.pieces.at(id);
            const PieceKnots& pk = out_.pieces.at(id);
            if (p.onRail())
                for (int c = 0; c < p.columns; ++c)
                    fixOnRail(pk.at(0, c), p.railTop(), c);
            if (p.bottom)
                for (int c = 0; c < p.columns; ++c)
                    fixOnRail(pk.at(p.rows - 1, c), *p.bottom, c);
        }
    }

    /// Places a knot from the knots it hangs from (Eq. 1 and 2), all of them already placed.
    void placeFromUppers(std::uint32_t k) {
        const auto& uppers = uppers_[k];
        auto& pos = out_.system.position;
        const Upper& u0 = uppers[0];
        const KnotRef& ref = out_.system.refs[out_.system.refStart[k]];
        const Piece& piece = s_.pieces.at(ref.piece);
        if (uppers.size() == 1) {
            pos[k] = pos[u0.knot] - Vec3{0, 0, u0.length};
            checkPlaced(pos[k], u0.length, piece, ref.row, ref.column);
            return;
        }
        const Upper& u1 = uppers[1];
        const double fraction = u0.fraction >= 0 ? u0.fraction : 0.5;
        const double l = 0.5 * (u0.length + u1.length);
        try {
            pos[k] = hangBetween(pos[u0.knot], pos[u1.knot], fraction, l, piece, ref.row,
                                 ref.column);
        } catch (const UserError& e) {
            throw UserError(e.what() + acrossPiecesText(u0.knot, u1.knot, piece.id));
        }
        checkPlaced(pos[k], l, piece, ref.row, ref.column);
    }

    /// When a knot hangs from the last rows of two pieces side by side (a child below split
    /// parts): "; it hangs from piece 1 row 39 (at z = 4.1 m) and piece 3 row 29 (at z = 6.3
    /// m): ..." - the cause when those rows end at different heights. Empty otherwise, also
    /// when one piece's last row holds both knots (a sibling below the same parent, whose
    /// row 0 shares them, is not a piece side by side).
    std::string acrossPiecesText(std::uint32_t a, std::uint32_t b, PieceId below) const {
        const MassSpringSystem& sys = out_.system;
        const auto inLastRows = [&](std::uint32_t k) { // k in pieces other than `below`
            std::vector<KnotRef> refs;
            for (std::uint32_t i = sys.refStart[k]; i < sys.refStart[k + 1]; ++i) {
                const KnotRef& r = sys.refs[i];
                if (r.piece != below && r.row == s_.pieces.at(r.piece).rows - 1)
                    refs.push_back(r);
            }
            return refs;
        };
        const std::vector<KnotRef> ra = inLastRows(a), rb = inLastRows(b);
        if (ra.empty() || rb.empty())
            return "";
        for (const KnotRef& x : ra)
            for (const KnotRef& y : rb)
                if (x.piece == y.piece)
                    return "";
        const auto knot = [&](const KnotRef& r, std::uint32_t k) {
            return toString(r.piece) + " row " + std::to_string(r.row) + " (at z = " +
                   formatNumber(sys.worldPosition(k).z) + " m)";
        };
        return "; it hangs from " + knot(ra.front(), a) + " and " + knot(rb.front(), b) +
               ": pieces side by side whose last rows end at different heights leave the row "
               "hanging from both too short to span the step";
    }

    /// Kahn's order over "hangs from": a knot is placed once every knot it hangs from is.
    void placeKnots() {
        fixRailRows();
        const std::size_t n = out_.system.knotCount();
        std::vector<std::uint32_t> waiting(n, 0);
        // lowers of knot j: lowers[lowerStart[j] .. lowerStart[j + 1]), in increasing k
        std::vector<std::uint32_t> lowerStart(n + 1, 0);
        for (std::uint32_t k = 0; k < n; ++k) {
            if (out_.system.fixed[k]) continue;
            waiting[k] = std::uint32_t(uppers_[k].size());
            for (const Upper& u : uppers_[k]) ++lowerStart[u.knot + 1];
        }
        for (std::size_t j = 0; j < n; ++j) lowerStart[j + 1] += lowerStart[j];
        std::vector<std::uint32_t> lowers(lowerStart[n]);
        std::vector<std::uint32_t> filled(lowerStart.begin(), lowerStart.end() - 1);
        for (std::uint32_t k = 0; k < n; ++k)
            if (!out_.system.fixed[k])
                for (const Upper& u : uppers_[k]) lowers[filled[u.knot]++] = k;
        std::vector<std::uint32_t> queue;
        for (std::uint32_t k = 0; k < n; ++k)
            if (out_.system.fixed[k] || waiting[k] == 0) queue.push_back(k);
        for (std::size_t i = 0; i < queue.size(); ++i) {
            const std::uint32_t k = queue[i];
            if (!out_.system.fixed[k] && !uppers_[k].empty()) placeFromUppers(k);
            for (std::uint32_t at = lowerStart[k]; at < lowerStart[k + 1]; ++at)
                if (--waiting[lowers[at]] == 0) queue.push_back(lowers[at]);
        }
    }

    /// A bar from knot `a` up to knot `b` (b is in the row above, or a shared knot of a gear).
    void addBar(BarPairs& seen, const Piece& p, std::uint32_t a, std::uint32_t b, double l,
                double fraction = -1) {
        if (a == b) return;
        auto& uppers = uppers_[a];
        if (uppers.size() < 2 && std::none_of(uppers.begin(), uppers.end(), [&](const Upper& u) { return u.knot == b; }))
            uppers.push_back({b, l, fraction});
        if (!seen.insert(a, b)) return; // a seam's shared column: the bar already exists
        MassSpringSystem& sys = out_.system;
        const double ks = p.material.stiffness / l;
        sys.barA.push_back(a);
        sys.barB.push_back(b);
        sys.restLength.push_back(l);
        sys.kTension.push_back(ks);
        sys.kCompression.push_back(p.material.compressionRatio * ks);
        sys.linearDensity.push_back(p.material.linearDensity);
        sys.barPiece.push_back(p.id);
    }

    void buildBars() {
        BarPairs seen(out_.system.knotCount());
        for (PieceId id : slots_.order()) {
            const Piece& p = s_.pieces.at(id);
            const PieceKnots& pk = out_.pieces.at(id);
            if (!p.onRail()) {
                const auto source = sourceRow(s_, p.parentTop());
                for (int c = 0; c < p.columns; ++c) {
                    const TopLink link = topLink(p.parentTop(), c, int(source.size()));
                    if (link.shared >= 0) continue;
                    const double l = p.barLength(0, c, 0, c);
                    for (int side : {link.left, link.right}) {
                        const KnotKey& k = source[side];
                        addBar(seen, p, pk.at(0, c), out_.knotOf(k.piece, k.row, k.column), l,
                               side == link.left ? link.fraction : -1);
                    }
                }
            }
            for (int r = 1; r < p.rows; ++r)
                for (int c = 0; c < p.columns; ++c) {
                    int up[2];
                    const int n = parentsAbove(p, r, c, up);
                    for (int i = 0; i < n; ++i)
                        addBar(seen, p, pk.at(r, c), pk.at(r - 1, up[i]), p.barLength(r, c, r - 1, up[i]));
                }
        }
    }

    void finishMasses() {
        MassSpringSystem& sys = out_.system;
        for (std::size_t k = 0; k < sys.knotCount(); ++k) sys.mass[k] = s_.pieces.at(massOwner_[k]).material.knotMass;
        for (std::size_t b = 0; b < sys.barCount(); ++b) {
            const double half = 0.5 * sys.linearDensity[b] * sys.restLength[b];
            sys.mass[sys.barA[b]] += half;
            sys.mass[sys.barB[b]] += half;
        }
        for (std::size_t k = 0; k < sys.knotCount(); ++k)
            if (!(sys.mass[k] > 0))
                throwWeightless(k);
    }

    /// A knot without bars (a piece of one row on a rail) and of knot_mass 0 would weigh
    /// nothing, which no relaxation, report or snapshot accepts: the edit is refused instead.
    [[noreturn]] void throwWeightless(std::size_t k) const {
        const KnotRef& ref = out_.system.refs[out_.system.refStart[k]];
        throw UserError(toString(ref.piece) + ": the knot at row " + std::to_string(ref.row) +
                        ", column " + std::to_string(ref.column) +
                        " would weigh nothing: knot_mass 0 kg and no rope of any weight (no bars, "
                        "or bars of linear_density 0); give the piece a knot_mass above 0");
    }
};

} // namespace

double railPosition(const RailEdge& edge, int column) {
    const double offset = double(edge.offset + column) * edge.step;
    return edge.reverse ? edge.at - offset : edge.at + offset;
}

std::uint32_t CompiledSculpture::knotOf(PieceId piece, int row, int column) const {
    auto it = pieces.find(piece);
    if (it == pieces.end()) throw UserError("there is no " + toString(piece) + " in the compiled sculpture");
    const PieceKnots& pk = it->second;
    if (row < 0 || row >= pk.rows || column < 0 || column >= pk.columns)
        throw UserError(toString(piece) + " has rows 0.." + std::to_string(pk.rows - 1) + " and columns 0.." +
                        std::to_string(pk.columns - 1) + "; got row " + std::to_string(row) + ", column " +
                        std::to_string(column));
    return pk.at(row, column);
}

CompiledSculpture compileSculpture(const Sculpture& s) { return Builder(s).build(); }

Vec3 chooseOrigin(const Sculpture& s) {
    std::set<RailId> holding; // rails that hold a piece: a drawing's other lines do not count
    for (const auto& [id, piece] : s.pieces) {
        if (piece.onRail()) holding.insert(piece.railTop().rail);
        if (piece.bottom) holding.insert(piece.bottom->rail);
    }
    if (holding.empty()) // no net yet: the rails alone, as the studio draws them
        for (const auto& [id, rail] : s.rails) holding.insert(id);
    Vec3 low{HUGE_VAL, HUGE_VAL, HUGE_VAL}, high = -low;
    for (RailId id : holding)
        for (const Vec3& p : s.rail(id).curve().spec().points) {
            low = {std::min(low.x, p.x), std::min(low.y, p.y), std::min(low.z, p.z)};
            high = {std::max(high.x, p.x), std::max(high.y, p.y), std::max(high.z, p.z)};
        }
    const auto axis = [](double lo, double hi) {
        const double centre = 0.5 * lo + 0.5 * hi;
        const bool far = std::isfinite(centre) && std::abs(centre) > kOriginFreeRadius;
        return far ? std::round(centre) : 0.0;
    };
    return {axis(low.x, high.x), axis(low.y, high.y), axis(low.z, high.z)};
}

namespace {

/// A piece tied to a rail below whose rows grew: its free rows from the old rail row down are
/// placed row by row between the two knots each hangs from, one even step nearer the rail (the
/// last kept row's distance to the rail, column by column, in equal parts). Moved with the old
/// rail row, as rows added below a hanging piece are, they would start tens of per cent off
/// their length, which makes the next relaxation a cold one.
void spreadRowsToRail(const MassSpringSystem& previousSystem, const PieceKnots& old,
                      const PieceKnots& now, MassSpringSystem& sys) {
    const int kept = old.rows - 2, rail = now.rows - 1;
    if (now.rows <= old.rows || kept < 0 || old.columns != now.columns) return;
    for (int c = 0; c < now.columns; ++c)
        if (!previousSystem.fixed[old.at(old.rows - 1, c)] || !sys.fixed[now.at(rail, c)]) return;
    // The knots each knot of the spread rows hangs from (its bars to the row above).
    std::unordered_map<std::uint32_t, int> rowOf;
    for (int r = kept; r < rail; ++r)
        for (int c = 0; c < now.columns; ++c) rowOf.emplace(now.at(r, c), r);
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> above;
    for (std::size_t b = 0; b < sys.barCount(); ++b) {
        const auto a = rowOf.find(sys.barA[b]), e = rowOf.find(sys.barB[b]);
        if (a == rowOf.end() || e == rowOf.end() || std::abs(a->second - e->second) != 1) continue;
        if (a->second < e->second) above[sys.barB[b]].push_back(sys.barA[b]);
        else above[sys.barA[b]].push_back(sys.barB[b]);
    }
    for (int r = kept + 1; r < rail; ++r)
        for (int c = 0; c < now.columns; ++c) {
            const std::uint32_t k = now.at(r, c);
            const auto up = above.find(k);
            if (sys.fixed[k] || up == above.end()) continue;
            Vec3 mean;
            for (std::uint32_t u : up->second) mean += sys.position[u];
            mean = mean * (1.0 / double(up->second.size()));
            const Vec3 step = (sys.position[now.at(rail, c)] - sys.position[now.at(kept, c)]) *
                              (1.0 / double(rail - kept));
            sys.position[k] = mean + step;
        }
}

} // namespace

KnotRenaming splitRenaming(PieceId piece, PieceId right, int column, int columns) {
    return [=](const KnotRef& ref) -> std::optional<KnotRef> {
        if (ref.piece == piece)
            return ref;
        if (ref.piece == right)
            return KnotRef{piece, ref.row, (ref.column + column) % columns};
        return std::nullopt;
    };
}

namespace {

/// The position `previous` had for a knot its edit renamed, moved to next's origin.
std::optional<Vec3> renamedPosition(const CompiledSculpture& previous, const KnotRef& ref,
                                    const KnotRenaming& renamed, const Vec3& origin) {
    if (!renamed)
        return std::nullopt;
    const std::optional<KnotRef> before = renamed(ref);
    if (!before)
        return std::nullopt;
    const auto old = previous.pieces.find(before->piece);
    if (old == previous.pieces.end() || before->row >= old->second.rows ||
        before->column >= old->second.columns)
        return std::nullopt;
    return inOrigin(previous.system, old->second.at(before->row, before->column), origin);
}

} // namespace

std::size_t carryPositions(const CompiledSculpture& previous, CompiledSculpture& next,
                           const KnotRenaming& renamed) {
    MassSpringSystem& sys = next.system;
    const std::vector<Vec3> initial = sys.position;
    std::size_t carried = 0;
    for (std::size_t k = 0; k < sys.knotCount(); ++k) {
        if (sys.fixed[k]) continue;
        const KnotRef& ref = sys.refs[sys.refStart[k]];
        if (const auto place = renamedPosition(previous, ref, renamed, sys.origin)) {
            sys.position[k] = *place;
            ++carried;
            continue;
        }
        auto old = previous.pieces.find(ref.piece);
        auto now = next.pieces.find(ref.piece);
        if (old == previous.pieces.end() || old->second.columns != now->second.columns) continue;
        // A knot that existed keeps its relaxed position; a knot of a new row below moves with
        // the last old row's knot of its column, so that added rows start near the hung shape.
        const int row = std::min(ref.row, old->second.rows - 1);
        const Vec3 relaxed = inOrigin(previous.system, old->second.at(row, ref.column), sys.origin);
        const Vec3 start = initial[now->second.at(row, ref.column)];
        sys.position[k] = row == ref.row ? relaxed : initial[k] + (relaxed - start);
        ++carried;
    }
    for (const auto& [id, now] : next.pieces)
        if (const auto old = previous.pieces.find(id); old != previous.pieces.end())
            spreadRowsToRail(previous.system, old->second, now, sys);
    return carried;
}

} // namespace netsculpt
