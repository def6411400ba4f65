// Rails from OBJ and CSV files (io/Import.h): round trips through exportRailsFile (DXF too), the
// file formats' rules (headers, rail column, closed rails, units) and bad files.

#include "IoTestSupport.h"

#include "geometry/Curve.h"
#include "io/Export.h"
#include "io/Import.h"
#include "io/ImportDetail.h"
#include "io/Scene.h"
#include "model/Error.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;

namespace {

Sculpture threeRails() {
    Sculpture s;
    edit(s, [](Sculpture& m) { return addRail(m, "ring top", polygonRail(7, 1.3, 2.5)); });
    edit(s, [](Sculpture& m) {
        CurveSpec open;
        open.points = {
            {0.1, 0.2, 0.3}, {1.0 / 3.0, 2.0 / 7.0, 1e-17}, {-4.5, 12345.678901234567, 6}};
        return addRail(m, "open, with comma", open);
    });
    edit(s, [](Sculpture& m) {
        CurveSpec spline;
        spline.spline = true;
        spline.degree = 3;
        spline.closed = true;
        for (int i = 0; i < 6; ++i)
            spline.points.push_back({std::cos(i * 1.0), std::sin(i * 1.0), 0.1 * i});
        return addRail(m, "spline", spline);
    });
    return s;
}

/// The points exportRailsFile writes for a rail (a closed rail's first point is not repeated).
std::vector<Vec3> exported(const Rail& rail) {
    return io::railPolyline(rail.curve(), false);
}

void checkRoundTrip(const Sculpture& s, const std::filesystem::path& file) {
    exportRailsFile(s, file);
    const auto rails = importRailsFile(file);
    REQUIRE(rails.size() == s.rails.size());
    std::size_t i = 0;
    for (const auto& [id, rail] : s.rails) {
        const NamedCurve& back = rails[i++];
        INFO(file.filename().string() << ": " << rail.name);
        CHECK(back.name == rail.name);
        CHECK(back.curve.closed == rail.curve().closed());
        const auto expected = exported(rail);
        REQUIRE(back.curve.points.size() == expected.size());
        for (std::size_t k = 0; k < expected.size(); ++k) {
            // Round-trip precision: the text reads back to the same doubles (1e-12 asked, 0 got).
            CHECK(distance(back.curve.points[k], expected[k]) <=
                  1e-12 * std::max(1.0, expected[k].norm()));
            CHECK(back.curve.points[k] == expected[k]);
        }
    }
}

/// Writes `text` to a file of that name in a folder of its own (test cases may run in parallel).
std::vector<NamedCurve> importText(const std::string& name, const std::string& text,
                                   const ImportOptions& options = {}) {
    const auto file = outputDir("rail-text-" + name) / name;
    writeText(file, text);
    return importRailsFile(file, options);
}

} // namespace

TEST_CASE("rails exported to CSV, OBJ and DXF read back to the same names, closure and points") {
    const Sculpture s = threeRails();
    const auto dir = outputDir("rail-round-trip");
    checkRoundTrip(s, dir / "rails.csv");
    checkRoundTrip(s, dir / "rails.OBJ");
    checkRoundTrip(s, dir / "rails.dxf");
    // A polyline rail is its own vertices, so it comes back as the same rail.
    const auto rails = importRailsFile(dir / "rails.csv");
    CHECK(rails[0].curve.points == s.rails.begin()->second.curve().spec().points);
    CHECK(Curve::build(rails[0].curve).length() ==
          Approx(s.rails.begin()->second.curve().length()).epsilon(1e-15));
}

