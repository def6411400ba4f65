// DXF block references read through their transform, and the layers that are read
// (io/Import.h). Fixtures: tools/fixtures/make_dxf_fixtures.py (ezdxf); the numbers below are
// computed by hand from the fixtures' comments (ezdxf's virtual_entities() agrees with them).

#include "IoTestSupport.h"

#include "geometry/Curve.h"
#include "io/DxfBlocks.h"
#include "io/Import.h"
#include "model/Error.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;

namespace {

std::vector<NamedCurve> dxf(const std::string& name, const ImportOptions& options = {}) {
    return importRailsFile(dataDir() / "dxf" / name, options);
}

std::string withBlock(const std::string& block, const std::string& entities) {
    return "0\nSECTION\n2\nBLOCKS\n" + block + "0\nENDSEC\n0\nSECTION\n2\nENTITIES\n" + entities +
           "0\nENDSEC\n0\nEOF\n";
}

const std::string kLineBlock = "0\nBLOCK\n8\n0\n2\nB\n70\n0\n10\n0\n20\n0\n30\n0\n"
                               "0\nLINE\n8\n0\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n"
                               "0\nENDBLK\n8\n0\n";

std::string insert(const std::string& block, const std::string& more = "") {
    return "0\nINSERT\n5\nA1\n8\nI\n2\n" + block + "\n10\n0\n20\n0\n30\n0\n" + more;
}

/// Blocks B0 (holding `bottom`'s entities) to B6, each of B1 to B6 inserting the block below
/// ten times, side by side along x.
std::string tenfoldBlocks(const std::string& bottom) {
    const auto header = [](int level) {
        return "0\nBLOCK\n8\n0\n2\nB" + std::to_string(level) + "\n70\n0\n10\n0\n20\n0\n30\n0\n";
    };
    std::string blocks = header(0) + bottom + "0\nENDBLK\n8\n0\n";
    for (int level = 1; level <= 6; ++level) {
        blocks += header(level);
        for (int copy = 0; copy < 10; ++copy)
            blocks += "0\nINSERT\n8\n0\n2\nB" + std::to_string(level - 1) + "\n10\n" +
                      std::to_string(copy) + "\n20\n0\n30\n0\n";
        blocks += "0\nENDBLK\n8\n0\n";
    }
    return blocks;
}

} // namespace

TEST_CASE("DXF INSERT: a block's rails are placed by scale, rotation, base point and extrusion") {
    const auto rails = dxf("blocks.dxf");
    REQUIRE(rails.size() == 4);
    // Scaled (2, 3) from the base point (1, 1), turned 90 degrees, moved to (10, 0, 5).
    const NamedCurve& turned = rails[0];
    CHECK_THAT(turned.name, Contains("INS:") && Contains("/RING:"));
    CHECK(turned.curve.closed);
    REQUIRE(turned.curve.points.size() == 4);
    const std::vector<Vec3> square{{10, 0, 5}, {10, 2, 5}, {7, 2, 5}, {7, 0, 5}};
    for (std::size_t i = 0; i < 4; ++i)
        CHECK(distance(turned.curve.points[i], square[i]) < 1e-12);
    CHECK(Curve::build(turned.curve).length() == Approx(10).epsilon(1e-14));
    // Extrusion (0, 0, -1): the OCS maps (x, y, z) to (-x, y, -z).
    const NamedCurve& mirrored = rails[1];
    CHECK_THAT(mirrored.name, Contains("MIRROR:") && Contains("/RING:"));
    const std::vector<Vec3> below{{-1, 0, -2}, {-2, 0, -2}, {-2, 1, -2}, {-1, 1, -2}};
    REQUIRE(mirrored.curve.points.size() == 4);
    for (std::size_t i = 0; i < 4; ++i)
        CHECK(distance(mirrored.curve.points[i], below[i]) < 1e-12);
    // Nested: an ARC of block HOOK inside block PAIR, turned 180 degrees, moved to (0, 20, 0).
    const NamedCurve& hook = rails[2];
    CHECK_THAT(hook.name, Contains("OUTER:") && Contains("/PAIR:") && Contains("/HOOK:"));
    CHECK_FALSE(hook.curve.closed);
    CHECK(distance(hook.curve.points.front(), {-1, 20, 0}) < 1e-12);
    CHECK(distance(hook.curve.points.back(), {0, 19, 0}) < 1e-12);
    for (const Vec3& p : hook.curve.points)
        CHECK(distance(p, {0, 20, 0}) == Approx(1).epsilon(1e-12));
    CHECK(Curve::build(hook.curve).length() == Approx(std::numbers::pi / 2).epsilon(1e-5));
    CHECK_THAT(rails[3].name, Contains("PLAIN:"));
}

