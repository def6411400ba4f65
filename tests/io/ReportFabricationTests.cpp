// The report's net-maker sections (io/ReportSections.h, ReportFabrication.cpp): which knot of
// which piece a child is knotted to, and every length its bars are knotted to, against numbers
// worked out by hand from DESIGN.md's rules.

#include "IoTestSupport.h"

#include "io/Report.h"
#include "io/ReportSections.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
using nlohmann::json;

namespace {

/// A ring of 12 columns and 5 rows (bars 0.4 m) on a 48-point circle of radius 1 m, a gear-1
/// child of 3 rows (bars 0.5 m) below it, the ring split at column 4 into parts of 5 and 9
/// columns: the left part keeps the ring's id.
struct SplitRing {
    Sculpture s;
    PieceId left, right, child;
};
SplitRing splitRingWithChild() {
    SplitRing t;
    const RailId rail = edit(t.s, [](Sculpture& s) {
        return addRail(s, "ring", ringRail({0, 0, 5}, 1.0, 48));
    });
    t.left = edit(t.s, [&](Sculpture& s) { return attachToRail(s, {rail, 12, 0, 5, 0.4}); });
    t.child = edit(t.s, [&](Sculpture& s) {
        return attachToPiece(s, {t.left, Gear{1, 1}, 3, 0.5});
    });
    t.right = edit(t.s, [&](Sculpture& s) { return split(s, t.left, 4).second; });
    return t;
}

/// The rest length of the bar between knots a and b (0 when there is none).
double restLengthBetween(const MassSpringSystem& sys, std::uint32_t a, std::uint32_t b) {
    for (std::size_t i = 0; i < sys.barCount(); ++i)
        if ((sys.barA[i] == a && sys.barB[i] == b) || (sys.barA[i] == b && sys.barB[i] == a))
            return sys.restLength[i];
    return 0;
}

const json& pieceOf(const json& report, PieceId id) {
    return reportPiece(report, json(id.value));
}

} // namespace

TEST_CASE("the report numbers the joined row of split parents as the child hangs from it") {
    // Parts of 5 and 9 columns on one row: the cut's seam knot once, the ring's seam knot once
    // (the right part's column 8 is the left part's column 0), 5 + 9 - 2 = 12 knots.
    SplitRing even = splitRingWithChild();
    json r = buildReport(even.s, compileSculpture(even.s));
    const json& top = pieceOf(r, even.child)["top"];
    CHECK(top["joined_knots"] == 12);
    REQUIRE(top["joined_row"].size() == 2);
    CHECK(top["joined_row"][1]["first_column"] == 1);
    CHECK(top["joined_row"][1]["last_column"] == 7);
    CHECK(top["joined_row"][1]["first_knot"] == 5);
    CHECK_THAT(reportMarkdown(r),
               Contains("(12 knots: 0 to 4 are knots (4, 0) to (4, 4) of piece 1, 5 to 11 are "
                        "knots (4, 1) to (4, 7) of piece 3; a seam knot counted once, in the part "
                        "before it, round the ring"));

    // The right part one row longer: its last row is row 5, the seam knots of the two last rows
    // are different knots, so the row has 5 + 9 = 14 and the child 14 columns (gear 1).
    SplitRing step = splitRingWithChild();
    edit(step.s, [&](Sculpture& s) {
        setRows(s, step.right, 6);
        return 0;
    });
    r = buildReport(step.s, compileSculpture(step.s));
    const json& child = pieceOf(r, step.child);
    CHECK(child["columns"] == 14);
    CHECK(child["top"]["joined_knots"] == 14);
    const std::string md = reportMarkdown(r);
    CHECK_THAT(md, Contains("(14 knots: 0 to 4 are knots (4, 0) to (4, 4) of piece 1, 5 to 13 "
                            "are knots (5, 0) to (5, 8) of piece 3, round the ring"));
    CHECK_THAT(md, !Contains("12 knots"));
}