TEST_CASE("CSV rails: one rail per file, or grouped by a rail column") {
    auto one = importText("single.csv", "0,0,0\n1,0,0\n# a comment\n\n1,2,0\n");
    REQUIRE(one.size() == 1);
    CHECK(one[0].name == "single");
    CHECK_FALSE(one[0].curve.closed);
    CHECK(one[0].curve.points.size() == 3);

    auto grouped = importText(
        "grouped.csv",
        "Z,rail,X,y\r\n1,b,0,0\r\n1,a,5,5\r\n1,b,1,0\r\n1,a,6,5\r\n1,\"a\",6,6\r\n1,a,5,5\r\n");
    REQUIRE(grouped.size() == 2);
    CHECK(grouped[0].name == "b");
    CHECK(grouped[1].name == "a");
    CHECK(grouped[1].curve.closed); // its last point repeats the first
    CHECK(grouped[1].curve.points.size() == 3);
    CHECK(grouped[0].curve.points[1] == Vec3{1, 0, 1});

    ImportOptions mm;
    mm.units = "mm";
    auto scaled = importText("mm.csv", "0,0,0\n1000,0,-250\n", mm);
    CHECK(scaled[0].curve.points[1] == Vec3{1, 0, -0.25});

    // Spreadsheets save CSV as UTF-8 with a byte-order mark before the first field.
    const std::string mark = "\xEF\xBB\xBF";
    auto excel = importText("excel.csv", mark + "rail,x,y,z\nedge,0,0,3\nedge,2,0,3\n");
    REQUIRE(excel.size() == 1);
    CHECK(excel[0].name == "edge");
    auto bare = importText("bare.csv", mark + "0,0,0\n1,0,0\n");
    REQUIRE(bare.size() == 1);
    CHECK(bare[0].curve.points[0] == Vec3{0, 0, 0});
}

TEST_CASE("A CSV coordinate too far out is refused naming its own line, not its rail's first") {
    // It said "rail 'b' (from line 3): has a coordinate of ...", the line where rail b starts.
    const std::string text = "rail,x,y,z\n"
                             "a,0,0,5\n"
                             "b,0,3,5\n"
                             "a,1,0,5\n"
                             "b,1,3,5\n"
                             "# a comment\n"
                             "a,2,0,5\n"
                             "b,2,3,5\n"
                             "b,3,3,-2.5e8\n"
                             "a,3,0,5\n";
    CHECK_THROWS_WITH(importText("far.csv", text),
                      EndsWith("far.csv:9: z is -2.5e+08 m, too large: rails must lie within "
                               "1e+08 m of the origin in x, y and z"));
    // In another unit, the limit is said in it too; the same numbers in mm are near.
    ImportOptions km;
    km.units = "km";
    CHECK_THROWS_WITH(importText("far-km.csv", "0,0,0\n1,0,0\n2,0,0\n3,2e5,0\n", km),
                      EndsWith("far-km.csv:4: y is 2e+05 (2e+08 m), too large: rails must lie "
                               "within 1e+08 m of the origin in x, y and z (1e+05 in the file's "
                               "units)"));
    ImportOptions mm;
    mm.units = "mm";
    CHECK(importText("far-mm.csv", text, mm)[1].curve.points[3] == Vec3{0.003, 0.003, -2.5e5});
}

TEST_CASE("An OBJ vertex too far out is refused naming its own line and the l that uses it") {
    // It named only the 'l' line ("line 8: has a coordinate of ..."), where no number is.
    const std::string text = "v 0 0 5\nv 1 0 5\n# far\nv 2 0 -2.5e8\nv 9e9 0 0\n"
                             "o edge\nl 1 2\nl 2 3\n";
    CHECK_THROWS_WITH(importText("far.obj", text),
                      EndsWith("far.obj:4: vertex 3, used by the 'l' on line 8: z is -2.5e+08 m, "
                               "too large: rails must lie within 1e+08 m of the origin in x, y "
                               "and z"));
    // A vertex no 'l' uses is no rail's: vertex 4 is as far, and the rail without vertex 3 reads.
    CHECK(importText("near.obj", "v 0 0 5\nv 1 0 5\nv 9e9 0 0\nl 1 2\n")[0].curve.points ==
          std::vector<Vec3>{{0, 0, 5}, {1, 0, 5}});
}

TEST_CASE("OBJ rails: l elements, named by their object, closed when they end where they start") {
    auto rails = importText("net.obj", "# test\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 0.5 0.5 0.5\n"
                                       "o loop\nl 1 2 3 4 1\no pair\nl 1 3\nl -1 -2/7\n");
    REQUIRE(rails.size() == 2);
    CHECK(rails[0].name == "loop");
    CHECK(rails[0].curve.closed);
    CHECK(rails[0].curve.points.size() == 4);
    // "l 1 3" and "l 4 3" share vertex 3: one rail, from the first element's direction.
    CHECK(rails[1].name == "pair");
    CHECK(rails[1].curve.points == std::vector<Vec3>{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}});

    auto apart = importText("apart.obj", "v 0 0 0\nv 1 0 0\nv 5 0 0\nv 6 0 0\nl 1 2\nl 3 4\n");
    REQUIRE(apart.size() == 2);
    CHECK(apart[0].name == "apart#1");
    CHECK(apart[1].name == "apart#2");
}