TEST_CASE("DXF INSERT: what cannot be placed is refused naming the INSERT and the block") {
    const auto dir = outputDir("dxf-inserts");
    ImportOptions metres;
    metres.units = "m";
    const auto fails = [&](const std::string& name, const std::string& text,
                           std::initializer_list<std::string> parts) {
        INFO(name);
        writeText(dir / name, text);
        try {
            importRailsFile(dir / name, metres);
            FAIL("no error");
        } catch (const UserError& e) {
            const std::string message = e.what();
            INFO(message);
            for (const auto& part : parts)
                CHECK_THAT(message, Contains(part));
        }
    };
    fails("minsert.dxf", withBlock(kLineBlock, insert("B", "70\n3\n71\n2\n44\n5\n45\n5\n")),
          {"INSERT A1 on layer I", "3 columns by 2 rows of block 'B'", "MINSERT", "explode"});
    fails("missing.dxf", withBlock(kLineBlock, insert("C")),
          {"INSERT A1", "block 'C', which the file does not define", "explode"});
    fails("flat.dxf", withBlock(kLineBlock, insert("B", "41\n1\n42\n0\n")),
          {"INSERT A1", "scale of 0 (x 1, y 0, z 1)"});
    const std::string loop = "0\nBLOCK\n8\n0\n2\nL\n10\n0\n20\n0\n30\n0\n"
                             "0\nINSERT\n8\n0\n2\nL\n10\n1\n20\n0\n30\n0\n0\nENDBLK\n";
    fails("loop.dxf", withBlock(loop, insert("L")), {"inserts block 'L' inside itself"});
    const std::string ellipse = "0\nBLOCK\n8\n0\n2\nE\n10\n0\n20\n0\n30\n0\n"
                                "0\nELLIPSE\n8\n0\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n"
                                "40\n0.5\n0\nENDBLK\n";
    fails("ellipse.dxf", withBlock(ellipse, insert("E")),
          {"ELLIPSE on layer 0", "in block E, inserted by INSERT A1 on layer I", "convert it"});
    // A block that is not inserted is not drawn: its ELLIPSE is no reason to refuse the file.
    writeText(dir / "unused.dxf",
              withBlock(ellipse, "0\nLINE\n8\nR\n10\n0\n20\n0\n30\n0\n11\n2\n21\n0\n31\n0\n"));
    CHECK(importRailsFile(dir / "unused.dxf", metres).size() == 1);
    // The block's LINE on layer 0 takes the INSERT's layer I; x scale 3 makes it 3 long.
    writeText(dir / "scaled.dxf", withBlock(kLineBlock, insert("B", "41\n3\n")));
    const auto scaled = importRailsFile(dir / "scaled.dxf", metres);
    REQUIRE(scaled.size() == 1);
    CHECK(scaled[0].name == "I:A1/B:#1");
    CHECK(scaled[0].curve.points == std::vector<Vec3>{{0, 0, 0}, {3, 0, 0}});
    // A scale of 1e-200 shrinks the 1 m LINE to 1e-200 m, too short to measure: the INSERT and its
    // scale are named.
    fails("tiny.dxf", withBlock(kLineBlock, insert("B", "41\n1e-200\n42\n1e-200\n43\n1e-200\n")),
          {"LINE on layer 0", "inserted by INSERT A1 on layer I",
           "with a scale of x 1e-200, y 1e-200, z 1e-200", "2 distinct points"});
}