TEST_CASE("the report gives where a split child starts in its parent's knots") {
    // The ring of 12 columns and 5 rows with its gear-2 child of 24 columns: child column v of
    // the whole row is the ring's knot (4, v / 2) when v is even, a new knot after (4, v / 2)
    // when odd. The child split at 6 starts at (4, 3), not at "column 6" of a 12-knot row.
    Tube even = tubeWithChild(12, 5, 1.0, 0.4);
    edit(even.s, [&](Sculpture& s) { return split(s, even.child, 6); });
    std::string csv = reportPiecesCsv(buildReport(even.s, compileSculpture(even.s)));
    CHECK_THAT(csv, Contains(",\"piece 1, gear 2, from knot (4, 3) of piece 1\","));
    CHECK_THAT(csv, !Contains("from column 6"));

    Tube odd = tubeWithChild(12, 5, 1.0, 0.4);
    edit(odd.s, [&](Sculpture& s) { return split(s, odd.child, 5); });
    csv = reportPiecesCsv(buildReport(odd.s, compileSculpture(odd.s)));
    CHECK_THAT(csv,
               Contains(",\"piece 1, gear 2, from the new knot after knot (4, 2) of piece 1\","));

    // Gear 3 (36 columns) split at 7: 7 = 3 x 2 + 1, the first of the two new knots after (4, 2).
    Tube three = tubeWithChild(12, 5, 1.0, 0.4);
    edit(three.s, [&](Sculpture& s) {
        setGear(s, three.child, Gear{3, 1});
        return 0;
    });
    edit(three.s, [&](Sculpture& s) { return split(s, three.child, 7); });
    const std::string md = reportMarkdown(buildReport(three.s, compileSculpture(three.s)));
    CHECK_THAT(
        md, Contains("| piece 1, gear 3, from the first new knot after knot (4, 2) of piece 1 |"));
}

TEST_CASE("the report gives the length of a gear's bars in a graded child") {
    // The gear-2 child (24 columns, 3 rows) graded by row, 0.3 m at row 0 to 0.4 m at row 2:
    // 48 bars of 0.325 between rows 0 and 1, 48 of 0.375 between rows 1 and 2, and the 12 new
    // knots of row 0 hang by 2 bars each of row 0's 0.3 m. Rope by hand: 15.6 + 18 + 7.2 m.
    Tube t = tubeWithChild(12, 5, 1.0, 0.4);
    edit(t.s, [&](Sculpture& s) {
        setBarLengthByRow(s, t.child, 0, 0.3);
        setBarLengthByRow(s, t.child, 2, 0.4);
        return 0;
    });
    const CompiledSculpture c = compileSculpture(t.s);
    const json r = buildReport(t.s, c);
    const json& child = reportPiece(r, json(t.child.value));
    CHECK(child["bars"] == 48 + 48 + 24);
    CHECK(child["rope_length"].get<double>() == Approx(15.6 + 18 + 7.2).epsilon(1e-14));
    std::size_t gearBars = 0;
    for (std::size_t b = 0; b < c.system.barCount(); ++b)
        gearBars += c.system.barPiece[b] == t.child && c.system.restLength[b] == 0.3 ? 1 : 0;
    CHECK(gearBars == 24);
    const std::string md = reportMarkdown(r);
    CHECK_THAT(md, Contains("| 0 (the gear's new knots to the knots above) | 0.3 |\n"
                            "| 0 to 1 | 0.325 |\n"));
    CHECK_THAT(md, Contains("the knot between two of them is new, tied by one bar of 0.3 m to "
                            "each of the two."));
    CHECK_THAT(md, Contains("| 0.325 between rows 0 and 1 to 0.375 between rows 1 and 2, 0.3 in "
                            "row 0 (the gear's new knots) |"));
    CHECK_THAT(reportPiecesCsv(r), Contains(",row,0.3,0.375,")); // bar_min, bar_max

    // Graded by column (a split part, 0.25 m at column 0 to 0.35 m at its last, 12): a new knot
    // hangs by bars of its own column's length, 0.25 + 0.1 x c / 12, which its table lists.
    Tube split = tubeWithChild(12, 5, 1.0, 0.4);
    const PieceId part = edit(split.s, [&](Sculpture& s) {
        netsculpt::split(s, split.child, 12);
        setBarLength(s, split.child, 12, 0.35);
        return split.child;
    });
    const CompiledSculpture cs = compileSculpture(split.s);
    // Its knot (0, 3) is new, between the ring's knots (4, 1) and (4, 2).
    const std::uint32_t newKnot = cs.knotOf(part, 0, 3);
    for (int column : {1, 2})
        CHECK(restLengthBetween(cs.system, newKnot, cs.knotOf(split.piece, 4, column)) ==
              Approx(0.25 + 0.1 * 3 / 12).epsilon(1e-14));
    const std::string partMd = reportMarkdown(buildReport(split.s, cs));
    CHECK_THAT(partMd, Contains("| 3 | 0.275 | 0.279167 |"));
    CHECK_THAT(partMd, Contains("Row 0's new knots (gear 2) hang from the knots above by bars of "
                                "their own column's length (bars within the column)."));
    CHECK_THAT(partMd, Contains("tied by one bar of its column's length (Bar lengths below)"));
}

