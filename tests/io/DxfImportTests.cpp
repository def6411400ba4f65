// DXF rails (io/Import.h) from fixtures written by a real CAD library (tools/fixtures/
// make_dxf_fixtures.py, ezdxf): geometry checked against numbers computed by hand, units, and
// bad files that must fail with the file, the entity or line, and the reason.

#include "IoTestSupport.h"

#include "geometry/Curve.h"
#include "io/DxfGeometry.h"
#include "io/Import.h"
#include "model/Error.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <clocale>
#include <cmath>
#include <locale>
#include <numbers>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

constexpr double pi = std::numbers::pi;

std::vector<NamedCurve> dxf(const std::string& name, const ImportOptions& options = {}) {
    return importRailsFile(dataDir() / "dxf" / name, options);
}

/// The length of an arc of `sweep` radians sampled as the importer does (kArcStep at most).
double sampledArc(double radius, double sweep) {
    const int n = std::max(2, int(std::ceil(sweep / io::kArcStep)));
    return n * 2 * radius * std::sin(0.5 * sweep / n);
}

double length(const NamedCurve& rail) {
    return Curve::build(rail.curve).length();
}

/// Points along a curve at equal parameter steps.
std::vector<Vec3> dense(const CurveSpec& spec, int n = 2000) {
    CurveSpec byParameter = spec;
    byParameter.sampling = Sampling::Parameter;
    const Curve c = Curve::build(byParameter);
    return c.samplePoints(0, 1.0 / n, n);
}

std::string minimalDxf(const std::string& entities) {
    return "0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n";
}

/// Writes `text` to `file` and checks that importing it in metres is refused with a message that
/// names the file and holds every one of `parts`.
void refusesInMetres(const std::filesystem::path& file, const std::string& text,
                     std::initializer_list<std::string> parts) {
    const std::string name = file.filename().string();
    INFO(name);
    writeText(file, text);
    ImportOptions metres;
    metres.units = "m";
    try {
        importRailsFile(file, metres);
        FAIL("no error");
    } catch (const UserError& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK_THAT(message, Contains(name));
        for (const auto& part : parts)
            CHECK_THAT(message, Contains(part));
    }
}

} // namespace

TEST_CASE("DXF SPLINE: open and non-uniform, and a rational quarter circle") {
    const auto rails = dxf("spline_open.dxf");
    REQUIRE(rails.size() == 2);
    const CurveSpec& s = rails[0].curve;
    CHECK_THAT(rails[0].name, StartsWith("RAILS:"));
    CHECK(s.spline);
    CHECK_FALSE(s.closed);
    CHECK(s.degree == 3);
    CHECK(s.knots == std::vector<double>{0, 0, 0, 0, 0.3, 0.5, 1, 1, 1, 1});
    REQUIRE(s.points.size() == 6);
    CHECK(s.points[2] == Vec3{3, 2, 0.5});
    CHECK(s.weights.empty());
    // A clamped spline starts and ends at its end control points.
    const Curve c = Curve::build(s);
    CHECK(distance(c.pointAt(0), {0, 0, 0}) < 1e-12);
    CHECK(distance(c.pointAt(1), {7, 1, 1}) < 1e-12);

    // Quarter circle of radius 2 about (0, 0, 1) as a rational quadratic: exact circle, length pi.
    const CurveSpec& q = rails[1].curve;
    CHECK_THAT(rails[1].name, StartsWith("TOP:"));
    CHECK(q.degree == 2);
    REQUIRE(q.weights.size() == 3);
    CHECK(q.weights[1] == Approx(std::sqrt(0.5)).epsilon(1e-15));
    for (const Vec3& p : dense(q))
        CHECK(distance(p, {0, 0, 1}) == Approx(2).epsilon(1e-12));
    CHECK(length(rails[1]) == Approx(pi).epsilon(1e-9));
}

