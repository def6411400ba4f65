// The sculpture model and its compiled mass-spring system (DESIGN.md "Net piece", "How pieces
// are joined"): counts, the staggering rule, Eq. 1-2 initial geometry, gears, seams, bad input.

#include "TestSculptures.h"

#include "model/BarPairs.h"
#include "model/Error.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <numbers>
#include <queue>
#include <set>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;

namespace {

bool sameModel(const Sculpture& a, const Sculpture& b) {
    if (a.rails.size() != b.rails.size() || a.pieces != b.pieces || a.seams != b.seams) return false;
    for (const auto& [id, rail] : a.rails) {
        auto it = b.rails.find(id);
        if (it == b.rails.end() || it->second.name != rail.name || it->second.shape != rail.shape) return false;
    }
    return a.nextRailId == b.nextRailId && a.nextPieceId == b.nextPieceId && a.gravity == b.gravity;
}

bool everyKnotHasPathUp(const MassSpringSystem& sys) {
    std::vector<std::vector<std::uint32_t>> adjacent(sys.knotCount());
    for (std::size_t b = 0; b < sys.barCount(); ++b) {
        adjacent[sys.barA[b]].push_back(sys.barB[b]);
        adjacent[sys.barB[b]].push_back(sys.barA[b]);
    }
    std::vector<char> reached(sys.knotCount(), 0);
    std::queue<std::uint32_t> todo;
    for (std::uint32_t k = 0; k < sys.knotCount(); ++k)
        if (sys.fixed[k]) {
            reached[k] = 1;
            todo.push(k);
        }
    while (!todo.empty()) {
        const auto k = todo.front();
        todo.pop();
        for (auto n : adjacent[k])
            if (!reached[n]) {
                reached[n] = 1;
                todo.push(n);
            }
    }
    return std::all_of(reached.begin(), reached.end(), [](char c) { return c != 0; });
}

struct Tube {
    Sculpture s;
    RailId rail;
    PieceId piece;
};

Tube tube(int columns, int rows, double radius = 2.0, double bar = 0.8) {
    Tube t;
    t.rail = edit(t.s, [&](Sculpture& s) { return addRail(s, "ring", polygonRail(columns, radius)); });
    t.piece = edit(t.s, [&](Sculpture& s) {
        return attachToRail(s, {t.rail, columns, 0, rows, bar, 0, false});
    });
    return t;
}

} // namespace

TEST_CASE("knot and bar counts of closed and open pieces") {
    Tube t = tube(12, 5);
    auto c = compileSculpture(t.s);
    CHECK(c.system.knotCount() == 60);
    CHECK(c.system.barCount() == 2 * 12 * 4);
    CHECK(std::count(c.system.fixed.begin(), c.system.fixed.end(), 1) == 12);

    Sculpture s;
    RailId line = edit(s, [](Sculpture& m) { return addRail(m, "line", lineRail({0, 0, 0}, {3, 0, 0})); });
    PieceId sheet = edit(s, [&](Sculpture& m) { return attachToRail(m, {line, 7, 0, 4, 0.5, 0, false}); });
    auto o = compileSculpture(s);
    CHECK(o.system.knotCount() == 28);
    CHECK(o.system.barCount() == 3 * (2 * 7 - 1));
    CHECK_FALSE(s.piece(sheet).closed);
    CHECK(everyKnotHasPathUp(o.system));
}

