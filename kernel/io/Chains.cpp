#include "io/Chains.h"

#include "io/IoText.h"
#include "model/Error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>

namespace netsculpt::io {

namespace {

std::string pointText(const Vec3& p) {
    return concat({"(", numberText(p.x), ", ", numberText(p.y), ", ", numberText(p.z), ")"});
}

bool shorterThan(const ChainPart& part, double tolerance) {
    return std::all_of(part.points.begin(), part.points.end(), [&](const Vec3& p) {
        return distance(p, part.points.front()) <= tolerance;
    });
}

/// At most this many ends at different points share a cell of the end grid (a cube as wide as
/// the join tolerance): the ends around one end are compared with it, so that crowding many
/// tiny pieces into one spot took time growing with the square of their number.
constexpr std::size_t kMaxEndsPerCell = 64;

/// The parts' ends hashed into a grid of cubes `tolerance` wide, so that ends within the
/// tolerance of one another lie in the same or in neighbouring cells: finding an end's partners
/// looks at 27 cells, not at every end. Ends at the same point are entered once: the first of
/// them stands for the others (same()).
class EndGrid {
  public:
    EndGrid(const std::vector<ChainPart>& parts, double tolerance) : parts_(parts) {
        lo_ = parts[0].points[0];
        for (const auto& part : parts)
            for (const Vec3* p : {&part.points.front(), &part.points.back()})
                lo_ = {std::min(lo_.x, p->x), std::min(lo_.y, p->y), std::min(lo_.z, p->z)};
        // Cells are indexed from the lowest end: at most 1e6 cells along each axis, as the
        // tolerance is 1e-6 of the extent (0 when every end is the same point: one cell).
        cell_ = tolerance > 0 ? tolerance : 1.0;
        std::map<std::array<double, 3>, int> firstAt;
        for (int node = 0; node < int(2 * parts.size()); ++node) {
            const Vec3& p = end(node);
            const auto [first, fresh] = firstAt.emplace(std::array{p.x, p.y, p.z}, node);
            same_.push_back(first->second);
            if (!fresh)
                continue;
            std::vector<int>& cell = cells_[keyOf(cellOf(p))];
            cell.push_back(node);
            if (cell.size() > kMaxEndsPerCell && !crowded_)
                crowded_ = &cell;
        }
    }

    const Vec3& end(int node) const {
        const auto& pts = parts_[std::size_t(node / 2)].points;
        return node % 2 == 0 ? pts.front() : pts.back();
    }

    /// The first end at the point of `node`'s: the one entered into the grid.
    int same(int node) const { return same_[std::size_t(node)]; }

    /// The ends entered into a cell holding more than kMaxEndsPerCell, if there is one.
    const std::vector<int>* crowded() const { return crowded_; }

    /// Calls `visit(other)` for every other end entered in the cells around `node`'s.
    template <class Visit> void around(int node, Visit&& visit) const {
        const auto [cx, cy, cz] = cellOf(end(node));
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy)
                for (long long dz = -1; dz <= 1; ++dz) {
                    const auto found = cells_.find(keyOf({cx + dx, cy + dy, cz + dz}));
                    if (found == cells_.end())
                        continue;
                    for (int other : found->second)
                        if (other != node)
                            visit(other);
                }
    }

  private:
    using Cell = std::array<long long, 3>;
    const std::vector<ChainPart>& parts_;
    Vec3 lo_;
    double cell_ = 1;
    std::unordered_map<std::uint64_t, std::vector<int>> cells_;
    std::vector<int> same_;
    const std::vector<int>* crowded_ = nullptr; ///< values of an unordered_map stay in place