TEST_CASE("DXF layers: frozen, off and Defpoints are not read - layers = {...} chooses") {
    const auto drawn = dxf("layers.dxf");
    REQUIRE(drawn.size() == 1);
    CHECK_THAT(drawn[0].name, Contains("RAIL:"));
    CHECK(drawn[0].curve.closed);

    ImportOptions chosen;
    chosen.layers = {"helper", "Defpoints"}; // without case, as CAD programs compare them
    const auto helpers = dxf("layers.dxf", chosen);
    REQUIRE(helpers.size() == 3);
    CHECK_THAT(helpers[0].name, Contains("HELPER:"));
    CHECK(helpers[0].curve.points == std::vector<Vec3>{{-5, 0, 0}, {5, 0, 0}});
    CHECK_THAT(helpers[1].name, Contains("Defpoints:"));
    // The INSERT on HELPER: its LINE (0,0,0)-(0,0,1) moved to (3, 3, 0).
    CHECK_THAT(helpers[2].name, Contains("HELPER:") && Contains("/B:"));
    CHECK(helpers[2].curve.points == std::vector<Vec3>{{3, 3, 0}, {3, 3, 1}});

    ImportOptions unknown;
    unknown.layers = {"RAIL", "RAILZ"};
    CHECK_THROWS_WITH(dxf("layers.dxf", unknown),
                      Contains("layers.dxf") && Contains("the layer 'RAILZ'") &&
                          Contains("its layers are 0, Defpoints, HELPER, HIDDEN, RAIL"));

    const auto dir = outputDir("dxf-layers");
    ImportOptions metres;
    metres.units = "m";
    writeText(dir / "rails.csv", "0,0,0\n1,0,0\n");
    metres.layers = {"RAIL"};
    CHECK_THROWS_WITH(importRailsFile(dir / "rails.csv", metres),
                      Contains("rails.csv") && Contains("layers selects the layers of a DXF"));
}

TEST_CASE("DXF INSERT: copies multiplied through nested blocks are counted before placing") {
    // B0 holds one LINE (2 points); B1 to B6 each insert the block below ten times, so the
    // INSERT of B6 would place 10^6 LINEs: 2,000,000 points, twice the budget.
    const std::string blocks =
        tenfoldBlocks("0\nLINE\n8\n0\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n");
    const auto dir = outputDir("dxf-insert-budget");
    ImportOptions metres;
    metres.units = "m";
    writeText(dir / "copies.dxf", withBlock(blocks, insert("B6")));
    CHECK(io::kMaxInsertedPoints == 1'000'000);
    CHECK_THROWS_WITH(importRailsFile(dir / "copies.dxf", metres),
                      Contains("copies.dxf: INSERT A1 on layer I") &&
                          Contains("places 2000000 points through block 'B6'") &&
                          Contains("at most 1000000 points through block references"));
    // An INSERT of B5 places 2 * 10^5 points: five fill the budget exactly, the sixth passes it.
    std::string six;
    for (int copy = 0; copy < 6; ++copy)
        six += "0\nINSERT\n5\nC" + std::to_string(copy) + "\n8\nI\n2\nB5\n10\n0\n20\n0\n30\n0\n";
    writeText(dir / "six.dxf", withBlock(blocks, six));
    CHECK_THROWS_WITH(importRailsFile(dir / "six.dxf", metres),
                      Contains("INSERT C5 on layer I") &&
                          Contains("places 200000 points through block 'B5'") &&
                          Contains("1000000 more through the INSERTs before it"));
}

TEST_CASE("DXF INSERT: block references nested in blocks are counted before placing") {
    // A fuzzed DXF: blocks that insert the next one ten times, sixteen deep, with no entity in
    // the last, placed no point but 10^16 block references. Here B0 is empty and B1 to B6 each
    // insert the block below ten times: the INSERT of B6 places 1,111,110 references.
    const std::string blocks = tenfoldBlocks("");
    const auto dir = outputDir("dxf-insert-references");
    ImportOptions metres;
    metres.units = "m";
    writeText(dir / "empty.dxf", withBlock(blocks, insert("B6")));
    CHECK(io::kMaxInsertedReferences == 1'000'000);
    CHECK_THROWS_WITH(importRailsFile(dir / "empty.dxf", metres),
                      Contains("empty.dxf: INSERT A1 on layer I") &&
                          Contains("places 1111110 block references through block 'B6'") &&
                          Contains("at most 1000000 block references through block references"));
    // B5 places 111,110 references: nine INSERTs of it stay within the budget, a tenth does not.
    std::string nine;
    for (int copy = 0; copy < 9; ++copy)
        nine += "0\nINSERT\n5\nC" + std::to_string(copy) + "\n8\nI\n2\nB5\n10\n0\n20\n0\n30\n0\n";
    const std::string line = "0\nLINE\n8\nR\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n";
    writeText(dir / "ten.dxf", withBlock(blocks, nine + insert("B5") + line));
    CHECK_THROWS_WITH(importRailsFile(dir / "ten.dxf", metres),
                      Contains("INSERT A1 on layer I") &&
                          Contains("places 111110 block references through block 'B5'") &&
                          Contains("999990 more through the INSERTs before it"));
}