TEST_CASE("every bar follows the staggering rule - columns wrap only in closed pieces") {
    for (bool closed : {true, false}) {
        Sculpture s;
        const int columns = 8, rows = 6;
        RailId rail = edit(s, [&](Sculpture& m) {
            return addRail(m, "r", closed ? polygonRail(columns, 1.5) : lineRail({0, 0, 0}, {3.5, 0, 0}));
        });
        edit(s, [&](Sculpture& m) { return attachToRail(m, {rail, columns, 0, rows, 0.9, 0, false}); });
        auto c = compileSculpture(s);
        const auto& sys = c.system;
        std::vector<int> up(sys.knotCount(), 0), down(sys.knotCount(), 0);
        for (std::size_t b = 0; b < sys.barCount(); ++b) {
            KnotRef a = sys.refs[sys.refStart[sys.barA[b]]];
            KnotRef d = sys.refs[sys.refStart[sys.barB[b]]];
            if (a.row < d.row) std::swap(a, d); // a is the lower knot
            REQUIRE(a.row == d.row + 1);
            const int expected1 = a.row % 2 == 1 ? a.column : a.column - 1;
            const int expected2 = a.row % 2 == 1 ? a.column + 1 : a.column;
            const int parent = d.column;
            const auto wrapped = [&](int x) { return closed ? (x + columns) % columns : x; };
            CHECK((parent == wrapped(expected1) || parent == wrapped(expected2)));
            ++up[sys.barA[b] == c.knotOf(a.piece, a.row, a.column) ? sys.barA[b] : sys.barB[b]];
            ++down[sys.barA[b] == c.knotOf(a.piece, a.row, a.column) ? sys.barB[b] : sys.barA[b]];
        }
        for (int r = 0; r < rows; ++r)
            for (int col = 0; col < columns; ++col) {
                const auto k = c.knotOf(PieceId(1), r, col);
                const bool edgeUp = !closed && ((r % 2 == 1 && col == columns - 1) || (r % 2 == 0 && col == 0));
                CHECK(up[k] == (r == 0 ? 0 : (edgeUp ? 1 : 2)));
                const bool edgeDown = !closed && r + 1 < rows &&
                                      (((r + 1) % 2 == 1 && col == 0) || ((r + 1) % 2 == 0 && col == columns - 1));
                CHECK(down[k] == (r == rows - 1 ? 0 : (edgeDown ? 1 : 2)));
            }
    }
}

TEST_CASE("initial geometry on a circular rail follows Eq. 1 and 2") {
    const int n = 12;
    const double radius = 2.0, l = 0.8;
    Tube t = tube(n, 3, radius, l);
    auto c = compileSculpture(t.s);
    const double half = std::numbers::pi / n;
    const double h1 = std::sqrt(l * l - std::pow(radius * std::sin(half), 2)); // s/2 = R sin(pi/n)
    const double r1 = radius * std::cos(half);
    const double h2 = std::sqrt(l * l - std::pow(r1 * std::sin(half), 2));
    const double r2 = r1 * std::cos(half);
    for (int col = 0; col < n; ++col) {
        const Vec3 top = c.system.position[c.knotOf(t.piece, 0, col)];
        CHECK(top.x == Approx(radius * std::cos(2 * half * col)).margin(1e-12));
        CHECK(top.y == Approx(radius * std::sin(2 * half * col)).margin(1e-12));
        const Vec3 p1 = c.system.position[c.knotOf(t.piece, 1, col)];
        const double a1 = 2 * half * (col + 0.5);
        CHECK(p1.x == Approx(r1 * std::cos(a1)).margin(1e-12));
        CHECK(p1.y == Approx(r1 * std::sin(a1)).margin(1e-12));
        CHECK(p1.z == Approx(-h1).margin(1e-12));
        const Vec3 p2 = c.system.position[c.knotOf(t.piece, 2, col)];
        CHECK(p2.x == Approx(r2 * std::cos(2 * half * col)).margin(1e-12));
        CHECK(p2.y == Approx(r2 * std::sin(2 * half * col)).margin(1e-12));
        CHECK(p2.z == Approx(-h1 - h2).margin(1e-12));
    }
}

TEST_CASE("knot masses come from the material") {
    Tube t = tube(12, 3, 2.0, 0.8);
    auto c = compileSculpture(t.s);
    const Material m = t.s.piece(t.piece).material;
    // A middle-row knot has four bars of 0.8 m: knot mass + 1/2 * density * 3.2 m.
    CHECK(c.system.mass[c.knotOf(t.piece, 1, 0)] == Approx(m.knotMass + 0.5 * m.linearDensity * 3.2));
    CHECK(c.system.mass[c.knotOf(t.piece, 2, 0)] == Approx(m.knotMass + 0.5 * m.linearDensity * 1.6));
    CHECK(c.system.kTension[0] == Approx(m.stiffness / 0.8));
    CHECK(c.system.kCompression[0] == Approx(m.compressionRatio * m.stiffness / 0.8));
}

