#include "model/ReferenceSculptures.h"

#include "geometry/Circle.h"
#include "model/Edits.h"

#include <cmath>
#include <numbers>

namespace netsculpt {

namespace {

/// A closed rail of `columns` vertices kReferenceSpacing apart, so that the top knots sit at its
/// vertices.
CurveSpec circularRail(int columns) {
    CurveSpec circle;
    circle.closed = true;
    const double radius = columns * kReferenceSpacing / (2 * std::numbers::pi);
    circle.points = circlePoints({}, radius, columns);
    return circle;
}

PieceId attachNet(Sculpture& s, RailId rail, int rows, int columns, double bar) {
    AttachToRailArgs args;
    args.rail = rail;
    args.columns = columns;
    args.rows = rows;
    args.bar = bar;
    return attachToRail(s, args);
}

Sculpture withMaterial(Sculpture s, PieceId piece, const Material& material) {
    setMaterial(s, piece, material);
    refreshAndValidate(s);
    return s;
}

} // namespace

Sculpture tubeOnCircularRail(int rows, int columns, const Material& material) {
    Sculpture s;
    const RailId top = addRail(s, "top", circularRail(columns));
    const PieceId tube = attachNet(s, top, rows, columns, kReferenceBar);
    return withMaterial(std::move(s), tube, material);
}

Sculpture sheetBetweenParallelRails(int rows, int columns, const Material& material) {
    const double width = (columns - 1) * kReferenceSpacing;
    const double height = (rows - 1) * std::sqrt(kReferenceBar * kReferenceBar -
                                                 kReferenceSpacing * kReferenceSpacing / 4);
    CurveSpec upper, lower;
    upper.points = {{0, 0, 0}, {width, 0, 0}};
    lower.points = {{0, 0.3 * height, -0.5 * height}, {width, 0.3 * height, -0.5 * height}};
    Sculpture s;
    const RailId top = addRail(s, "top", upper);
    const RailId bottom = addRail(s, "bottom", lower);
    const PieceId sheet = attachNet(s, top, rows, columns, kReferenceBar);
    connectToRail(s, sheet, bottom, 0.0, false);
    return withMaterial(std::move(s), sheet, material);
}

Sculpture bannerOnWavyRail(int rows, int columns, const Material& material) {
    CurveSpec wave;
    wave.spline = true;
    wave.degree = 3;
    wave.points = {{0, 0, 12.5}, {1, 0.8, 13.0}, {2, 0, 12.5}, {3, 0.8, 13.0}, {4, 0, 12.5}};
    Sculpture s;
    const RailId rail = addRail(s, "wave", wave);
    const PieceId banner = attachNet(s, rail, rows, columns, 0.12);
    setBarLengthByRow(s, banner, 0, 0.1);
    setBarLengthByRow(s, banner, rows - 1, 0.14);
    return withMaterial(std::move(s), banner, material);
}

} // namespace netsculpt