TEST_CASE("DXF: an entity that cannot be a rail is refused only when its layer is read") {
    const auto dir = outputDir("dxf-unread-refusals");
    const std::string table = "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n"
                              "0\nLAYER\n2\nDECOR\n70\n1\n62\n7\n0\nENDTAB\n0\nENDSEC\n";
    const std::string ellipse = "0\nELLIPSE\n8\nDECOR\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n"
                                "40\n0.5\n";
    const std::string line = "0\nLINE\n8\nR\n10\n0\n20\n0\n30\n0\n11\n2\n21\n0\n31\n0\n";
    const std::string block =
        "0\nBLOCK\n8\n0\n2\nE\n70\n0\n10\n0\n20\n0\n30\n0\n" + ellipse + "0\nENDBLK\n8\n0\n";
    ImportOptions metres;
    metres.units = "m";
    // Model space: the ELLIPSE is on the frozen layer DECOR, and then on a layer not chosen.
    writeText(dir / "frozen.dxf",
              table + "0\nSECTION\n2\nENTITIES\n" + ellipse + line + "0\nENDSEC\n0\nEOF\n");
    const auto drawn = importRailsFile(dir / "frozen.dxf", metres);
    REQUIRE(drawn.size() == 1);
    CHECK(drawn[0].curve.points == std::vector<Vec3>{{0, 0, 0}, {2, 0, 0}});
    ImportOptions onlyR = metres;
    onlyR.layers = {"R"};
    CHECK(importRailsFile(dir / "frozen.dxf", onlyR).size() == 1);
    ImportOptions decor = metres;
    decor.layers = {"DECOR", "R"};
    CHECK_THROWS_WITH(importRailsFile(dir / "frozen.dxf", decor),
                      Contains("ELLIPSE on layer DECOR") && Contains("convert it"));
    // In a block: the ELLIPSE keeps its frozen layer DECOR, inserted on layer I.
    writeText(dir / "block.dxf", table + withBlock(block, insert("E") + line));
    CHECK(importRailsFile(dir / "block.dxf", onlyR).size() == 1);
    CHECK(importRailsFile(dir / "block.dxf", metres).size() == 1);
    ImportOptions byInsert = metres;
    byInsert.layers = {"I"};
    CHECK_THROWS_WITH(importRailsFile(dir / "block.dxf", byInsert),
                      Contains("ELLIPSE on layer DECOR") &&
                          Contains("inserted by INSERT A1 on layer I"));
}

TEST_CASE("DXF layers: without rails on the chosen layers, the message says what they hold") {
    const auto dir = outputDir("dxf-chosen-empty");
    writeText(dir / "text.dxf",
              "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n0\nLAYER\n2\nC\n70\n0\n62\n7\n"
              "0\nENDTAB\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n"
              "0\nLINE\n8\nA\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n"
              "0\nTEXT\n8\nB\n10\n0\n20\n0\n30\n0\n40\n1\n1\nlabel\n0\nENDSEC\n0\nEOF\n");
    ImportOptions chosen;
    chosen.units = "m";
    chosen.layers = {"B", "C"};
    try {
        importRailsFile(dir / "text.dxf", chosen);
        FAIL("no error");
    } catch (const UserError& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK_THAT(message, Contains("on the layers chosen by layers = {...} (B: 1 TEXT; C: "
                                     "nothing)") &&
                                Contains("its rails are on A; name those layers") &&
                                !Contains("it has 1 LINE"));
    }
}