TEST_CASE("gear junctions share their knots") {
    struct Case {
        Gear gear;
        int childColumns;
        int newKnots; // gear-up knots between shared ones
    };
    const Case cases[] = {{{3, 1}, 36, 24}, {{2, 1}, 24, 12}, {{1, 1}, 12, 0}, {{1, 2}, 6, 0}, {{1, 3}, 4, 0}};
    for (const Case& k : cases) {
        Tube t = tube(12, 3);
        PieceId child = edit(t.s, [&](Sculpture& m) { return attachToPiece(m, {t.piece, k.gear, 4, k.gear.den > 1 ? 1.5 : 0.6}); });
        auto c = compileSculpture(t.s);
        const Piece& q = t.s.piece(child);
        INFO("gear " << toString(k.gear));
        CHECK(q.columns == k.childColumns);
        CHECK(q.closed);
        const int shared = std::min(12, k.childColumns);
        CHECK(c.system.knotCount() == std::size_t(36 + 4 * k.childColumns - shared));
        CHECK(c.system.barCount() == std::size_t(2 * 12 * 2 + 2 * k.childColumns * 3 + 2 * k.newKnots));
        for (int col = 0; col < k.childColumns; ++col) {
            const auto childKnot = c.knotOf(child, 0, col);
            if (k.gear.den > 1) {
                CHECK(childKnot == c.knotOf(t.piece, 2, col * k.gear.den));
            } else if (col % k.gear.num == 0) {
                CHECK(childKnot == c.knotOf(t.piece, 2, col / k.gear.num));
            } else {
                const auto refs = c.system.refStart[childKnot + 1] - c.system.refStart[childKnot];
                CHECK(refs == 1); // a new knot, not shared
            }
        }
        CHECK(everyKnotHasPathUp(c.system));
    }
}

TEST_CASE("a gear that does not divide is refused with the allowed gears") {
    Tube t = tube(9, 2, 2.0, 1.0);
    const Sculpture before = t.s;
    REQUIRE_THROWS_WITH(edit(t.s, [&](Sculpture& m) { return attachToPiece(m, {t.piece, {1, 2}, 3, 0.3}); }),
                        Contains("gear 1/2 does not divide a row of 9") && Contains("1/3"));
    CHECK(sameModel(before, t.s));
}

TEST_CASE("a split or a gear that leaves too few columns says so in the piece's terms") {
    Sculpture s;
    const RailId line = edit(s, [](Sculpture& m) {
        return addRail(m, "line", lineRail({0, 0, 3}, {1, 0, 3}));
    });
    const PieceId narrow = edit(s, [&](Sculpture& m) {
        return attachToRail(m, {line, 2, 0, 2, 0.6, 0, false});
    });
    REQUIRE_THROWS_WITH(edit(s, [&](Sculpture& m) { return split(m, narrow, 1); }),
                        Contains("is an open piece of 2 columns, which has no column to split at"));
    CHECK_THAT(splitRefusal(s, narrow), Contains("is an open piece of 2 columns"));
    Tube t = tube(6, 3, 1.0, 0.6);
    REQUIRE_THROWS_WITH(
        edit(t.s,
             [&](Sculpture& m) {
                 return attachToPiece(m, {t.piece, {1, 3}, 2, 0.6});
             }),
        Contains("gear 1/3 below piece 1's 6 columns gives 2, and a closed tube needs 3"));
}

TEST_CASE("a knot that would weigh nothing is refused, naming it") {
    // A piece of one row has no bars: with knot_mass 0 its knots weigh nothing, which no
    // relaxation, report or snapshot accepts. With two rows every knot has half a bar's rope.
    Tube one = tube(12, 1, 2.0, 0.8);
    Material weightlessKnots = one.s.pieces.at(one.piece).material;
    weightlessKnots.knotMass = 0;
    const Sculpture before = one.s;
    REQUIRE_THROWS_WITH(
        edit(one.s,
             [&](Sculpture& m) {
                 setMaterial(m, one.piece, weightlessKnots);
                 return 0;
             }),
        Contains("piece 1: the knot at row 0, column 0 would weigh nothing: knot_mass 0 kg"));
    CHECK(sameModel(before, one.s));
    Tube two = tube(12, 2, 2.0, 0.8);
    edit(two.s, [&](Sculpture& m) {
        setMaterial(m, two.piece, weightlessKnots);
        return 0;
    });
    CHECK(two.s.pieces.at(two.piece).material.knotMass == 0);
}

