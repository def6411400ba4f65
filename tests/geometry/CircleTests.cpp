// Tests for kernel/geometry/Circle: a ring rail's corners, against closed forms.

#include "geometry/Circle.h"
#include "model/Error.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace netsculpt;
using Catch::Contains;

TEST_CASE("circlePoints: the corners of a regular polygon about the centre, counter-clockwise") {
    const auto hexagon = circlePoints({1, -2, 3}, 0.5, 6);
    REQUIRE(hexagon.size() == 6);
    const double h = 0.5 * std::sqrt(3.0) / 2; // sin 60 degrees times the radius
    const Vec3 expected[6] = {{1.5, -2, 3},      {1.25, -2 + h, 3}, {0.75, -2 + h, 3},
                              {0.5, -2, 3},      {0.75, -2 - h, 3}, {1.25, -2 - h, 3}};
    for (int i = 0; i < 6; ++i) {
        CHECK(hexagon[i].x == Approx(expected[i].x).margin(1e-15));
        CHECK(hexagon[i].y == Approx(expected[i].y).margin(1e-15));
        CHECK(hexagon[i].z == 3);
    }
}

TEST_CASE("circlePoints: a bad radius, count or centre is a user error naming the value") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(circlePoints({}, -1, 8), Contains("radius must be a number > 0 m, got -1"));
    CHECK_THROWS_WITH(circlePoints({}, nan, 8), Contains("radius must be a number > 0 m"));
    CHECK_THROWS_WITH(circlePoints({}, 1, 2), Contains("points must be 3 to 100000, got 2"));
    CHECK_THROWS_WITH(circlePoints({}, 1, kMaxCircleVertices + 1), Contains("got 100001"));
    CHECK_THROWS_AS(circlePoints({0, nan, 0}, 1, 8), UserError);
    CHECK(circlePoints({}, 1, kMaxCircleVertices).size() == kMaxCircleVertices);
}
