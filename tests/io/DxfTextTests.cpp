// DXF text as CAD programs and old tools write it (code pages, byte-order marks, old Mac line
// ends), and drawings whose content is odd: polylines snapped shut without the closed flag,
// segments shorter than the join tolerance, coordinates out of range, paper space only, layers
// that are not drawn (io/Import.h).

#include "IoTestSupport.h"

#include "geometry/Curve.h"
#include "io/Import.h"
#include "model/Error.h"

#include <catch2/catch.hpp>

#include <algorithm>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;

namespace {

std::string header(const std::string& version, const std::string& codePage) {
    return "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\n" + version + "\n9\n$DWGCODEPAGE\n3\n" +
           codePage + "\n9\n$INSUNITS\n70\n6\n0\nENDSEC\n";
}

std::string entities(const std::string& body) {
    return "0\nSECTION\n2\nENTITIES\n" + body + "0\nENDSEC\n0\nEOF\n";
}

std::string line(const std::string& layer, const std::string& to = "1\n21\n0") {
    return "0\nLINE\n8\n" + layer + "\n10\n0\n20\n0\n30\n0\n11\n" + to + "\n31\n0\n";
}

std::vector<NamedCurve> read(const std::string& name, const std::string& text,
                             const std::string& units = "m") {
    const auto file = outputDir("dxf-text-" + name) / name;
    writeText(file, text);
    ImportOptions options;
    options.units = units;
    return importRailsFile(file, options);
}

} // namespace

TEST_CASE("DXF text: code pages of drawings before AutoCAD 2007 are decoded to UTF-8") {
    // "Außen€" in Windows-1252: ß is 0xDF, € is 0x80.
    const auto cp1252 = read("cp1252.dxf", header("AC1015", "ANSI_1252") +
                                               entities(line("Au\xDF" "en\x80")));
    REQUIRE(cp1252.size() == 1);
    CHECK(cp1252[0].name == "Au\xC3\x9F" "en\xE2\x82\xAC:#1");
    // ISO 8859-1 has no euro sign: 0xDF is ß there too.
    const auto latin1 = read("latin1.dxf", header("AC1015", "ISO8859-1") +
                                               entities(line("Au\xDF" "en")));
    CHECK(latin1[0].name == "Au\xC3\x9F" "en:#1");
    // UTF-8 under ANSI_1252 (as LibreCAD writes) stays UTF-8.
    const auto utf8 = read("utf8.dxf", header("AC1015", "ANSI_1252") +
                                           entities(line("Au\xC3\x9F" "en")));
    CHECK(utf8[0].name == "Au\xC3\x9F" "en:#1");

    const std::string cyrillic = header("AC1015", "ANSI_1251") + entities(line("\xD0\xE5\xEB"));
    const auto lineNo = 1 + std::count(cyrillic.begin(), cyrillic.begin() + long(cyrillic.find('\xD0')), '\n');
    CHECK(lineNo == 26); // 18 header lines, 4 opening ENTITIES, "0 LINE" and "8", then the name
    CHECK_THROWS_WITH(read("cyrillic.dxf", cyrillic),
                      Contains("cyrillic.dxf: line 26") && Contains("\\xD0") &&
                          Contains("'ANSI_1251' ($DWGCODEPAGE)") && Contains("ANSI_1252"));
    CHECK_THROWS_WITH(read("broken.dxf", header("AC1027", "ANSI_1252") + entities(line("R\xFF"))),
                      Contains("broken.dxf: line 26") && Contains("AutoCAD 2007 or later"));
}

TEST_CASE("DXF text: a byte-order mark and old Mac line ends are read") {
    const std::string text = header("AC1015", "ANSI_1252") + entities(line("R"));
    CHECK(read("bom.dxf", "\xEF\xBB\xBF" + text).size() == 1);
    std::string mac = text;
    std::replace(mac.begin(), mac.end(), '\n', '\r');
    const auto rails = read("mac.dxf", mac);
    REQUIRE(rails.size() == 1);
    CHECK(rails[0].curve.points == std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}});
}