TEST_CASE(
    "a row too short to span split parts of different heights says which rows it hangs from") {
    // A ring of 48 columns, 30 rows of 0.25 m, a gear-2 child of 0.2 m bars, split at 12: the
    // part from column 0 made 40 rows long ends 10 rows lower than the other, and the child's
    // knot between the two last rows cannot reach across (DESIGN.md Eq. 2).
    Tube t = tube(48, 30, 2.0, 0.25);
    edit(t.s, [&](Sculpture& m) { return attachToPiece(m, {t.piece, {2, 1}, 20, 0.2}); });
    edit(t.s, [&](Sculpture& m) { return split(m, t.piece, 12); });
    const Sculpture before = t.s;
    REQUIRE_THROWS_WITH(
        edit(t.s,
             [&](Sculpture& m) {
                 setRows(m, t.piece, 40);
                 return 0;
             }),
        Contains("is not above half the spacing") && Contains("it hangs from piece 1 row 39") &&
            Contains("and piece 3 row 29") && Contains("last rows end at different heights"));
    CHECK(sameModel(before, t.s));
}

TEST_CASE("a gear-down child of bars too short names no sibling as a piece side by side") {
    // A gear-2 child's row 0 shares the parent's last row. A gear-1/3 child hanging from that
    // row with bars too short was told it hung from "piece 1 row 29 and piece 2 row 0", pieces
    // "side by side whose last rows end at different heights": piece 2 is the sibling below.
    Tube t = tube(48, 30, 2.0, 0.25);
    edit(t.s, [&](Sculpture& m) { return attachToPiece(m, {t.piece, {2, 1}, 20, 0.2}); });
    const Sculpture before = t.s;
    REQUIRE_THROWS_WITH(edit(t.s,
                             [&](Sculpture& m) {
                                 return attachToPiece(m, {t.piece, {1, 3}, 5, 0.2});
                             }),
                        Contains("piece 3: bar length 0.2 m at row 1") &&
                            Contains("is not above half the spacing") &&
                            !Contains("side by side") && !Contains("piece 2"));
    CHECK(sameModel(before, t.s));
}

namespace {

/// Sorted (position, rest length) fingerprint of a compiled system, for "nothing changed".
std::pair<std::vector<std::array<double, 3>>, std::vector<std::array<double, 7>>> fingerprint(const MassSpringSystem& sys) {
    std::vector<std::array<double, 3>> knots;
    for (const Vec3& p : sys.position) knots.push_back({p.x, p.y, p.z});
    std::vector<std::array<double, 7>> bars;
    for (std::size_t b = 0; b < sys.barCount(); ++b) {
        Vec3 a = sys.position[sys.barA[b]], d = sys.position[sys.barB[b]];
        if (std::tie(d.x, d.y, d.z) < std::tie(a.x, a.y, a.z)) std::swap(a, d);
        bars.push_back({a.x, a.y, a.z, d.x, d.y, d.z, sys.restLength[b]});
    }
    std::sort(knots.begin(), knots.end());
    std::sort(bars.begin(), bars.end());
    return {knots, bars};
}

} // namespace

TEST_CASE("a split changes no knot, bar or rest length") {
    Tube t = tube(12, 5, 2.0, 1.0);
    PieceId child = edit(t.s, [&](Sculpture& m) { return attachToPiece(m, {t.piece, {2, 1}, 3, 1.0}); });
    const auto before = compileSculpture(t.s);
    auto [a, b] = edit(t.s, [&](Sculpture& m) { return split(m, t.piece, 4); });
    CHECK(a == t.piece);
    CHECK(t.s.piece(a).columns == 5);
    CHECK(t.s.piece(b).columns == 9);
    CHECK_FALSE(t.s.piece(a).closed);
    CHECK(t.s.piece(child).columns == 24); // still hangs from the same knots
    const auto after = compileSculpture(t.s);
    CHECK(after.system.knotCount() == before.system.knotCount());
    CHECK(after.system.barCount() == before.system.barCount());
    CHECK(fingerprint(after.system) == fingerprint(before.system));
    // The seam: column 4 of a is column 0 of b, in every row; and b's last column is a's column 0.
    for (int r = 0; r < 5; ++r) {
        CHECK(after.knotOf(a, r, 4) == after.knotOf(b, r, 0));
        CHECK(after.knotOf(b, r, 8) == after.knotOf(a, r, 0));
    }
    // Split again, with a bar-length gradient across the seam.
    edit(t.s, [&](Sculpture& m) { setBarLength(m, a, 0, 1.1); return 0; });
    const auto graded = compileSculpture(t.s);
    auto [a2, c2] = edit(t.s, [&](Sculpture& m) { return split(m, a, 2); });
    CHECK(a2 == a);
    const auto resplit = compileSculpture(t.s);
    CHECK(fingerprint(resplit.system) == fingerprint(graded.system));
    CHECK(t.s.piece(c2).bar.at(0) == t.s.piece(a).bar.at(2));
}

