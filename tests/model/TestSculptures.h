#pragma once
// Small sculptures shared by the model tests, built through the model's edits.

#include "geometry/Circle.h"
#include "model/Edits.h"

namespace netsculpt::test {

/// A closed polyline rail: a regular polygon of `n` vertices, radius r, at height z.
inline CurveSpec polygonRail(int n, double r, double z = 0) {
    CurveSpec spec;
    spec.closed = true;
    spec.points = circlePoints({0, 0, z}, r, n);
    return spec;
}

/// A closed polyline rail: a regular polygon of `n` vertices, radius r, about `centre`.
inline CurveSpec ringRail(const Vec3& centre, double r, int n) {
    CurveSpec spec;
    spec.closed = true;
    spec.points = circlePoints(centre, r, n);
    return spec;
}

/// An open straight rail from a to b.
inline CurveSpec lineRail(Vec3 a, Vec3 b) {
    CurveSpec spec;
    spec.points = {a, b};
    return spec;
}

/// Applies one edit atomically (as the command layer does) and returns its result.
template <typename Edit> auto edit(Sculpture& s, Edit&& e) { return applyAtomically(s, e).first; }

} // namespace netsculpt::test
