// The report's net-maker sections (io/ReportSections.h, ReportFabrication.cpp): which knot of
// which piece a child is knotted to, and every length its bars are knotted to, against numbers
// worked out by hand from DESIGN.md's rules.

#include "IoTestSupport.h"

#include "io/Report.h"
#include "io/ReportSections.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

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
    CHECK_THAT(csv, !Contains("column 6"));

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