TEST_CASE("the report says where each rail starts and which way its distances run") {
    // A straight rail from (0, 0, 0) to (0.8, 0, 0): its start, and +x.
    SheetNet t = sheet(4, 3, 0.8, 0.3);
    json r = buildReport(t.s, t.compiled);
    CHECK(r["rails"][0]["start"] == json({{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}));
    CHECK(r["rails"][0]["direction"]["x"].get<double>() == Approx(1).epsilon(1e-15));
    CHECK_THAT(reportMarkdown(r),
               Contains("### Rail 1 (bar)\n\nDistances along the rail are measured from its start, "
                        "(0.0000, 0.0000, 0.0000) m, the way it runs from there: towards (1, 0, 0) "
                        "(a unit vector).\n"));

    // A ring of 10 corners, radius 0.8 m at z = 2: corner 0 at (0.8, 0, 2), its first side
    // towards corner 1 at 36 degrees, a chord at 90 + 18 = 108 degrees from +x.
    Sculpture s;
    const RailId rail =
        edit(s, [](Sculpture& x) { return addRail(x, "ring", polygonRail(10, 0.8, 2.0)); });
    edit(s, [&](Sculpture& x) { return attachToRail(x, {rail, 10, 0, 6, 0.3}); });
    r = buildReport(s, compileSculpture(s));
    const double pi = std::acos(-1.0), angle = 108 * pi / 180;
    const json& ring = r["rails"][0];
    CHECK(ring["start"]["x"].get<double>() == Approx(0.8).epsilon(1e-15));
    CHECK(ring["start"]["z"].get<double>() == Approx(2).epsilon(1e-15));
    CHECK(ring["direction"]["x"].get<double>() == Approx(std::cos(angle)).epsilon(1e-12));
    CHECK(ring["direction"]["y"].get<double>() == Approx(std::sin(angle)).epsilon(1e-12));
    CHECK_THAT(reportMarkdown(r), Contains("from its start, (0.8000, 0.0000, 2.0000) m, the way it "
                                           "runs from there: towards (-0.309017, 0.951057, 0) (a "
                                           "unit vector), and round the ring back to its start."));
}

TEST_CASE("the report says which columns of two pieces a seam joins, down to which row") {
    // The ring of 12 columns split at 4: the left part (columns 0 to 4 of the ring, 5 columns)
    // meets the right part (ring columns 4 to 12 = 0, 9 columns) at its column 4 = their column
    // 0, and at its column 0 = their column 8, in all 5 rows.
    Tube t = tubeWithChild(12, 5, 1.0, 0.4);
    const PieceId right = edit(t.s, [&](Sculpture& s) { return split(s, t.piece, 4).second; });
    json r = buildReport(t.s, compileSculpture(t.s));
    const json& seams = reportPiece(r, json(t.piece.value))["seams"];
    REQUIRE(seams.size() == 2);
    for (const json& seam : seams) {
        const bool toTheRight = seam["side"] == "right";
        CHECK(seam["column"] == (toTheRight ? 4 : 0));
        CHECK(seam["other_column"] == (toTheRight ? 0 : 8));
        CHECK(seam["rows"] == 5);
    }
    const std::string id = std::to_string(right.value);
    CHECK_THAT(reportMarkdown(r), Contains("piece " + id +
                                           " to the right: its column 4, rows 0 to "
                                           "4, is column 0 of piece " +
                                           id + " (the 4 bars"));
    CHECK_THAT(reportMarkdown(r), Contains("piece 1 to the right: its column 8, rows 0 to 4, is "
                                           "column 0 of piece 1 (the 4 bars"));

    // The right part one row longer shares the seam's knots down to the left part's row 4.
    edit(t.s, [&](Sculpture& s) {
        setRows(s, right, 6);
        return 0;
    });
    r = buildReport(t.s, compileSculpture(t.s));
    CHECK_THAT(reportMarkdown(r), Contains("piece 1 to the left: its column 0, rows 0 to 4, is "
                                           "column 4 of piece 1 (the 4 bars"));
}
