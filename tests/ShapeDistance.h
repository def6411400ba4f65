#pragma once
// Comparing two shapes of the same net in tests.

#include "geometry/Vec3.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace netsculpt::test {

/// The largest distance between matching knots of two shapes, m.
inline double maxDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    double worst = 0;
    for (std::size_t j = 0; j < a.size(); ++j)
        worst = std::max(worst, distance(a[j], b[j]));
    return worst;
}

} // namespace netsculpt::test