TEST_CASE("DXF SPLINE: closed periodic spline is unwrapped to CurveSpec's closed form") {
    const auto rails = dxf("spline_closed.dxf");
    REQUIRE(rails.size() == 1);
    const CurveSpec& s = rails[0].curve;
    CHECK(s.closed);
    CHECK(s.spline);
    REQUIRE(s.points.size() == 8); // ezdxf wrote 11: the first 3 repeated
    CHECK(s.knots.size() == 8 + 2 * 3 + 1);
    // Uniform cubic B-spline of a regular octagon of radius 3 (z = 2): radius between
    // 3 (2 cos 67.5 + 46 cos 22.5) / 48 (mid-span) and 3 (4 + 2 cos 45) / 6 (at the knots).
    const double atKnot = 3 * (4 + 2 * std::cos(pi / 4)) / 6;
    const double midSpan = 3 * (2 * std::cos(3 * pi / 8) + 46 * std::cos(pi / 8)) / 48;
    double lo = 1e9, hi = 0;
    for (const Vec3& p : dense(s)) {
        CHECK(p.z == Approx(2).epsilon(1e-12));
        const double r = std::hypot(p.x, p.y);
        lo = std::min(lo, r);
        hi = std::max(hi, r);
    }
    CHECK(hi == Approx(atKnot).epsilon(1e-9));
    CHECK(lo == Approx(midSpan).epsilon(1e-6));
}

TEST_CASE("DXF LWPOLYLINE and POLYLINE: bulges become finely sampled arcs") {
    const auto rails = dxf("lwpolyline.dxf");
    REQUIRE(rails.size() == 3);
    // Stadium: sides of 4, half circles of radius 1 (bulge 1), elevation 1.5, closed.
    const NamedCurve& stadium = rails[0];
    CHECK(stadium.curve.closed);
    for (const Vec3& p : stadium.curve.points)
        CHECK(p.z == 1.5);
    CHECK(length(stadium) == Approx(8 + 2 * sampledArc(1, pi)).epsilon(1e-12));
    CHECK(length(stadium) == Approx(8 + 2 * pi).epsilon(1e-5));
    for (const Vec3& p : stadium.curve.points)
        if (p.x > 4)
            CHECK(distance(p, {4, 1, 1.5}) == Approx(1).epsilon(1e-12));

    // Open: (0,0) -> (2,0) with bulge 0.5, then straight to (2,3). Included angle 4 atan(0.5),
    // radius = chord / (2 sin(angle / 2)) = 1.25, centre (1, 0.75); the arc dips to y = -0.5.
    const NamedCurve& open = rails[1];
    CHECK_FALSE(open.curve.closed);
    const double angle = 4 * std::atan(0.5);
    const double radius = 2 / (2 * std::sin(angle / 2));
    CHECK(radius == Approx(1.25).epsilon(1e-15));
    double lowest = 0;
    for (const Vec3& p : open.curve.points) {
        if (p.x < 2 || (p.x == 2 && p.y == 0))
            CHECK(distance(p, {1, 0.75, 0}) == Approx(radius).epsilon(1e-12));
        lowest = std::min(lowest, p.y);
    }
    // The sample nearest the bottom is at most half a step away: r (1 - cos(step / 2)) higher.
    CHECK(lowest >= -0.5 - 1e-12);
    CHECK(lowest <= -0.5 + radius * (1 - std::cos(io::kArcStep / 2)) + 1e-12);
    CHECK(length(open) == Approx(sampledArc(radius, angle) + 3).epsilon(1e-12));
    CHECK(length(open) == Approx(radius * angle + 3).epsilon(1e-5));
    CHECK(open.curve.points.back() == Vec3{2, 3, 0});

    // A closed 3D POLYLINE: its 4 vertices as written.
    CHECK(rails[2].curve.closed);
    CHECK(rails[2].curve.points ==
          std::vector<Vec3>{{0, 0, 0}, {1, 0, 0.5}, {1, 1, 1}, {0, 1, 0.5}});
    CHECK_THAT(rails[2].name, StartsWith("POLY3D:"));
}

