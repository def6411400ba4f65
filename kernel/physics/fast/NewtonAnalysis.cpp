#include "physics/fast/NewtonAnalysis.h"

#include <algorithm>

namespace netsculpt {

void NewtonAnalysis::analyse(const MassSpringSystem& system) {
    factorStiffness = 0;
    reusedIterations = 0;
    fixed = system.fixed;
    barA = system.barA;
    barB = system.barB;
    const std::size_t knots = system.knotCount(), bars = system.barCount();
    freeKnots.clear();
    pairs.clear();
    freeIndex.assign(knots, -1);
    for (std::size_t j = 0; j < knots; ++j)
        if (!fixed[j]) {
            freeIndex[j] = static_cast<std::int64_t>(freeKnots.size());
            freeKnots.push_back(static_cast<std::uint32_t>(j));
        }
    // One block per pair of free knots joined by a bar (two bars between the same knots
    // share it), numbered in the order of their first bar. The pairs found so far are listed
    // by their lower free index (flat: a slot per bar, grouped by that index).
    barPair.assign(bars, -1);
    std::vector<std::uint32_t> slotStart(freeKnots.size() + 1, 0);
    for (std::size_t b = 0; b < bars; ++b) {
        const std::int64_t i = freeIndex[barA[b]], j = freeIndex[barB[b]];
        if (i >= 0 && j >= 0)
            ++slotStart[static_cast<std::size_t>(std::min(i, j)) + 1];
    }
    for (std::size_t f = 0; f < freeKnots.size(); ++f)
        slotStart[f + 1] += slotStart[f];
    std::vector<std::uint32_t> slotEnd(slotStart.begin(), slotStart.end() - 1);
    std::vector<std::uint32_t> slotPair(slotStart.back());
    pairs.reserve(slotStart.back());
    for (std::size_t b = 0; b < bars; ++b) {
        const std::int64_t i = freeIndex[barA[b]], j = freeIndex[barB[b]];
        if (i < 0 || j < 0)
            continue;
        const auto low = static_cast<std::size_t>(std::min(i, j));
        const auto high = static_cast<std::uint32_t>(std::max(i, j));
        std::uint32_t k = slotStart[low];
        while (k < slotEnd[low] && std::max(pairs[slotPair[k]][0], pairs[slotPair[k]][1]) != high)
            ++k;
        if (k == slotEnd[low]) {
            slotPair[slotEnd[low]++] = static_cast<std::uint32_t>(pairs.size());
            pairs.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
        }
        barPair[b] = slotPair[k];
    }
    // The free knots' positions (the start's) guide the ordering.
    std::vector<std::array<double, 3>> coordinates(freeKnots.size());
    for (std::size_t f = 0; f < freeKnots.size(); ++f) {
        const Vec3& p = system.position[freeKnots[f]];
        coordinates[f] = {p.x, p.y, p.z};
    }
    cholesky.analyse(freeKnots.size(), pairs, coordinates);
    barBlock.allocate(9 * bars);
    values.allocate(9 * (freeKnots.size() + pairs.size()));
}

} // namespace netsculpt
