#include "physics/WarmStart.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

namespace netsculpt {

namespace {

/// A knot's first (piece, row, column) as one number; false when it does not fit 24/20/20 bits.
bool knotKey(const MassSpringSystem& system, std::size_t knot, std::uint64_t& key) {
    if (system.refStart.size() != system.knotCount() + 1 ||
        system.refStart[knot] == system.refStart[knot + 1])
        return false;
    const KnotRef& ref = system.refs[system.refStart[knot]];
    if (ref.piece.value >= (1u << 24) || ref.row < 0 || ref.row >= (1 << 20) || ref.column < 0 ||
        ref.column >= (1 << 20))
        return false;
    key = std::uint64_t{ref.piece.value} << 40 | std::uint64_t(ref.row) << 20 |
          std::uint64_t(ref.column);
    return true;
}

/// Eq. 3's tension of bar b of `law` (its rest length and stiffness) at length l, N.
double tensionOf(const MassSpringSystem& law, std::size_t b, double l) {
    const double extension = l - law.restLength[b];
    return (extension > 0 ? law.kTension[b] : law.kCompression[b]) * extension;
}

std::uint64_t pairKey(std::uint32_t a, std::uint32_t b) {
    return std::uint64_t{std::min(a, b)} << 32 | std::max(a, b);
}

/// Every knot of `system` by its knotKey (knots without one left out).
std::unordered_map<std::uint64_t, std::uint32_t> knotsByKey(const MassSpringSystem& system) {
    std::unordered_map<std::uint64_t, std::uint32_t> knots;
    knots.reserve(system.knotCount());
    for (std::size_t j = 0; j < system.knotCount(); ++j) {
        std::uint64_t key = 0;
        if (knotKey(system, j, key))
            knots.emplace(key, static_cast<std::uint32_t>(j));
    }
    return knots;
}

/// The same knots, in the same order: knot j of one is knot j of the other.
bool sameKnots(const MassSpringSystem& previous, const MassSpringSystem& next) {
    return previous.refStart == next.refStart && previous.refs == next.refs;
}

/// m: a held knot this close to where it was is held at the same place.
constexpr double kSamePlace = 1e-9;

/// Per piece, one more than the largest column (or row) of its knots.
std::unordered_map<std::uint32_t, int> extentOf(const MassSpringSystem& system, bool columns) {
    std::unordered_map<std::uint32_t, int> extent;
    for (const KnotRef& ref : system.refs) {
        int& e = extent[ref.piece.value];
        e = std::max(e, (columns ? ref.column : ref.row) + 1);
    }
    return extent;
}

/// Pieces tied to a rail below: their last row held.
std::unordered_set<std::uint32_t> tiedPieces(const MassSpringSystem& system) {
    const auto rows = extentOf(system, false);
    std::unordered_set<std::uint32_t> tied;
    for (std::size_t j = 0; j < system.knotCount(); ++j)
        for (std::uint32_t i = system.refStart[j]; system.fixed[j] && i < system.refStart[j + 1];
             ++i)
            if (const KnotRef& ref = system.refs[i];
                ref.row > 0 && ref.row + 1 == rows.at(ref.piece.value))
                tied.insert(ref.piece.value);
    return tied;
}

} // namespace

bool heldAtTheSamePlaces(const MassSpringSystem& previous, const MassSpringSystem& next) {
    if (sameKnots(previous, next)) { // knot j is knot j: no lookup (a drag that keeps the knots)
        for (std::size_t j = 0; j < next.knotCount(); ++j)
            if (std::uint64_t key = 0;
                next.fixed[j] && previous.fixed[j] && knotKey(next, j, key) &&
                distance(previous.worldPosition(j), next.worldPosition(j)) > kSamePlace)
                return false;
        return true;
    }
    const std::unordered_map<std::uint64_t, std::uint32_t> oldKnot = knotsByKey(previous);
    for (std::size_t j = 0; j < next.knotCount(); ++j) {
        std::uint64_t key = 0;
        if (!next.fixed[j] || !knotKey(next, j, key))
            continue;
        const auto at = oldKnot.find(key);
        if (at != oldKnot.end() && previous.fixed[at->second] &&
            distance(previous.worldPosition(at->second), next.worldPosition(j)) > kSamePlace)
            return false;
    }
    return true;
}

bool sameKnotsWhereMatched(const MassSpringSystem& previous, const MassSpringSystem& next) {
    if (!heldAtTheSamePlaces(previous, next))
        return false;
    if (sameKnots(previous, next))
        return true;
    const auto oldColumns = extentOf(previous, true), newColumns = extentOf(next, true);
    const auto oldRows = extentOf(previous, false), newRows = extentOf(next, false);
    const auto tied = tiedPieces(next);
    for (const auto& [piece, columns] : newColumns) {
        const auto old = oldColumns.find(piece);
        if (old == oldColumns.end())
            continue;
        const bool rowsChanged = oldRows.at(piece) != newRows.at(piece);
        if (old->second != columns || (tied.contains(piece) && rowsChanged))
            return false;
    }
    return true;
}

std::size_t carryMatchedPositions(const MassSpringSystem& previous, MassSpringSystem& next) {
    if (sameKnots(previous, next)) { // no lookup: knot j is knot j
        std::size_t carried = 0;
        for (std::size_t j = 0; j < next.knotCount(); ++j)
            if (std::uint64_t key = 0; !next.fixed[j] && knotKey(next, j, key)) {
                next.position[j] = inOrigin(previous, j, next.origin);
                ++carried;
            }
        return carried;
    }
    const std::unordered_map<std::uint64_t, std::uint32_t> oldKnot = knotsByKey(previous);
    std::size_t carried = 0;
    for (std::size_t j = 0; j < next.knotCount(); ++j) {
        std::uint64_t key = 0;
        if (next.fixed[j] || !knotKey(next, j, key))
            continue;
        const auto at = oldKnot.find(key);
        if (at == oldKnot.end())
            continue;
        next.position[j] = inOrigin(previous, at->second, next.origin);
        ++carried;
    }
    return carried;
}

std::size_t continueNewRows(const MassSpringSystem& previous, MassSpringSystem& next) {
    // The same knots (a drag that keeps the topology): none is new.
    if (sameKnots(previous, next))
        return 0;
    // Columns per piece in both systems: only a piece whose column count is the same has rows to
    // go on from.
    const auto oldColumns = extentOf(previous, true), newColumns = extentOf(next, true);
    // Pieces tied to a rail below (their last row held) are left as they are: the document's warm
    // start spreads their rows between the rows they kept and the rail (Compiler.h).
    const std::unordered_set<std::uint32_t> tied = tiedPieces(next);
    std::unordered_map<std::uint64_t, std::uint32_t> oldKnot, newKnot;
    for (std::size_t j = 0; j < previous.knotCount(); ++j) {
        std::uint64_t key = 0;
        if (knotKey(previous, j, key))
            oldKnot.emplace(key, static_cast<std::uint32_t>(j));
    }
    std::vector<std::pair<int, std::uint32_t>> added; // (row, knot) of knots new in `next`
    for (std::size_t j = 0; j < next.knotCount(); ++j) {
        std::uint64_t key = 0;
        if (!knotKey(next, j, key))
            continue;
        newKnot.emplace(key, static_cast<std::uint32_t>(j));
        const KnotRef& ref = next.refs[next.refStart[j]];
        const auto old = oldColumns.find(ref.piece.value);
        if (!next.fixed[j] && !oldKnot.contains(key) && ref.row >= 3 && old != oldColumns.end() &&
            old->second == newColumns.at(ref.piece.value) && !tied.contains(ref.piece.value))
            added.emplace_back(ref.row, static_cast<std::uint32_t>(j));
    }
    std::sort(added.begin(),
              added.end()); // rows in order: a new row goes on from the new rows above it
    std::size_t placed = 0;
    for (const auto& [row, j] : added) {
        const KnotRef& ref = next.refs[next.refStart[j]];
        std::uint32_t above[3];
        bool found = true;
        for (int i = 0; i < 3 && found; ++i) {
            const std::uint64_t key = std::uint64_t{ref.piece.value} << 40 |
                                      std::uint64_t(row - 1 - i) << 20 | std::uint64_t(ref.column);
            const auto at = newKnot.find(key);
            found = at != newKnot.end();
            if (found)
                above[i] = at->second;
        }
        if (!found)
            continue;
        next.position[j] =
            next.position[above[0]] + next.position[above[1]] - next.position[above[2]];
        ++placed;
    }
    return placed;
}

std::size_t continueRowDrag(const MassSpringSystem& before, const MassSpringSystem& previous,
                            const MassSpringSystem& next, std::vector<Vec3>& positions) {
    if (before.origin != previous.origin || previous.origin != next.origin ||
        positions.size() != next.knotCount())
        return 0;
    const auto beforeKnots = knotsByKey(before), previousKnots = knotsByKey(previous);
    // next's knots in (piece, row, column) order, so that a knot's column above has moved first
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order;
    order.reserve(next.knotCount());
    for (std::size_t j = 0; j < next.knotCount(); ++j)
        if (std::uint64_t key = 0; knotKey(next, j, key))
            order.emplace_back(key, static_cast<std::uint32_t>(j));
    std::sort(order.begin(), order.end());
    constexpr std::uint64_t kRow = std::uint64_t{1} << 20;
    std::unordered_map<std::uint64_t, Vec3> motion;
    motion.reserve(order.size());
    std::size_t count = 0;
    for (const auto& [key, j] : order) {
        const auto p = previousKnots.find(key);
        const auto b = beforeKnots.find(key);
        Vec3 moved{0, 0, 0};
        if (p != previousKnots.end() && b != beforeKnots.end())
            moved = previous.position[p->second] - before.position[b->second];
        else if (const auto up = motion.find(key - kRow);
                 (key >> 20 & (kRow - 1)) > 0 && up != motion.end())
            moved = up->second; // a row new in `previous` or in `next`: as the knot above
        motion.emplace(key, moved);
        if (next.fixed[j])
            continue;
        positions[j] =
            (p != previousKnots.end() ? previous.position[p->second] : positions[j]) + moved;
        ++count;
    }
    return count;
}

std::vector<double> startTensions(const MassSpringSystem& previous, const MassSpringSystem& next) {
    const std::size_t bars = next.barCount();
    auto lengthOf = [&](std::size_t b) {
        return distance(next.position[next.barA[b]], next.position[next.barB[b]]);
    };
    std::vector<double> hint(bars, 0.0);
    if (previous.barA == next.barA && previous.barB == next.barB &&
        previous.knotCount() == next.knotCount()) {
        for (std::size_t b = 0; b < bars; ++b)
            hint[b] = tensionOf(previous, b, lengthOf(b)); // same topology
        return hint;
    }
    // Another topology (rows or columns changed): bars are matched by the knots they join.
    const std::unordered_map<std::uint64_t, std::uint32_t> oldKnot = knotsByKey(previous);
    std::unordered_map<std::uint64_t, std::uint32_t> oldBar;
    oldBar.reserve(previous.barCount());
    for (std::size_t b = 0; b < previous.barCount(); ++b)
        oldBar.emplace(pairKey(previous.barA[b], previous.barB[b]), static_cast<std::uint32_t>(b));
    auto oldOf = [&](std::uint32_t knot, std::uint32_t& old) {
        std::uint64_t key = 0;
        if (!knotKey(next, knot, key))
            return false;
        const auto at = oldKnot.find(key);
        if (at == oldKnot.end())
            return false;
        old = at->second;
        return true;
    };
    std::vector<std::uint8_t> matched(bars, 0);
    std::vector<double> knotSum(next.knotCount(), 0.0);
    std::vector<std::uint32_t> knotCount(next.knotCount(), 0);
    std::size_t matchedCount = 0;
    for (std::size_t b = 0; b < bars; ++b) {
        std::uint32_t a = 0, e = 0;
        if (!oldOf(next.barA[b], a) || !oldOf(next.barB[b], e))
            continue;
        const auto at = oldBar.find(pairKey(a, e));
        if (at == oldBar.end())
            continue;
        hint[b] = tensionOf(previous, at->second, lengthOf(b));
        matched[b] = 1;
        ++matchedCount;
        if (hint[b] > 0)
            for (std::uint32_t knot : {next.barA[b], next.barB[b]}) {
                knotSum[knot] += hint[b];
                ++knotCount[knot];
            }
    }
    if (2 * matchedCount < bars)
        return {};
    // New bars, in passes outward from the old ones (several rows added: the second new row's
    // bars take the first's); a bar that no pass reaches keeps its own elastic tension.
    for (bool grew = true; grew;) {
        grew = false;
        std::vector<std::pair<std::size_t, double>> reached;
        for (std::size_t b = 0; b < bars; ++b) {
            if (matched[b])
                continue;
            double sum = 0;
            std::uint32_t count = 0;
            for (std::uint32_t knot : {next.barA[b], next.barB[b]}) {
                sum += knotSum[knot];
                count += knotCount[knot];
            }
            if (count > 0)
                reached.emplace_back(b, sum / count);
        }
        for (const auto& [b, t] : reached) {
            hint[b] = t;
            matched[b] = 1;
            grew = true;
            for (std::uint32_t knot : {next.barA[b], next.barB[b]}) {
                knotSum[knot] += t;
                ++knotCount[knot];
            }
        }
    }
    for (std::size_t b = 0; b < bars; ++b)
        if (!matched[b])
            hint[b] = tensionOf(next, b, lengthOf(b));
    return hint;
}

} // namespace netsculpt