TEST_CASE("a piece graded by row is not split: seamed pieces vary their bar length by column") {
    // Both parts would keep the profile, until set_rows on one of them stretched its profile
    // over other rows and the seam's two sides took different lengths (a property test's find).
    Sculpture s;
    const RailId line = edit(s, [](Sculpture& m) {
        return addRail(m, "line", lineRail({0, 0, 0}, {4.5, 0, 0}));
    });
    const PieceId p = edit(s, [&](Sculpture& m) {
        return attachToRail(m, {line, 10, 0, 4, 0.5, 0, false});
    });
    edit(s, [&](Sculpture& m) {
        setBarLengthByRow(m, p, 0, 0.5);
        setBarLengthByRow(m, p, 3, 0.8);
        return 0;
    });
    const Sculpture before = s;
    REQUIRE_THROWS_WITH(edit(s, [&](Sculpture& m) { return split(m, p, 4); }),
                        Contains("piece 1 varies its bar length by row") &&
                            Contains("set its bar length by column"));
    CHECK(sameModel(before, s));
    // Asked before a split (the studio's divide mode), the refusal is the same, word for word.
    std::string refused;
    try {
        (void)split(s, p, 4);
    } catch (const UserError& e) {
        refused = e.what();
    }
    CHECK(splitRefusal(s, p) == refused);
    // One length again: the split is the same net, rest length for rest length.
    edit(s, [&](Sculpture& m) {
        setBarLength(m, p, std::nullopt, 0.6);
        return 0;
    });
    CHECK(splitRefusal(s, p).empty());
    const auto whole = compileSculpture(s);
    edit(s, [&](Sculpture& m) { return split(m, p, 4); });
    CHECK(fingerprint(compileSculpture(s).system) == fingerprint(whole.system));
}

TEST_CASE("bar length at a seam is shared and interpolated across each piece") {
    Sculpture s;
    RailId line = edit(s, [](Sculpture& m) { return addRail(m, "line", lineRail({0, 0, 0}, {4.5, 0, 0})); });
    PieceId p = edit(s, [&](Sculpture& m) { return attachToRail(m, {line, 10, 0, 4, 0.5, 0, false}); });
    auto [a, b] = edit(s, [&](Sculpture& m) { return split(m, p, 5); });
    edit(s, [&](Sculpture& m) { setBarLength(m, a, 5, 0.7); return 0; });
    CHECK(s.piece(a).bar.at(5) == 0.7);
    CHECK(s.piece(b).bar.at(0) == 0.7);
    CHECK(s.piece(a).bar.at(0) == 0.5);
    CHECK(s.piece(a).bar.at(2) == Approx(0.5 + 0.2 * 2 / 5));
    CHECK(s.piece(b).bar.at(4) == 0.5);
}

TEST_CASE("numbers in messages read back to the same double, and a NaN reads nan") {
    CHECK(formatNumber(0.1) == "0.1");
    CHECK(std::stod(formatNumber(1.0 / 3)) == 1.0 / 3);
    CHECK(formatNumber(-std::nan("")) == "nan"); // not "-nan", which reads as a number
    CHECK(formatNumber(std::nan("")) == "nan");
    CHECK(formatNumber(-1e300 * 1e300) == "-inf");
}

