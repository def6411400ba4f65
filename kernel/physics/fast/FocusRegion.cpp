#include "physics/fast/FocusRegion.h"

#include <algorithm>

namespace netsculpt::newton {

std::vector<std::uint32_t> focusRegion(const ForceField& field, std::span<const Vec3> force,
                                       std::span<const std::uint32_t> freeKnots, double tolerance,
                                       double share) {
    const auto limit = static_cast<std::size_t>(share * static_cast<double>(freeKnots.size()));
    if (freeKnots.size() < kFocusMinKnots)
        return {};
    std::vector<std::uint32_t> region;
    for (std::uint32_t j : freeKnots)
        if (!(field.residualOf(j, force[j]) < tolerance))
            region.push_back(j);
    if (region.size() > limit)
        return {};
    std::vector<char> inRegion(field.knotCount(), 0);
    for (std::uint32_t j : region)
        inRegion[j] = 1;
    std::size_t ringStart = 0;
    for (int ring = 0; ring < kFocusRings && region.size() <= limit; ++ring) {
        const std::size_t ringEnd = region.size();
        for (std::size_t i = ringStart; i < ringEnd; ++i)
            for (std::uint32_t b : field.barsOfKnot(region[i]))
                for (std::uint32_t end : {field.barEndA(b), field.barEndB(b)})
                    if (!inRegion[end] && !field.isFixed(end)) {
                        inRegion[end] = 1;
                        region.push_back(end);
                    }
        ringStart = ringEnd;
    }
    if (region.size() > limit)
        return {};
    std::sort(region.begin(), region.end());
    return region;
}

Part regionSystem(const MassSpringSystem& system, const std::vector<std::uint32_t>& region,
                  double blend, double scale, std::vector<std::int64_t>& scratch) {
    Part part = extractPart(system, region, scratch);
    MassSpringSystem& own = part.system;
    for (std::size_t b = 0; b < own.barCount(); ++b) {
        own.kCompression[b] = scale * std::max(own.kCompression[b], blend * own.kTension[b]);
        own.kTension[b] *= scale;
    }
    return part;
}

} // namespace netsculpt::newton
