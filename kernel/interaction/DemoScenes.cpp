#include "interaction/DemoScenes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace netsculpt {

namespace {

/// A closed cubic B-spline through a wavy ring: radius r (+- wave), height z (+- tilt).
CurveSpec wavyRing(double r, double z, double wave, double tilt, int lobes) {
    CurveSpec spec;
    spec.spline = true;
    spec.degree = 3;
    spec.closed = true;
    const int n = 16;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * std::numbers::pi * i / n;
        const double radius = r * (1 + wave * std::cos(lobes * a));
        spec.points.push_back({radius * std::cos(a), radius * std::sin(a), z + tilt * std::sin(a)});
    }
    return spec;
}

RailId firstRail(const CommandResult& r) { return r.rails.front(); }
PieceId firstPiece(const CommandResult& r) { return r.pieces.front(); }

} // namespace

void buildDemoSculpture(Document& doc) {
    const RailId crown = firstRail(doc.execute(AddRailCommand{"crown", wavyRing(2.0, 4.2, 0.12, 0.25, 3)}));
    const RailId ring = firstRail(doc.execute(AddRailCommand{"ring", wavyRing(0.55, 0.6, 0.0, 0.0, 1)}));
    CurveSpec arc;
    arc.spline = true;
    arc.degree = 2;
    arc.points = {{2.6, -2.4, 3.6}, {3.8, -1.2, 4.4}, {4.0, 0.6, 3.8}};
    const RailId side = firstRail(doc.execute(AddRailCommand{"arc", arc}));

    AttachToRailArgs top;
    top.rail = crown;
    top.columns = 48;
    top.rows = 14;
    top.bar = 0.2;
    const PieceId crownNet = firstPiece(doc.execute(AttachToRailCommand{top}));

    AttachToPieceArgs below;
    below.parent = crownNet;
    below.gear = Gear{1, 2};
    below.rows = 8;
    below.bar = 0.3;
    const PieceId lower = firstPiece(doc.execute(AttachToPieceCommand{below}));
    doc.execute(ConnectToRailCommand{lower, ring, 0.0, false});

    AttachToRailArgs sheet;
    sheet.rail = side;
    sheet.columns = 18;
    sheet.rows = 12;
    sheet.bar = 0.16;
    doc.execute(AttachToRailCommand{sheet});
}

void buildLargeDemoSculpture(Document& doc, int knots) {
    // A wide tube: twice as many columns as rows.
    const int columns = std::max(8, int(std::lround(std::sqrt(knots * 2.0))));
    const int rows = std::max(2, knots / columns);
    const double radius = 3.0;
    const double spacing = 2 * std::numbers::pi * radius / columns;
    const RailId crown = firstRail(doc.execute(AddRailCommand{"crown", wavyRing(radius, 8.0, 0.1, 0.3, 4)}));
    AttachToRailArgs net;
    net.rail = crown;
    net.columns = columns;
    net.rows = rows;
    net.bar = 0.75 * spacing;
    doc.execute(AttachToRailCommand{net});
}

void buildLargeSlackSheet(Document& doc, int knots, bool tied) {
    const int columns = std::max(8, int(std::lround(std::sqrt(knots * 2.0))));
    const int rows = std::max(2, knots / columns);
    const double spacing = 0.1, bar = 0.1;
    const double width = (columns - 1) * spacing;
    // The sheet's height hanging straight: each row's knots between two of the row above.
    const double height = (rows - 1) * std::sqrt(bar * bar - spacing * spacing / 4);
    const double lowerY = 0.3 * height, lowerZ = 8.0 - 0.5 * height; // the second rail's place
    CurveSpec upper, lower;
    upper.points = {{0, 0, 8.0}, {width, 0, 8.0}};
    lower.points = {{0, lowerY, lowerZ}, {width, lowerY, lowerZ}};
    const RailId top = firstRail(doc.execute(AddRailCommand{"top", upper}));
    const RailId bottom = firstRail(doc.execute(AddRailCommand{"bottom", lower}));
    AttachToRailArgs sheet;
    sheet.rail = top;
    sheet.columns = columns;
    sheet.rows = rows;
    sheet.bar = bar;
    const PieceId piece = firstPiece(doc.execute(AttachToRailCommand{sheet}));
    if (tied)
        doc.execute(ConnectToRailCommand{piece, bottom, 0.0, false});
}

} // namespace netsculpt