TEST_CASE("bad input is refused with a clear message and changes nothing") {
    Tube t = tube(12, 4);
    const Sculpture before = t.s;
    const auto refused = [&](auto e, const std::string& needle) {
        INFO(needle);
        REQUIRE_THROWS_WITH(edit(t.s, e), Contains(needle));
        CHECK(sameModel(before, t.s));
    };
    refused([&](Sculpture& m) { setRows(m, t.piece, 0); return 0; }, "got 0");
    refused([&](Sculpture& m) { setRows(m, t.piece, -3); return 0; }, "got -3");
    refused([&](Sculpture& m) { return attachToRail(m, {t.rail, 0, 0, 3, 0.5, 0, false}); }, "spacing");
    refused([&](Sculpture& m) { return attachToRail(m, {t.rail, 2, 0, 3, 0.5, 0, false}); }, "got 2");
    refused([&](Sculpture& m) { return attachToRail(m, {t.rail, 12, 0, 3, 0.4, 0, false}); },
            "bar length 0.4 m at row 1");
    refused([&](Sculpture& m) { return attachToRail(m, {t.rail, 12, 0, 3, 0.4, 0, false}); }, "m / 2 =");
    refused([&](Sculpture& m) { setBarLength(m, t.piece, std::nullopt, -1); return 0; }, "got -1");
    // Numbers beyond the physical ranges (a bar of 1e300 m would hang its knots at z = -inf).
    refused([&](Sculpture& m) { setBarLength(m, t.piece, std::nullopt, 1e300); return 0; },
            "bar length must be a number of metres above 0 and at most 1000, got 1e+300");
    refused([&](Sculpture& m) { setBarLength(m, t.piece, std::nullopt, 1000.5); return 0; },
            "got 1000.5");
    refused([&](Sculpture& m) { return attachToRail(m, {t.rail, 12, 0, 3, 1e200, 0, false}); },
            "at most 1000, got 1e+200");
    refused([&](Sculpture& m) { setGravity(m, {0, 0, -1e300}); return 0; },
            "gravity must be a vector of magnitude 0.001 to 1000 m/s^2, got (0, 0, -1e+300)");
    refused([&](Sculpture& m) { setGravity(m, {0, 0, -1e-300}); return 0; }, "-1e-300");
    refused([&](Sculpture& m) { setGravity(m, {-600, 0, -900}); return 0; }, "(-600, 0, -900)");
    refused([&](Sculpture& m) { setGravity(m, {0, 0, 0}); return 0; }, "(0, 0, 0)");
    refused([&](Sculpture& m) { return attachToPiece(m, {PieceId(99), {1, 1}, 3, 0.5}); }, "piece 99");
    refused([&](Sculpture& m) { return split(m, t.piece, 12); }, "got 12");
    refused([&](Sculpture& m) { return split(m, t.piece, 0); }, "from 1 to 11");
    refused([&](Sculpture& m) { removeRail(m, t.rail); return 0; }, "piece 1");
    CurveSpec nan = polygonRail(5, 1.0);
    nan.points[2].y = std::nan("");
    refused([&](Sculpture& m) { return addRail(m, "bad", nan); }, "nan");
    CurveSpec dot;
    dot.points = {{1, 1, 1}, {1, 1, 1}};
    refused([&](Sculpture& m) { return addRail(m, "dot", dot); }, "distinct");
    CurveSpec spline;
    spline.spline = true;
    spline.degree = 3;
    spline.points = {{0, 0, 0}, {1, 0, 0}};
    refused([&](Sculpture& m) { return addRail(m, "short", spline); }, "2");
    Material soft;
    soft.stiffness = 0;
    refused([&](Sculpture& m) { setMaterial(m, t.piece, soft); return 0; }, "stiffness");
    Material steel;
    steel.stiffness = 2e12;
    refused([&](Sculpture& m) { setMaterial(m, t.piece, steel); return 0; }, "at most 1e+12, got 2e+12");
    Material heavy;
    heavy.knotMass = 1001;
    refused([&](Sculpture& m) { setMaterial(m, t.piece, heavy); return 0; }, "knot_mass");
    Material dense;
    dense.linearDensity = 1e300;
    refused([&](Sculpture& m) { setMaterial(m, t.piece, dense); return 0; }, "from 0 to 1000, got 1e+300");
    refused([&](Sculpture& m) { setGear(m, t.piece, {2, 1}); return 0; }, "rail");
    refused([&](Sculpture& m) { disconnect(m, t.piece); return 0; }, "not connected");
    // A removed piece is named as removed.
    edit(t.s, [&](Sculpture& m) { removePiece(m, t.piece); return 0; });
    REQUIRE_THROWS_WITH(t.s.piece(t.piece), Contains("piece 1 was removed"));
}

namespace {

/// A sculpture of two regular polygon rails: "top" of radius 2 m at z = 0 and "bottom" of
/// radius 1 m at z = -3, with `corners` corners each.
struct TwoRings {
    Sculpture s;
    RailId top, bottom;
    explicit TwoRings(int corners) {
        top = edit(s, [&](Sculpture& m) {
            return addRail(m, "top", polygonRail(corners, 2.0, 0));
        });
        bottom = edit(s, [&](Sculpture& m) {
            return addRail(m, "bottom", polygonRail(corners, 1.0, -3));
        });
    }
};

} // namespace