TEST_CASE("OBJ rails written one edge per l element (as Blender does) are chained") {
    // A square of side 2, its edges out of order and one reversed: one closed rail, 8 long.
    auto rails = importText("edges.obj", "o Ring\nv 0 0 1\nv 2 0 1\nv 2 2 1\nv 0 2 1\n"
                                         "l 1 2\nl 3 4\nl 3 2\nl 4 1\n");
    REQUIRE(rails.size() == 1);
    CHECK(rails[0].name == "Ring");
    CHECK(rails[0].curve.closed);
    CHECK(rails[0].curve.points ==
          std::vector<Vec3>{{0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}});
    CHECK(Curve::build(rails[0].curve).length() == 8);
    // Three edges at one vertex: a rail cannot branch.
    CHECK_THROWS_WITH(importText("branch.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\n"
                                               "l 1 2\nl 1 3\nl 1 4\n"),
                      Contains("3 ends meet at (0, 0, 0)") && Contains("line 5, line 6, line 7") &&
                          Contains("different objects"));
}

TEST_CASE("bad CSV and OBJ files give an error with the file and line, and no rails") {
    const auto fails = [](const std::string& name, const std::string& text,
                          const std::string& what) {
        INFO(name);
        CHECK_THROWS_WITH(importText(name, text), Contains(name) && Contains(what));
    };
    fails("nan.csv", "0,0,0\n1,nan,0\n", ":2: y is 'nan'");
    fails("word.csv", "0,0,0\n1,two,0\n", ":2: y 'two' is not a number");
    fails("range.csv", "0,0,0\n1e400,0,0\n", ":2: x '1e400' is out of range: too large");
    fails("far.csv", "0,0,0\n2e8,0,0\n",
          ":2: x is 2e+08 m, too large: rails must lie within 1e+08 m");
    fails("short.csv", "0,0,0\n1,0\n", ":2: 2 fields, expected 3");
    fails("header.csv", "a,b,c\n1,2,3\n", ":1: the header 'a,b,c' has a column 'a'");
    fails("knots.csv", "piece,row,column,x,y,z,fixed\n1,0,0,0,0,3,1\n",
          "has a column 'piece'; a rail file's columns are x, y, z and optionally rail");
    fails("extra.csv", "rail,x,y,z,extra\na,0,0,0,1\n", "has a column 'extra'");
    fails("twice.csv", "x,y,z,X\n0,0,0,1\n", "twice the column 'x'");
    fails("partial.csv", "rail,x,y\na,0,0\n", "must name columns x, y and z");
    fails("empty.csv", "", "holds no points");
    fails("one.csv", "1,2,3\n", "2 distinct points");
    fails("binary.csv", std::string("0,0,0\n\0\x01,2\n", 11), "binary data");
    fails("ref.obj", "v 0 0 0\nv 1 0 0\nl 1 3\n",
          ":3: vertex reference '3' does not name one of the 2 vertices");
    fails("inf.obj", "v 0 0 0\nv 1 inf 0\nl 1 2\n", ":2: y is 'inf'");
    fails("none.obj", "v 0 0 0\nv 1 0 0\n", "no polylines");
    fails("rails.txt", "0,0,0\n", ".dxf, .obj and .csv");
    CHECK_THROWS_WITH(importRailsFile(outputDir("rail-missing") / "missing.csv"),
                      Contains("missing.csv") && Contains("cannot open"));
    ImportOptions furlongs;
    furlongs.units = "furlong";
    CHECK_THROWS_WITH(importText("units.csv", "0,0,0\n1,0,0\n", furlongs),
                      Contains("furlong") && Contains("mm"));
}

