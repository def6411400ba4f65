#pragma once
// Nets the fast path's tests relax: a tube below a circular rail and a sheet hanging slack
// between two parallel rails, a banner on a wavy rail, built through the model's edits.
#include "model/Compiler.h"
#include "model/Edits.h"
#include "model/TestSculptures.h"

#include <cmath>
#include <numbers>

namespace netsculpt::test {

inline Material rope(double stiffness) { return Material{stiffness, 0.01, 0.002, 0.006}; }

/// A tube of `rows` x `columns` below a circular rail, knots 0.1 m apart on the rail.
inline Sculpture tube(int rows, int columns, double stiffness) {
    Sculpture s;
    const double radius = columns * 0.1 / (2 * std::numbers::pi);
    const RailId top = addRail(s, "top", polygonRail(columns, radius));
    const PieceId piece = attachToRail(s, {top, columns, 0, rows, 0.1, 0, false});
    setMaterial(s, piece, rope(stiffness));
    refreshAndValidate(s);
    return s;
}

/// A sheet on an open rail whose last row is held by a parallel rail 0.58 of the sheet's
/// height away (0.3 H aside, 0.5 H below): it hangs slack between them.
inline Sculpture slackSheet(int rows, int columns, double stiffness) {
    Sculpture s;
    const double width = (columns - 1) * 0.1;
    const double height = (rows - 1) * std::sqrt(0.01 - 0.0025);
    const RailId top = addRail(s, "top", lineRail({0, 0, 0}, {width, 0, 0}));
    const RailId bottom = addRail(s, "bottom", lineRail({0, 0.3 * height, -0.5 * height},
                                                    {width, 0.3 * height, -0.5 * height}));
    const PieceId piece = attachToRail(s, {top, columns, 0, rows, 0.1, 0, false});
    connectToRail(s, piece, bottom, 0.0, false);
    setMaterial(s, piece, rope(stiffness));
    refreshAndValidate(s);
    return s;
}

/// A banner of `rows` x `columns` on a wavy rail 5 m long (the benchmark's banner-RxC scene,
/// tools/bench/BenchScenes.h), its bars 0.1 m in the top row and
/// 0.14 m in the bottom one: its lower part hangs in strands whose free edges creep to their
/// equilibrium at the rope's stiffness (docs/performance.md).
inline Sculpture banner(int rows, int columns, double stiffness) {
    CurveSpec wave;
    wave.spline = true;
    wave.degree = 3;
    wave.points = {{0, 0, 12.5}, {1, 0.8, 13.0}, {2, 0, 12.5}, {3, 0.8, 13.0}, {4, 0, 12.5}};
    Sculpture s;
    AttachToRailArgs args;
    args.rail = addRail(s, "wave", wave);
    args.columns = columns;
    args.rows = rows;
    args.bar = 0.12;
    const PieceId piece = attachToRail(s, args);
    setBarLengthByRow(s, piece, 0, 0.1);
    setBarLengthByRow(s, piece, rows - 1, 0.14);
    setMaterial(s, piece, rope(stiffness));
    refreshAndValidate(s);
    return s;
}

} // namespace netsculpt::test