TEST_CASE("a tube connected to a second rail has its last row fixed on that rail") {
    TwoRings rings(16);
    Sculpture& s = rings.s;
    const RailId top = rings.top, bottom = rings.bottom;
    PieceId p = edit(s, [&](Sculpture& m) { return attachToRail(m, {top, 16, 0, 8, 0.6, 0, false}); });
    edit(s, [&](Sculpture& m) { connectToRail(m, p, bottom, 0.25, false); return 0; });
    auto c = compileSculpture(s);
    CHECK(std::count(c.system.fixed.begin(), c.system.fixed.end(), 1) == 32);
    const Vec3 k0 = c.system.position[c.knotOf(p, 7, 0)];
    CHECK(k0.x == Approx(0).margin(1e-12)); // t = 0.25 on the ring of radius 1: (0, 1, -3)
    CHECK(k0.y == Approx(1.0));
    CHECK(k0.z == Approx(-3.0));
    CHECK(c.system.hold[c.knotOf(p, 7, 4)].rail == bottom);
    CHECK(c.system.hold[c.knotOf(p, 7, 4)].t == Approx(0.5));
}

TEST_CASE(
    "a knot held on a closed rail has its rail position from 0 up to 1 and its place unchanged") {
    TwoRings rings(7);
    Sculpture& s = rings.s;
    const RailId top = rings.top, bottom = rings.bottom;
    PieceId p = edit(s, [&](Sculpture& m) {
        return attachToRail(m, {top, 12, 0, 6, 0.6, 0.9, false});
    });
    edit(s, [&](Sculpture& m) {
        connectToRail(m, p, bottom, 0.3, true);
        return 0;
    });
    const auto c = compileSculpture(s);
    const PieceKnots& knots = c.pieces.at(p);
    int wrapped = 0;
    for (int row : {0, 5})
        for (int column = 0; column < 12; ++column) {
            const RailHold& hold = c.system.hold[knots.at(row, column)];
            CHECK(hold.t >= 0);
            CHECK(hold.t < 1);
            // The unwrapped position, at + column step (reversed on the lower rail), is the
            // same point of the rail.
            const double unwrapped = row == 0 ? 0.9 + column / 12.0 : 0.3 - column / 12.0;
            wrapped += unwrapped < 0 || unwrapped >= 1;
            const Curve& rail = s.rail(hold.rail).curve();
            const Vec3 off = c.system.position[knots.at(row, column)] + c.system.origin -
                             rail.pointAt(unwrapped);
            CHECK(off.norm() < 1e-12);
        }
    CHECK(wrapped == 10 + 8); // columns 2-11 above (t from 1.067), 4-11 below (from -0.033)
}

TEST_CASE("a piece of one row is not tied to a rail by its last row, which is its top row") {
    TwoRings rings(16);
    Sculpture& s = rings.s;
    const RailId top = rings.top, bottom = rings.bottom;
    PieceId band = edit(s, [&](Sculpture& m) {
        return attachToRail(m, {top, 16, 0, 1, 0.6, 0, false});
    });
    PieceId tied = edit(s, [&](Sculpture& m) {
        return attachToRail(m, {top, 16, 0, 8, 0.6, 0.5, false});
    });
    edit(s, [&](Sculpture& m) {
        connectToRail(m, tied, bottom, 0, false);
        return 0;
    });
    const Sculpture before = s;
    const std::string needle = "has 1 row, so its last row is its top row";
    REQUIRE_THROWS_WITH(edit(s,
                             [&](Sculpture& m) {
                                 connectToRail(m, band, bottom, 0, false);
                                 return 0;
                             }),
                        Contains(toString(band) + " " + needle));
    REQUIRE_THROWS_WITH(edit(s,
                             [&](Sculpture& m) {
                                 setRows(m, tied, 1);
                                 return 0;
                             }),
                        Contains(toString(tied) + " " + needle));
    CHECK(sameModel(before, s));
    edit(s, [&](Sculpture& m) {
        setRows(m, tied, 2);
        return 0;
    });
    CHECK(s.piece(tied).rows == 2);
}