TEST_CASE("DXF LINE and ARC chains are joined end to end, per layer") {
    const auto rails = dxf("line_arc_chain.dxf");
    REQUIRE(rails.size() == 2);
    // Closed loop: two lines of 2 and two half circles of radius 1, written out of order.
    CHECK(rails[0].curve.closed);
    CHECK(length(rails[0]) == Approx(4 + 2 * sampledArc(1, pi)).epsilon(1e-12));
    // It runs like its first entity in the file (the ARC about (2, 1) from -90 degrees).
    CHECK(distance(rails[0].curve.points[0], {2, 0, 0}) < 1e-15);
    CHECK(rails[0].curve.points[1].x > 2);
    // Open chain at z = 1: 1 + pi / 2 + 2, from the first entity's start (12, 3) to (10, 0).
    CHECK_FALSE(rails[1].curve.closed);
    CHECK(length(rails[1]) == Approx(3 + sampledArc(1, pi / 2)).epsilon(1e-12));
    CHECK(rails[1].curve.points.front() == Vec3{12, 3, 1});
    CHECK(rails[1].curve.points.back() == Vec3{10, 0, 1});
}

TEST_CASE("DXF units: $INSUNITS converts to metres, unitless and unknown units are refused") {
    const auto mm = dxf("millimetres.dxf");
    REQUIRE(mm.size() == 1);
    CHECK(mm[0].curve.points == std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 2, 0.5}});
    CHECK(length(mm[0]) == Approx(1 + std::sqrt(4.25)).epsilon(1e-15));

    CHECK_THROWS_WITH(dxf("units_unitless.dxf"), Contains("units_unitless.dxf") &&
                                                     Contains("no units") &&
                                                     Contains("$INSUNITS is 0"));
    ImportOptions inches;
    inches.units = "in";
    const auto given = dxf("units_unitless.dxf", inches);
    CHECK(given[0].curve.points.back() == Vec3{0.0254, 0.0254, 0});

    CHECK_THROWS_WITH(dxf("units_unknown.dxf"),
                      Contains("units_unknown.dxf") && Contains("$INSUNITS is 99"));
    CHECK_THROWS_WITH(dxf("units_unknown.dxf", inches), Contains("$INSUNITS is 99"));
    ImportOptions metres;
    metres.units = "m";
    CHECK_THROWS_WITH(dxf("millimetres.dxf", metres),
                      Contains("millimetres ($INSUNITS 4)") && Contains("\"m\""));
    ImportOptions millimetres;
    millimetres.units = "mm";
    CHECK(dxf("millimetres.dxf", millimetres).size() == 1); // agreeing is fine
}

TEST_CASE("bad DXF files name the file, the entity or line, and the reason") {
    const auto fails = [](const std::string& name, std::initializer_list<std::string> parts) {
        INFO(name);
        try {
            dxf(name);
            FAIL("no error");
        } catch (const UserError& e) {
            const std::string message = e.what();
            INFO(message);
            CHECK_THAT(message, StartsWith((dataDir() / "dxf" / name).string()));
            for (const auto& part : parts)
                CHECK_THAT(message, Contains(part));
        }
    };
    fails("bad_spline_knots.dxf",
          {"SPLINE", "on layer BAD", "(line ", "knot vector has 7 values", "needs 9"});
    fails("bad_spline_decreasing.dxf", {"SPLINE", "on layer BAD", "knots must not decrease"});
    fails("truncated.dxf", {"line ", "truncated"});
    fails("garbage.dxf", {"line ", "binary data"});
    fails("nan_coordinate.dxf", {"line 2118", "LINE", "on layer RAILS", "'nan'", "finite"});
}