TEST_CASE("DXF polylines whose last vertex is their first are closed, flagged or not") {
    // The 4 x 3 outline snapped shut: 4 points, closed, 14 long; the same with the flag set.
    for (const std::string flags : {"0", "1"}) {
        INFO("flags " << flags);
        const auto rails = read("snapped.dxf",
                                entities("0\nLWPOLYLINE\n8\nR\n90\n5\n70\n" + flags +
                                         "\n10\n0\n20\n0\n10\n4\n20\n0\n10\n4\n20\n3\n"
                                         "10\n0\n20\n3\n10\n0\n20\n0\n"));
        REQUIRE(rails.size() == 1);
        CHECK(rails[0].curve.closed);
        CHECK(rails[0].curve.points ==
              std::vector<Vec3>{{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}});
        CHECK(Curve::build(rails[0].curve).length() == 14);
    }
}

TEST_CASE("DXF LINE chains: a segment shorter than the join tolerance is left out") {
    // 10 m of LINEs with a 5 um one in the middle; the tolerance is 1e-6 of 10 m = 10 um.
    const auto rails = read("short.dxf", entities(line("S", "5\n21\n0") +
                                                  "0\nLINE\n8\nS\n10\n5\n20\n0\n30\n0\n"
                                                  "11\n5.000005\n21\n0\n31\n0\n"
                                                  "0\nLINE\n8\nS\n10\n5.000005\n20\n0\n30\n0\n"
                                                  "11\n10\n21\n0\n31\n0\n"));
    REQUIRE(rails.size() == 1);
    CHECK(rails[0].curve.points == std::vector<Vec3>{{0, 0, 0}, {5, 0, 0}, {10, 0, 0}});
    // A 20 um segment is longer than the tolerance: a part of the rail.
    const auto kept = read("kept.dxf", entities(line("S", "5\n21\n0") +
                                                "0\nLINE\n8\nS\n10\n5\n20\n0\n30\n0\n"
                                                "11\n5.00002\n21\n0\n31\n0\n"));
    CHECK(kept[0].curve.points.size() == 3);
}

TEST_CASE("DXF coordinates beyond 1e8 m are refused with the entity and the range") {
    CHECK_THROWS_WITH(read("huge.dxf", entities(line("H", "1e300\n21\n0")), "mm"),
                      Contains("LINE on layer H (line 5)") && Contains("coordinate of 1e+300") &&
                          Contains("(1e+297 m)") && Contains("within 1e+08 m") &&
                          Contains("1e+11 in the file's units"));
    CHECK_THROWS_WITH(read("circle.dxf",
                           entities("0\nCIRCLE\n8\nC\n10\n0\n20\n0\n30\n0\n40\n1e200\n")),
                      Contains("CIRCLE on layer C") && Contains("coordinate of 1e+200 m"));
    // 1e8 m itself is allowed.
    CHECK(read("edge.dxf", entities(line("E", "1e8\n21\n0"))).size() == 1);
}

TEST_CASE("DXF without rails says why: paper space only, or layers that are not drawn") {
    CHECK_THROWS_WITH(read("paper.dxf", entities("0\nLINE\n8\nR\n67\n1\n10\n0\n20\n0\n30\n0\n"
                                                 "11\n1\n21\n0\n31\n0\n")),
                      Contains("paper.dxf: holds no rails") &&
                          Contains("only entities (1 LINE) are in paper space"));
    const std::string frozen = "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n70\n1\n"
                               "0\nLAYER\n2\nH\n70\n1\n62\n7\n0\nENDTAB\n0\nENDSEC\n";
    CHECK_THROWS_WITH(read("frozen.dxf", frozen + entities(line("H"))),
                      Contains("not drawn (frozen, off or Defpoints): H") &&
                          Contains("layers = {...}"));
}