TEST_CASE("a sculpture far from (0, 0, 0) is compiled about the whole metre nearest its rails' "
          "centre, one about it where it stands") {
    const auto ringAt = [](const Vec3& centre) {
        Sculpture s;
        const RailId rail = edit(s, [&](Sculpture& m) {
            return addRail(m, "ring", ringRail(centre, 2.0, 16));
        });
        edit(s, [&](Sculpture& m) { return attachToRail(m, {rail, 16, 0, 6, 0.8, 0, false}); });
        return s;
    };
    Sculpture aroundZero = ringAt({0, 0, 0});
    const CompiledSculpture near = compileSculpture(aroundZero);
    CHECK(near.system.origin == Vec3{0, 0, 0});
    // A rail that holds nothing (another line of a site drawing) does not move it.
    edit(aroundZero, [](Sculpture& m) {
        return addRail(m, "kerb", lineRail({4000, 300, 0}, {4100, 300, 0}));
    });
    CHECK(compileSculpture(aroundZero).system.origin == Vec3{0, 0, 0});
    // Before any net is attached, the rails alone place it (the studio draws them from it).
    Sculpture railsOnly;
    edit(railsOnly, [](Sculpture& m) {
        return addRail(m, "kerb", lineRail({4000, 300, 0}, {4100, 300, 0}));
    });
    CHECK(chooseOrigin(railsOnly) == Vec3{4050, 300, 0});
    // Within 32 m per axis nothing moves: the positions are the sculpture's own, bit for bit.
    const Sculpture within = ringAt({31.5, -20.25, 12});
    const CompiledSculpture inPlace = compileSculpture(within);
    CHECK(inPlace.system.origin == Vec3{0, 0, 0});
    const Curve& inPlaceRing = within.rails.begin()->second.curve();
    for (std::size_t k = 0; k < inPlace.system.knotCount(); ++k)
        if (inPlace.system.fixed[k])
            CHECK(inPlace.system.position[k] == inPlaceRing.pointAt(inPlace.system.hold[k].t));

    const Vec3 site{-32.5, 512345.678, 1234.4};
    const Sculpture far = ringAt(site);
    const CompiledSculpture compiled = compileSculpture(far);
    const MassSpringSystem& sys = compiled.system;
    CHECK(sys.origin == Vec3{-33, 512346, 1234}); // -32.5 rounds away from 0
    const Curve& ring = far.rails.begin()->second.curve();
    double worst = 0, farthest = 0;
    for (std::size_t k = 0; k < sys.knotCount(); ++k) {
        farthest = std::max(farthest, sys.position[k].norm());
        worst = std::max(worst, distance(sys.worldPosition(k) - site, near.system.position[k]));
        if (sys.fixed[k]) // held where the rail is, to its coordinates' rounding (1.2e-10 m)
            CHECK(distance(sys.worldPosition(k), ring.pointAt(sys.hold[k].t)) < 2e-10);
    }
    CHECK(farthest < 8); // the ring and the net hanging from it, within a metre of the origin
    CHECK(worst < 1e-9);   // the net about (0, 0, 0), moved to the site
}

TEST_CASE("a piece reversed on an open rail runs from the rail's far end back to its start") {
    Sculpture s;
    const RailId rail = edit(s, [](Sculpture& m) {
        return addRail(m, "beam", lineRail({0, 0, 5}, {4, 0, 5}));
    });
    const PieceId forward =
        edit(s, [&](Sculpture& m) { return attachToRail(m, {rail, 11, 0, 3, 0.25, 0, false}); });
    const PieceId reversed =
        edit(s, [&](Sculpture& m) { return attachToRail(m, {rail, 11, 0, 3, 0.25, 0, true}); });
    const CompiledSculpture c = compileSculpture(s);
    for (int column = 0; column < 11; ++column) {
        const Vec3 f = c.system.position[c.knotOf(forward, 0, column)];
        const Vec3 r = c.system.position[c.knotOf(reversed, 0, column)];
        CHECK(f.x == Approx(0.4 * column).margin(1e-12));
        CHECK(r.x == Approx(4 - 0.4 * column).margin(1e-12));
    }
}

TEST_CASE("the compiler's bar pairs tell a bar met twice, in either order, past a knot's slots") {
    BarPairs pairs(20);
    // Knot 3's bars to eleven higher knots: the first four in its slots, the rest in the set.
    for (std::uint32_t k = 4; k < 15; ++k)
        CHECK(pairs.insert(3, k));
    for (std::uint32_t k = 4; k < 15; ++k) {
        INFO("knot " << k);
        CHECK_FALSE(pairs.insert(3, k));
        CHECK_FALSE(pairs.insert(k, 3));
    }
    CHECK(pairs.insert(4, 3 + 12)); // another knot's pair with the same higher end
    CHECK(pairs.insert(2, 3));      // knot 3 as the higher end
    CHECK_FALSE(pairs.insert(3, 2));
    CHECK(pairs.insert(0, 19));
    CHECK_FALSE(pairs.insert(19, 0));
}
