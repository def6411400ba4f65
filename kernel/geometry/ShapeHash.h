#pragma once
// A hash of a shape's positions, bit for bit: the same shape, the same hash. The live preview
// recognises the shapes it published by it (interaction/LiveRelaxer.h); the live bench prints it
// to show that a change left a drag's shapes as they were.

#include "geometry/Vec3.h"

#include <cstdint>
#include <cstring>
#include <vector>

namespace netsculpt {

/// FNV-1a over the bits of every coordinate, in order.
inline std::uint64_t shapeHash(const std::vector<Vec3>& positions) {
    std::uint64_t hash = 1469598103934665603ull;
    for (const Vec3& p : positions)
        for (double v : {p.x, p.y, p.z}) {
            std::uint64_t bits = 0;
            std::memcpy(&bits, &v, sizeof bits);
            hash = (hash ^ bits) * 1099511628211ull;
        }
    return hash;
}

} // namespace netsculpt