TEST_CASE("DXF: counts that disagree with the values, branches, text that is not DXF") {
    const auto dir = outputDir("dxf-text");
    ImportOptions metres;
    metres.units = "m";
    const auto fails = [&](const std::string& name, const std::string& text,
                           std::initializer_list<std::string> parts) {
        refusesInMetres(dir / name, text, parts);
    };
    // dxflib would silently pad the knot vector with zeros: the scan refuses the file first.
    fails("declared.dxf",
          minimalDxf("0\nSPLINE\n5\nA1\n8\nR\n70\n8\n71\n1\n72\n5\n73\n2\n40\n0\n40\n0\n40\n1\n"
                     "10\n0\n20\n0\n30\n0\n10\n1\n20\n0\n30\n0\n"),
          {"SPLINE A1 on layer R (line 5)", "declares 5 knots", "lists 3"});
    fails("branch.dxf",
          minimalDxf("0\nLINE\n8\nR\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n"
                     "0\nLINE\n8\nR\n10\n1\n20\n0\n30\n0\n11\n2\n21\n0\n31\n0\n"
                     "0\nLINE\n8\nR\n10\n1\n20\n0\n30\n0\n11\n1\n21\n1\n31\n0\n"),
          {"3 ends meet at (1, 0, 0)", "cannot branch"});
    fails("code.dxf", "0\nSECTION\n2\nENTITIES\nten\nLINE\n", {"line 5", "group code", "'ten'"});
    fails("text.dxf", "hello world\n", {"not an ASCII DXF file"});
    fails("eof.dxf", "0\nSECTION\n2\nENTITIES\n0\nLINE\n8\nR\n",
          {"without the closing '0 EOF'", "truncated"});
    fails("ellipse.dxf",
          minimalDxf("0\nELLIPSE\n8\nR\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n40\n0.5\n"),
          {"ELLIPSE", "convert it"});
    fails("nothing.dxf", minimalDxf("0\nTEXT\n8\nR\n10\n0\n20\n0\n30\n0\n1\nhello\n"),
          {"holds no rails", "1 TEXT"});

    // A minimal file without handles: names are LAYER:#N; a CIRCLE is a closed rail.
    writeText(dir / "circle.dxf", minimalDxf("0\nCIRCLE\n8\nHOOP\n10\n1\n20\n2\n30\n3\n40\n0.5\n"));
    const auto rails = importRailsFile(dir / "circle.dxf", metres);
    REQUIRE(rails.size() == 1);
    CHECK(rails[0].name == "HOOP:#1");
    CHECK(rails[0].curve.closed);
    for (const Vec3& p : rails[0].curve.points)
        CHECK(distance(p, {1, 2, 3}) == Approx(0.5).epsilon(1e-12));
    CHECK(length(rails[0]) == Approx(sampledArc(0.5, 2 * pi)).epsilon(1e-12));

    // An ARC drawn with extrusion (0, 0, -1), as CAD programs write mirrored arcs: its object
    // coordinate system has x = -X, y = Y, z = -Z (the DXF arbitrary axis algorithm). Centre
    // (1, 0) at elevation 2, radius 1, 0 to 90 degrees: from (-2, 0, -2) to (-1, 1, -2).
    writeText(dir / "mirrored.dxf", minimalDxf("0\nARC\n8\nM\n10\n1\n20\n0\n30\n2\n40\n1\n"
                                               "210\n0\n220\n0\n230\n-1\n50\n0\n51\n90\n"));
    const auto mirrored = importRailsFile(dir / "mirrored.dxf", metres);
    REQUIRE(mirrored.size() == 1);
    CHECK(distance(mirrored[0].curve.points.front(), {-2, 0, -2}) < 1e-12);
    CHECK(distance(mirrored[0].curve.points.back(), {-1, 1, -2}) < 1e-12);
    for (const Vec3& p : mirrored[0].curve.points)
        CHECK(distance(p, {-1, 0, -2}) == Approx(1).epsilon(1e-12));
}