TEST_CASE("OBJ rails of many edges written out of order chain into one rail") {
    // A helix of 2,000 edges in a shuffled order: one open rail of 2,001 points from its first
    // vertex. (The grid that finds each end's partner made 40,000 edges take 0.26 s instead of
    // 14.7 s, measured by hand in a Release build: a speed, not a unit test's business.)
    const int edges = 2000;
    std::string text;
    for (int i = 0; i <= edges; ++i) {
        const double t = 0.01 * i;
        text += "v " + std::to_string(3 * std::cos(t)) + " " + std::to_string(3 * std::sin(t)) +
                " " + std::to_string(0.0005 * i) + "\n";
    }
    for (int k = 0; k < edges; ++k) {
        const int i = int((7919LL * k) % edges); // 7919 is prime to 2000: every edge once
        text += "l " + std::to_string(i + 1) + " " + std::to_string(i + 2) + "\n";
    }
    const auto rails = importText("helix.obj", text);
    REQUIRE(rails.size() == 1);
    CHECK_FALSE(rails[0].curve.closed);
    CHECK(rails[0].curve.points.size() == std::size_t(edges + 1));
    CHECK(rails[0].curve.points.front() == Vec3{3, 0, 0});
}

TEST_CASE("OBJ: a piece shorter than the join tolerance is contracted, not a gap") {
    // Extent 20: tolerance 2e-5. The middle edge is 1.5e-5 long and each gap 1.5e-5; its
    // neighbours' ends are 4.5e-5 apart, so they must be joined through it: one rail
    // (0,0,0) (10,0,0) (20,0,0) (the third edge's first point dropped at the join).
    const auto rails = importText("slip.obj", "v 0 0 0\nv 10 0 0\nv 10.000015 0 0\nv 10.00003 0 0\n"
                                              "v 10.000045 0 0\nv 20 0 0\nl 1 2\nl 3 4\nl 5 6\n");
    REQUIRE(rails.size() == 1);
    CHECK_FALSE(rails[0].curve.closed);
    CHECK(rails[0].curve.points == std::vector<Vec3>{{0, 0, 0}, {10, 0, 0}, {20, 0, 0}});
}

TEST_CASE("OBJ: many pieces shorter than the join tolerance crowded into one spot") {
    // A fuzzed OBJ of thousands of zero-length edges at one vertex took time growing with the
    // square of their number (each end was compared with every other). Edges at the same points
    // are compared once: 2,000 of them at the first vertex leave the one rail as it is.
    std::string repeated = "v 0 0 0\nv 1 0 0\nl 1 2\n";
    for (int k = 0; k < 2000; ++k)
        repeated += "l 1 1\n";
    const auto rails = importText("repeated.obj", repeated);
    REQUIRE(rails.size() == 1);
    CHECK(rails[0].curve.points == std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}});
    // Extent 1: tolerance 1e-6. 40 edges 1e-9 long, each at its own points, put 80 different
    // ends into one cube 1e-6 wide: more than the 64 that are joined there.
    std::string crowded = "v 0 0 0\nv 1 0 0\nl 1 2\n";
    for (int k = 0; k < 80; ++k)
        crowded += "v " + std::to_string(k) + "e-9 0 0\n";
    for (int k = 0; k < 40; ++k)
        crowded += "l " + std::to_string(2 * k + 3) + " " + std::to_string(2 * k + 4) + "\n";
    CHECK_THROWS_WITH(importText("crowded.obj", crowded),
                      Contains("crowded.obj: more than 64 ends of pieces at different points lie "
                               "within 1e-06 of one another near (0, 0, 0) (line ") &&
                          Contains("remove the pieces shorter than 1e-06"));
}

TEST_CASE("a coordinate that is not a number is called so, not too large") {
    const std::vector<Vec3> points{{0, 0, 0}, {std::nan(""), 1, 2}};
    CHECK_THROWS_WITH(io::checkCoordinates("rails.dxf", "LINE 2F on layer R (line 9)", points, 1),
                      Contains("rails.dxf: LINE 2F on layer R (line 9): has a coordinate that is "
                               "not a number") &&
                          !Contains("too large"));
    // Infinity is beyond any limit: still too large, with the limit.
    const std::vector<Vec3> far{{0, 0, HUGE_VAL}};
    CHECK_THROWS_WITH(io::checkCoordinates("rails.dxf", "x", far, 1), Contains("too large"));
}