    Cell cellOf(const Vec3& p) const {
        return {(long long)std::floor((p.x - lo_.x) / cell_),
                (long long)std::floor((p.y - lo_.y) / cell_),
                (long long)std::floor((p.z - lo_.z) / cell_)};
    }
    /// Cell indices lie in [-1, 1e6 + 1]: 21 bits each.
    static std::uint64_t keyOf(const Cell& c) {
        return (std::uint64_t(c[0] + 1) << 42) | (std::uint64_t(c[1] + 1) << 21) |
               std::uint64_t(c[2] + 1);
    }
};

/// UserError when the grid has a crowded cell: more ends at different points than
/// kMaxEndsPerCell within one tolerance-wide cube, naming a few of their parts.
void refuseCrowding(const std::string& file, const std::vector<ChainPart>& parts,
                    const EndGrid& grid, double tolerance) {
    const std::vector<int>* crowded = grid.crowded();
    if (!crowded)
        return;
    std::string names;
    for (std::size_t k = 0; k < 3; ++k)
        names += parts[std::size_t((*crowded)[k] / 2)].where + ", ";
    throw UserError(file + ": more than " + std::to_string(kMaxEndsPerCell) +
                    " ends of pieces at different points lie within " + numberText(tolerance) +
                    " of one another near " + pointText(grid.end(crowded->front())) + " (" + names +
                    "...); netsculpt joins at most " + std::to_string(kMaxEndsPerCell) +
                    " there: remove the pieces shorter than " + numberText(tolerance) +
                    " (1e-6 of the drawing's extent) in the drawing program");
}

/// Ends are nodes 2 * part + (0 = start, 1 = end). Ends within `tolerance` of one another meet,
/// and so do the two ends of a dropped part (one shorter than the tolerance): the ends that meet
/// it on either side are joined directly, however far apart they are. Returns every end's
/// partner: the one other end of a kept part it meets (the other end of the same part for a
/// closed one), -1 for none. UserError when three or more ends of kept parts meet.
std::vector<int> partnersOf(const std::string& file, const std::vector<ChainPart>& parts,
                            const std::vector<char>& dropped, double tolerance,
                            std::string_view advice) {
    const int nodes = int(2 * parts.size());
    std::vector<int> partner(std::size_t(nodes), -1);
    if (parts.empty())
        return partner;
    // Union-find over the ends; kept[root] counts the ends of kept parts that meet there.
    std::vector<int> root(partner.size()), kept(partner.size());
    for (int a = 0; a < nodes; ++a) {
        root[std::size_t(a)] = a;
        kept[std::size_t(a)] = dropped[std::size_t(a / 2)] ? 0 : 1;
    }
    const auto find = [&](int a) {
        while (root[std::size_t(a)] != a)
            a = root[std::size_t(a)] = root[std::size_t(root[std::size_t(a)])];
        return a;
    };
    const auto unite = [&](int a, int b) {
        a = find(a);
        b = find(b);
        if (a == b)
            return;
        root[std::size_t(b)] = a;
        kept[std::size_t(a)] += kept[std::size_t(b)];
    };
    for (std::size_t part = 0; part < parts.size(); ++part)
        if (dropped[part])
            unite(int(2 * part), int(2 * part + 1));
    const EndGrid grid(parts, tolerance);
    refuseCrowding(file, parts, grid, tolerance);
    for (int a = 0; a < nodes; ++a) {
        if (grid.same(a) != a)
            unite(grid.same(a), a);
        else
            grid.around(a, [&](int b) {
                if (distance(grid.end(a), grid.end(b)) <= tolerance)
                    unite(a, b);
            });
        const int at = find(a);
        if (kept[std::size_t(at)] < 3)
            continue;
        std::vector<int> meeting; // in file order
        for (int b = 0; b < nodes; ++b)
            if (!dropped[std::size_t(b / 2)] && find(b) == at &&
                (meeting.empty() || meeting.back() != b / 2))
                meeting.push_back(b / 2);
        std::string names;
        for (int part : meeting)
            names += (names.empty() ? "" : ", ") + parts[std::size_t(part)].where;
        throw UserError(file + ": " + std::to_string(kept[std::size_t(at)]) + " ends meet at " +
                        pointText(grid.end(a)) + " (" + names +
                        "); a rail cannot branch: " + std::string(advice));
    }
    std::vector<int> firstEnd(std::size_t(nodes), -1); // by root: the first kept end there
    for (int a = 0; a < nodes; ++a) {
        if (dropped[std::size_t(a / 2)])
            continue;
        int& first = firstEnd[std::size_t(find(a))];
        if (first < 0) {
            first = a;
        } else {
            partner[std::size_t(a)] = first;
            partner[std::size_t(first)] = a;
        }
    }
    return partner;
}

} // namespace

double joinTolerance(const std::vector<ChainPart>& parts) {
    std::vector<Vec3> points;
    for (const auto& part : parts)
        points.insert(points.end(), part.points.begin(), part.points.end());
    return 1e-6 * extent(points);
}

std::vector<SourcedCurve> joinChains(const std::string& file, std::vector<ChainPart> parts,
                                     std::string_view advice) {
    const double tolerance = joinTolerance(parts);
    const int n = int(parts.size());
    // Short parts are dropped after their ends are matched, so that a chain runs on across them.
    std::vector<char> dropped(std::size_t(n), 0);
    if (std::any_of(parts.begin(), parts.end(),
                    [&](const ChainPart& p) { return !shorterThan(p, tolerance); }))
        for (int i = 0; i < n; ++i)
            dropped[std::size_t(i)] = shorterThan(parts[std::size_t(i)], tolerance);
    const auto partners = partnersOf(file, parts, dropped, tolerance, advice);
    const auto partner = [&](int node) { return partners[std::size_t(node)]; };

    std::vector<char> used = dropped;
    std::vector<SourcedCurve> chains;
    for (int first = 0; first < n; ++first) {
        if (used[std::size_t(first)])
            continue;
        used[std::size_t(first)] = 1;
        // (part, forward) in chain order: walk on from the first part's end, then back from its
        // start.
        std::vector<std::pair<int, bool>> forward{{first, true}}, backward;
        bool closed = false;
        for (int node = 2 * first + 1;;) {
            const int next = partner(node);
            if (next < 0)
                break;
            if (next / 2 == first) {
                closed = true;
                break;
            }
            used[std::size_t(next / 2)] = 1;
            forward.push_back({next / 2, next % 2 == 0});
            node = next ^ 1;
        }
        if (!closed)
            for (int node = 2 * first;;) {
                const int next = partner(node);
                if (next < 0 || next / 2 == first)
                    break;
                used[std::size_t(next / 2)] = 1;
                backward.push_back({next / 2, next % 2 == 1});
                node = next ^ 1;
            }
        std::vector<std::pair<int, bool>> order(backward.rbegin(), backward.rend());
        order.insert(order.end(), forward.begin(), forward.end());
        std::vector<Vec3> points;
        for (const auto& [part, along] : order) {
            std::vector<Vec3> pts = parts[std::size_t(part)].points;
            if (!along)
                std::reverse(pts.begin(), pts.end());
            points.insert(points.end(), pts.begin() + (points.empty() ? 0 : 1), pts.end());
        }
        if (closed && points.size() > 2)
            points.pop_back();
        const ChainPart& head = parts[std::size_t(first)];
        CurveSpec spec;
        spec.points = std::move(points);
        spec.closed = closed;
        const std::string where = order.size() == 1 ? head.where
                                                    : "the chain of " +
                                                          std::to_string(order.size()) +
                                                          " parts starting at " + head.where;
        chains.push_back({{head.name, std::move(spec)}, where, head.order});
    }
    return chains;
}

} // namespace netsculpt::io
