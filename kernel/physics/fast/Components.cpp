#include "physics/fast/Components.h"

#include <algorithm>
#include <numeric>

namespace netsculpt {

namespace {

bool consistent(const MassSpringSystem& s) {
    const std::size_t knots = s.knotCount(), bars = s.barCount();
    if (s.fixed.size() != knots || s.mass.size() != knots || s.barB.size() != bars ||
        s.restLength.size() != bars || s.kTension.size() != bars || s.kCompression.size() != bars)
        return false;
    for (std::size_t b = 0; b < bars; ++b)
        if (s.barA[b] >= knots || s.barB[b] >= knots)
            return false;
    return true;
}

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t j) {
    while (parent[j] != j) {
        parent[j] = parent[parent[j]]; // path halving
        j = parent[j];
    }
    return j;
}

} // namespace

std::vector<std::vector<std::uint32_t>> freeComponents(const MassSpringSystem& system) {
    if (!consistent(system))
        return {};
    const std::size_t knots = system.knotCount();
    std::vector<std::uint32_t> parent(knots);
    std::iota(parent.begin(), parent.end(), 0u);
    for (std::size_t b = 0; b < system.barCount(); ++b) {
        const std::uint32_t a = system.barA[b], e = system.barB[b];
        if (system.fixed[a] || system.fixed[e])
            continue;
        const std::uint32_t ra = findRoot(parent, a), re = findRoot(parent, e);
        if (ra != re)
            parent[std::max(ra, re)] = std::min(ra, re); // a root is its component's first knot
    }
    std::vector<std::vector<std::uint32_t>> components;
    std::vector<std::uint32_t> componentOf(knots, 0);
    for (std::uint32_t j = 0; j < knots; ++j) {
        if (system.fixed[j])
            continue;
        const std::uint32_t root = findRoot(parent, j);
        if (root == j) {
            componentOf[j] = static_cast<std::uint32_t>(components.size());
            components.emplace_back();
        }
        components[componentOf[root]].push_back(j);
    }
    return components;
}

Part extractPart(const MassSpringSystem& system, const std::vector<std::uint32_t>& freeKnots,
                 std::vector<std::int64_t>& scratch) {
    const MassSpringSystem& s = system;
    // whole knot -> part knot; before numbering: -1 not in the part, -2 one of `freeKnots`,
    // -3 reached by a bar of theirs (held in the part)
    std::vector<std::int64_t>& partKnot = scratch;
    partKnot.assign(s.knotCount(), -1);
    for (std::uint32_t j : freeKnots)
        if (!s.fixed[j])
            partKnot[j] = -2;
    Part part;
    for (std::size_t b = 0; b < s.barCount(); ++b) {
        const std::uint32_t a = s.barA[b], e = s.barB[b];
        if (partKnot[a] != -2 && partKnot[e] != -2)
            continue;
        part.barOf.push_back(static_cast<std::uint32_t>(b));
        for (std::uint32_t end : {a, e})
            if (partKnot[end] == -1)
                partKnot[end] = -3;
    }
    std::vector<bool> held;
    for (std::size_t j = 0; j < s.knotCount(); ++j)
        if (partKnot[j] < -1) {
            held.push_back(partKnot[j] == -3);
            partKnot[j] = static_cast<std::int64_t>(part.knotOf.size());
            part.knotOf.push_back(static_cast<std::uint32_t>(j));
        }

    MassSpringSystem& p = part.system;
    p.gravity = s.gravity;
    p.origin = s.origin;
    p.refStart.push_back(0);
    for (std::size_t k = 0; k < part.knotOf.size(); ++k) {
        const std::uint32_t j = part.knotOf[k];
        p.position.push_back(s.position[j]);
        p.mass.push_back(s.mass[j]);
        p.fixed.push_back(s.fixed[j] || held[k]);
        p.hold.push_back(j < s.hold.size() ? s.hold[j] : RailHold{});
        if (j + 1 < s.refStart.size())
            for (std::uint32_t r = s.refStart[j]; r < s.refStart[j + 1] && r < s.refs.size(); ++r)
                p.refs.push_back(s.refs[r]);
        p.refStart.push_back(static_cast<std::uint32_t>(p.refs.size()));
    }
    for (std::uint32_t b : part.barOf) {
        p.barA.push_back(static_cast<std::uint32_t>(partKnot[s.barA[b]]));
        p.barB.push_back(static_cast<std::uint32_t>(partKnot[s.barB[b]]));
        p.restLength.push_back(s.restLength[b]);
        p.kTension.push_back(s.kTension[b]);
        p.kCompression.push_back(s.kCompression[b]);
        if (b < s.linearDensity.size())
            p.linearDensity.push_back(s.linearDensity[b]);
        if (b < s.barPiece.size())
            p.barPiece.push_back(s.barPiece[b]);
    }
    return part;
}

} // namespace netsculpt