TEST_CASE("DXF: the counts dxflib allocates by are bounded and given once, in every section") {
    // dxflib allocates an array by each count as it reads it: these files asked for up to 64 GB,
    // and a repeated LWPOLYLINE count freed dxflib's array twice.
    const auto dir = outputDir("dxf-counts");
    const auto fails = [&](const std::string& name, const std::string& text,
                           std::initializer_list<std::string> parts) {
        refusesInMetres(dir / name, text, parts);
    };
    const std::string square = "10\n0\n20\n0\n10\n1\n20\n0\n";
    fails("repeated.dxf",
          minimalDxf("0\nLWPOLYLINE\n8\nR\n90\n2\n70\n0\n" + square + "90\n2000000000\n"),
          {"LWPOLYLINE on layer R (line 5)", "vertex count 2000000000 (group code 90)",
           "allowed 0 to 10000000"});
    fails("twice.dxf", minimalDxf("0\nLWPOLYLINE\n8\nR\n90\n2\n70\n0\n" + square + "90\n2\n"),
          {"line 22", "gives its vertex count (group code 90) twice, at lines 10 and 22"});
    fails("leader.dxf", minimalDxf("0\nLEADER\n8\nR\n76\n2000000000\n"),
          {"line 10", "LEADER on layer R", "vertex count 2000000000 (group code 76)"});
    fails("spline.dxf",
          minimalDxf("0\nSPLINE\n8\nR\n70\n8\n71\n1\n72\n4\n73\n2\n40\n0\n40\n0\n40\n1\n40\n1\n"
                     "10\n0\n20\n0\n30\n0\n10\n1\n20\n0\n30\n0\n72\n2000000000\n"),
          {"SPLINE on layer R", "knot count 2000000000 (group code 72)"});
    fails("block.dxf",
          "0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n8\n0\n2\nB\n0\nLWPOLYLINE\n8\nR\n90\n-1\n"
          "0\nENDBLK\n0\nENDSEC\n" +
              minimalDxf("0\nLINE\n8\nR\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n"),
          {"line 16", "LWPOLYLINE on layer R (line 11) in block B", "vertex count -1"});
    fails("objects.dxf",
          "0\nSECTION\n2\nOBJECTS\n0\nSPLINE\n73\n1e9\n0\nENDSEC\n" +
              minimalDxf("0\nLINE\n8\nR\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n"),
          {"line 8", "SPLINE in the OBJECTS section",
           "control point count (group code 73) holds '1e9'", "not an integer"});
}

TEST_CASE("DXF: an ARC's angles are taken modulo 360 degrees, however large") {
    // Their difference overflowed to infinity, the sweep was NaN and its sample count undefined.
    const auto dir = outputDir("dxf-arc-angles");
    ImportOptions metres;
    metres.units = "m";
    writeText(dir / "huge.dxf", minimalDxf("0\nARC\n8\nR\n10\n1\n20\n2\n30\n3\n40\n0.5\n"
                                           "50\n1.7e308\n51\n-1.7e308\n"));
    const auto rails = importRailsFile(dir / "huge.dxf", metres);
    REQUIRE(rails.size() == 1);
    const double start = std::fmod(1.7e308, 360.0);
    double sweep = std::fmod(-2 * start, 360.0);
    if (sweep <= 0)
        sweep += 360.0;
    CHECK(distance(rails[0].curve.points.front(), {1 + 0.5 * std::cos(start * pi / 180),
                                                   2 + 0.5 * std::sin(start * pi / 180), 3}) <
          1e-12);
    for (const Vec3& p : rails[0].curve.points)
        CHECK(distance(p, {1, 2, 3}) == Approx(0.5).epsilon(1e-12));
    CHECK(length(rails[0]) == Approx(sampledArc(0.5, sweep * pi / 180)).epsilon(1e-12));
    // 370 and 380 degrees are the arc from 10 to 20 degrees.
    writeText(dir / "turned.dxf", minimalDxf("0\nARC\n8\nR\n10\n0\n20\n0\n30\n0\n40\n1\n"
                                             "50\n370\n51\n380\n"));
    const auto turned = importRailsFile(dir / "turned.dxf", metres);
    REQUIRE(turned.size() == 1);
    CHECK(length(turned[0]) == Approx(sampledArc(1, 10 * pi / 180)).epsilon(1e-12));
}

