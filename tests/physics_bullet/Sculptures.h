#pragma once
// The sculptures of the Bullet cross-check (tests/physics_bullet), built with
// the model's edits: a tube on a circular rail (paper, Fig. 10), a sheet between two parallel
// rails, a tube connected to a second ring (Fig. 11) and a gear-changing stack. `size` scales the
// knot count (about 100 * size^2 knots); one material for every piece unless `barSpread` makes
// the pieces' bar lengths (and so their k = EA / l) differ.

#include "model/TestSculptures.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace netsculpt::test {

struct CrossCheckSculpture {
    std::string name;
    Sculpture sculpture;
    CompiledSculpture compiled;
};

/// Sets `material` on every piece and compiles (through applyAtomically, as the commands do).
inline CompiledSculpture withMaterial(Sculpture& s, const Material& material) {
    return applyAtomically(s, [&](Sculpture& m) {
               for (auto& [id, piece] : m.pieces)
                   setMaterial(m, id, material);
               return 0;
           })
        .second;
}

/// Closed rail of `columns` vertices, so that the columns sit at its vertices.
inline CurveSpec ring(int columns, double radius, double z = 0) { return polygonRail(columns, radius, z); }

/// Tube of `columns` x `rows` below a circular rail (Fig. 10).
inline CrossCheckSculpture tubeOnRing(const Material& material, double size = 1) {
    const int columns = int(std::lround(12 * size)), rows = int(std::lround(10 * size));
    const double radius = 0.5 * size;
    CrossCheckSculpture c{"tube on a ring", {}, {}};
    Sculpture& s = c.sculpture;
    const RailId rail = edit(s, [&](Sculpture& m) { return addRail(m, "ring", ring(columns, radius)); });
    edit(s, [&](Sculpture& m) { return attachToRail(m, {rail, columns, 0, rows, 0.2, 0, false}); });
    c.compiled = withMaterial(s, material);
    return c;
}

/// Sheet hanging like a hammock between two parallel straight rails: its top on the upper rail,
/// its last row connected to a rail 0.5 m across and 0.3 m lower (closer than the sheet is
/// long, so it sags).
inline CrossCheckSculpture sheetBetweenRails(const Material& material, double size = 1, double barSpread = 0) {
    const int columns = int(std::lround(11 * size)), rows = 2 * int(std::lround(4.5 * size)) + 1; // odd
    const double spacing = 0.2, length = spacing * (columns - 1);
    CrossCheckSculpture c{"sheet between two rails", {}, {}};
    Sculpture& s = c.sculpture;
    const RailId top = edit(s, [&](Sculpture& m) { return addRail(m, "top", lineRail({0, 0, 0}, {length, 0, 0})); });
    const RailId low = edit(s, [&](Sculpture& m) {
        return addRail(m, "low", lineRail({0, 0.5 * size, -0.3 * size}, {length, 0.5 * size, -0.3 * size}));
    });
    const PieceId sheet = edit(s, [&](Sculpture& m) { return attachToRail(m, {top, columns, 0, rows, 0.15, 0, false}); });
    if (barSpread != 0)
        edit(s, [&](Sculpture& m) { setBarLength(m, sheet, 0, 0.15 * (1 + barSpread)); return 0; });
    edit(s, [&](Sculpture& m) { connectToRail(m, sheet, low, 0, false); return 0; });
    c.compiled = withMaterial(s, material);
    return c;
}

/// Tube hung from one ring with its last row connected to a second, narrower ring below (Fig. 11),
/// a little lower than the tube reaches unloaded, so the tube is held taut between them.
inline CrossCheckSculpture tubeBetweenRings(const Material& material, double size = 1) {
    const int columns = int(std::lround(12 * size)), rows = int(std::lround(9 * size));
    const double radius = 0.5 * size, bar = 0.2;
    const double halfChord = radius * std::sin(std::numbers::pi / columns);
    const double drop = (rows - 1) * std::sqrt(bar * bar - halfChord * halfChord);
    CrossCheckSculpture c{"tube between two rings", {}, {}};
    Sculpture& s = c.sculpture;
    const RailId upper = edit(s, [&](Sculpture& m) { return addRail(m, "upper", ring(columns, radius)); });
    const RailId lower = edit(s, [&](Sculpture& m) { return addRail(m, "lower", ring(columns, 0.7 * radius, -1.05 * drop)); });
    const PieceId tube = edit(s, [&](Sculpture& m) { return attachToRail(m, {upper, columns, 0, rows, bar, 0, false}); });
    edit(s, [&](Sculpture& m) { connectToRail(m, tube, lower, 0, false); return 0; });
    c.compiled = withMaterial(s, material);
    return c;
}

/// Gear-changing stack: a tube, a child with gear 2 below it, a grandchild with gear 1/2 below
/// that. barSpread != 0 gives the three pieces different bar lengths.
inline CrossCheckSculpture gearStack(const Material& material, double size = 1, double barSpread = 0) {
    const int columns = int(std::lround(8 * size)), rows = int(std::lround(5 * size));
    const double radius = 0.3 * size;
    CrossCheckSculpture c{"gear-changing stack", {}, {}};
    Sculpture& s = c.sculpture;
    const RailId rail = edit(s, [&](Sculpture& m) { return addRail(m, "ring", ring(columns, radius)); });
    const PieceId tube = edit(s, [&](Sculpture& m) { return attachToRail(m, {rail, columns, 0, rows, 0.2, 0, false}); });
    const PieceId child = edit(s, [&](Sculpture& m) {
        return attachToPiece(m, {tube, Gear{2, 1}, rows, 0.2 * (1 - 0.5 * barSpread)});
    });
    edit(s, [&](Sculpture& m) { return attachToPiece(m, {child, Gear{1, 2}, rows, 0.2 * (1 + barSpread)}); });
    c.compiled = withMaterial(s, material);
    return c;
}

} // namespace netsculpt::test
