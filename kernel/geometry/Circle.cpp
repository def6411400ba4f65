// circlePoints: a regular polygon's corners.

#include "geometry/Circle.h"

#include "model/Error.h"

#include <cmath>
#include <numbers>
#include <string>

namespace netsculpt {

std::vector<Vec3> circlePoints(Vec3 centre, double radius, int vertices) {
    if (!std::isfinite(radius) || radius <= 0)
        throw UserError("circle: radius must be a number > 0 m, got " + formatNumber(radius));
    if (vertices < 3 || vertices > kMaxCircleVertices)
        throw UserError("circle: points must be 3 to " + std::to_string(kMaxCircleVertices) +
                        ", got " + std::to_string(vertices));
    if (!std::isfinite(centre.x) || !std::isfinite(centre.y) || !std::isfinite(centre.z))
        throw UserError("circle: centre must be finite, got (" + formatNumber(centre.x) + ", " +
                        formatNumber(centre.y) + ", " + formatNumber(centre.z) + ")");
    std::vector<Vec3> corners;
    corners.reserve(vertices);
    for (int i = 0; i < vertices; ++i) {
        const double angle = 2 * std::numbers::pi * i / vertices;
        corners.push_back(
            {centre.x + radius * std::cos(angle), centre.y + radius * std::sin(angle), centre.z});
    }
    return corners;
}

} // namespace netsculpt