TEST_CASE("DXF: a rounding-sized bulge keeps its segment straight") {
    // CAD programs write bulges like 3e-17 for straight segments; the arc's centre lies
    // chord / (4 bulge) away, so the samples must not be taken from it.
    const auto dir = outputDir("dxf-bulges");
    ImportOptions metres;
    metres.units = "m";
    for (const std::string bulge : {"3e-17", "-1e-16", "1e-100"}) {
        INFO("bulge " << bulge);
        writeText(dir / "nearly_straight.dxf",
                  minimalDxf("0\nLWPOLYLINE\n8\nR\n90\n3\n70\n0\n10\n0\n20\n0\n42\n" + bulge +
                             "\n10\n1\n20\n0\n10\n1\n20\n1\n"));
        const auto rails = importRailsFile(dir / "nearly_straight.dxf", metres);
        REQUIRE(rails.size() == 1);
        CHECK(length(rails[0]) == Approx(2).epsilon(1e-12));
        for (const Vec3& p : rails[0].curve.points) { // on (0, 0) - (1, 0) - (1, 1)
            CHECK(p.x >= 0);
            CHECK(p.x <= 1);
            CHECK((std::abs(p.y) < 1e-12 || p.x == 1));
        }
    }
}

TEST_CASE("DXF: extrusion directions written with huge or tiny numbers") {
    const auto dir = outputDir("dxf-extrusions");
    ImportOptions metres;
    metres.units = "m";
    // The same mirrored circle as with extrusion (0, 0, -1): centre (-1, 2, -3) in the world.
    for (const std::string z : {"-1", "-1e300", "-1e-300"}) {
        INFO("extrusion z " << z);
        writeText(dir / "mirrored.dxf", minimalDxf("0\nCIRCLE\n8\nM\n10\n1\n20\n2\n30\n3\n40\n0.5\n"
                                                   "210\n0\n220\n0\n230\n" +
                                                   z + "\n"));
        const auto rails = importRailsFile(dir / "mirrored.dxf", metres);
        REQUIRE(rails.size() == 1);
        for (const Vec3& p : rails[0].curve.points)
            CHECK(distance(p, {-1, 2, -3}) == Approx(0.5).epsilon(1e-12));
    }
}

TEST_CASE("DXF: reading leaves the host's C and C++ locales as they were") {
    const auto dir = outputDir("dxf-locale");
    writeText(dir / "line.dxf",
              minimalDxf("0\nLINE\n8\nR\n10\n0.5\n20\n0\n30\n0\n11\n2.25\n21\n0\n31\n0\n"));
    ImportOptions metres;
    metres.units = "m";
    const std::vector<Vec3> expected{{0.5, 0, 0}, {2.25, 0, 0}};
    // A host (Lua's os.setlocale) that set only the C locale: the C++ one is still classic.
    REQUIRE(std::setlocale(LC_ALL, "C.UTF-8") != nullptr);
    CHECK(importRailsFile(dir / "line.dxf", metres)[0].curve.points == expected);
    CHECK(std::string(std::setlocale(LC_ALL, nullptr)) == "C.UTF-8");
    // A host that set the C++ global locale (and with it the C one): switched and put back.
    std::locale::global(std::locale("C.UTF-8"));
    CHECK(importRailsFile(dir / "line.dxf", metres)[0].curve.points == expected);
    CHECK(std::locale().name() == "C.UTF-8");
    CHECK(std::string(std::setlocale(LC_ALL, nullptr)) == "C.UTF-8");
    std::locale::global(std::locale::classic());
    CHECK(std::string(std::setlocale(LC_ALL, nullptr)) == "C");
}
