// DXF out (io/DxfExport.h): bars as LINEs on a layer per piece, rails as 3D POLYLINEs carrying
// their names, metres, site coordinates kept, and netsculpt's DXF import giving the rails back.
// The drawing is read here by a small group-pair reader, independent of the importer.

#include "IoTestSupport.h"

#include "io/DxfExport.h"
#include "io/Export.h"
#include "io/Import.h"
#include "model/Error.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <charconv>
#include <map>
#include <set>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;

namespace {

/// One entity or table entry: its type and its groups in file order.
struct Record {
    std::string type;
    std::vector<std::pair<int, std::string>> groups;

    std::string text(int code) const {
        for (const auto& [c, v] : groups)
            if (c == code)
                return v;
        return {};
    }
    double real(int code, int occurrence = 0) const {
        for (const auto& [c, v] : groups)
            if (c == code && occurrence-- == 0) {
                double value = 0;
                const auto r = std::from_chars(v.data(), v.data() + v.size(), value);
                REQUIRE(r.ptr == v.data() + v.size()); // the whole field is one number
                return value;
            }
        FAIL("no group " << code << " in " << type);
        return 0;
    }
    Vec3 point(int code) const { return {real(code), real(code + 10), real(code + 20)}; }
    /// The strings of its NETSCULPT extended data.
    std::vector<std::string> mark() const {
        std::vector<std::string> out;
        bool ours = false;
        for (const auto& [c, v] : groups) {
            if (c == 1001)
                ours = v == "NETSCULPT";
            else if (c == 1000 && ours)
                out.push_back(v);
        }
        return out;
    }
};

/// Every "0" record of the file (section markers included), with the header variables.
struct Drawing {
    std::vector<Record> records;
    std::map<std::string, std::string> header; // $NAME -> its first value

    std::vector<Record> all(const std::string& type) const {
        std::vector<Record> out;
        for (const Record& r : records)
            if (r.type == type)
                out.push_back(r);
        return out;
    }
    std::map<std::string, int> layerColours() const {
        std::map<std::string, int> out;
        for (const Record& r : all("LAYER"))
            out[r.text(2)] = std::stoi(r.text(62));
        return out;
    }
};

Drawing readDrawing(const std::filesystem::path& file) {
    const std::string text = readText(file);
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = text.find('\n', start);
        REQUIRE(end != std::string::npos); // every line ends with a newline
        lines.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    REQUIRE(lines.size() % 2 == 0);
    Drawing d;
    std::string variable;
    for (std::size_t i = 0; i < lines.size(); i += 2) {
        const int code = std::stoi(lines[i]);
        const std::string& value = lines[i + 1];
        if (code == 0) {
            d.records.push_back({value, {}});
            variable.clear();
        } else if (code == 9) {
            variable = value;
        } else if (!variable.empty()) {
            d.header.emplace(variable, value);
        } else if (!d.records.empty()) {
            d.records.back().groups.push_back({code, value});
        }
    }
    REQUIRE(!d.records.empty());
    CHECK(d.records.back().type == "EOF");
    return d;
}

/// The POLYLINE records with their VERTEX points, in file order.
std::vector<std::pair<Record, std::vector<Vec3>>> polylines(const Drawing& d) {
    std::vector<std::pair<Record, std::vector<Vec3>>> out;
    bool open = false;
    for (const Record& r : d.records) {
        if (r.type == "POLYLINE") {
            out.push_back({r, {}});
            open = true;
        } else if (r.type == "VERTEX" && open) {
            CHECK(r.text(8) == out.back().first.text(8)); // on the polyline's layer
            out.back().second.push_back(r.point(10));
        } else {
            open = false;
        }
    }
    return out;
}

std::size_t reportedBars(const Sculpture& s, const CompiledSculpture& compiled) {
    std::size_t bars = 0;
    const nlohmann::json report = buildReport(s, compiled, {});
    for (const auto& piece : report.at("pieces"))
        bars += piece.at("bars").get<std::size_t>();
    return bars;
}

} // namespace

TEST_CASE("DXF: each bar a LINE from knot to knot on its piece's layer, the rail a 3D POLYLINE") {
    // 3 columns on a 3 m rail: row 0 at x = 0, 1.5, 3; with bars of 1.25 m row 1 starts 1 m
    // below the midpoints (h = sqrt(1.25² - 0.75²)), and has 2 + 2 + 1 bars up (an open sheet:
    // the last knot's second parent would be column 3).
    SheetNet t = sheet(2, 3, 3.0, 1.25);
    edit(t.s, [&](Sculpture& s) {
        renamePiece(s, t.piece, "front net/1");
        return 0;
    });
    const auto dir = outputDir("dxf-sheet");
    exportFile(t.s, t.compiled, {}, dir / "net.dxf");
    const Drawing d = readDrawing(dir / "net.dxf");
    CHECK(d.header.at("$INSUNITS") == "6"); // metres
    CHECK(d.header.at("$ACADVER") == "AC1009");

    const auto lines = d.all("LINE");
    REQUIRE(lines.size() == 5);
    CHECK(lines.size() == reportedBars(t.s, t.compiled));
    const MassSpringSystem& sys = t.compiled.system;
    std::set<std::array<double, 3>> knots;
    for (std::size_t k = 0; k < sys.knotCount(); ++k) {
        const Vec3 p = sys.worldPosition(k);
        knots.insert({p.x, p.y, p.z});
    }
    std::set<std::pair<std::array<double, 3>, std::array<double, 3>>> segments;
    for (const Record& line : lines) {
        CHECK(line.text(8) == "piece_1_front_net_1"); // ' ' and '/' are not in layer names
        CHECK(line.mark() == std::vector<std::string>{"bar"});
        const Vec3 a = line.point(10), b = line.point(11);
        CHECK(knots.count({a.x, a.y, a.z}) == 1); // bit for bit
        CHECK(knots.count({b.x, b.y, b.z}) == 1);
        segments.insert(std::minmax(std::array{a.x, a.y, a.z}, std::array{b.x, b.y, b.z}));
    }
    CHECK(segments.size() == 5);
    CHECK(segments.count({{0, 0, 0}, {0.75, 0, -1}}) == 1);
    CHECK(segments.count({{0.75, 0, -1}, {1.5, 0, 0}}) == 1);
    CHECK(segments.count({{1.5, 0, 0}, {2.25, 0, -1}}) == 1);
    CHECK(segments.count({{2.25, 0, -1}, {3, 0, 0}}) == 1);
    CHECK(segments.count({{3, 0, -1.25}, {3, 0, 0}}) == 1); // one bar up: straight down

    const auto rails = polylines(d);
    REQUIRE(rails.size() == 1);
    CHECK(rails[0].first.text(8) == "rail_1_bar");
    CHECK(rails[0].first.text(70) == "8"); // 3D, open
    CHECK(rails[0].first.mark() == std::vector<std::string>{"rail", "bar"});
    CHECK(rails[0].second == std::vector<Vec3>{{0, 0, 0}, {3, 0, 0}});
    const auto colours = d.layerColours();
    CHECK(colours.at("rail_1_bar") == 7);
    CHECK(colours.count("piece_1_front_net_1") == 1);

    // netsculpt's import leaves the bars out and gives the rail back, name and all.
    const auto back = importRailsFile(dir / "net.dxf");
    REQUIRE(back.size() == 1);
    CHECK(back[0].name == "bar");
    CHECK_FALSE(back[0].curve.closed);
    CHECK(back[0].curve.points == std::vector<Vec3>{{0, 0, 0}, {3, 0, 0}});
}

TEST_CASE("DXF in site coordinates: a closed rail flagged closed, layers per piece, every "
          "coordinate as in the sculpture") {
    const Vec3 site{2.5e6, 1.2e6, 400};
    const Tube t = tubeWithChild(12, 5, 1.0, 0.4, site);
    const auto dir = outputDir("dxf-site");
    exportFile(t.s, t.compiled, {}, dir / "net.DXF");
    const Drawing d = readDrawing(dir / "net.DXF");

    // 12 columns x 4 rows below the top, two bars up each: 96. The gear-2 child: 12 new knots
    // of two bars each, then 24 columns x 2 rows of two: 24 + 96 = 120.
    std::map<std::string, int> perLayer;
    const MassSpringSystem& sys = t.compiled.system;
    std::set<std::array<double, 3>> knots;
    for (std::size_t k = 0; k < sys.knotCount(); ++k) {
        const Vec3 p = sys.worldPosition(k);
        knots.insert({p.x, p.y, p.z});
    }
    std::size_t offKnots = 0;
    for (const Record& line : d.all("LINE")) {
        ++perLayer[line.text(8)];
        for (const Vec3& p : {line.point(10), line.point(11)})
            offKnots += knots.count({p.x, p.y, p.z}) == 1 ? 0 : 1;
    }
    CHECK(perLayer["piece_1_upper"] == 96);
    CHECK(perLayer["piece_2"] == 120); // its default name "piece 2" adds nothing
    CHECK(perLayer.size() == 2);
    CHECK(offKnots == 0);
    CHECK(96 + 120 == reportedBars(t.s, t.compiled));
    // The child's linear (0.1, 0.3, 0.8) is sRGB (0.35, 0.58, 0.91): hue 215 degrees, about
    // ACI 150's, value nearer 1 than 0.8, saturation 0.61 (the half-saturated shade): ACI 151.
    CHECK(d.layerColours().at("piece_2") == 151);

    const auto rails = polylines(d);
    REQUIRE(rails.size() == 1);
    CHECK(rails[0].first.text(70) == "9"); // 3D and closed
    const auto& ring = rails[0].second;
    REQUIRE(ring.size() == 12); // the first vertex is not repeated
    CHECK(ring[0] == Vec3{2500001, 1200000, 403});
    CHECK(ring[3] == Vec3{2500000, 1200001, 403});
    CHECK(ring[6] == Vec3{2499999, 1200000, 403});
    CHECK(ring[9] == Vec3{2500000, 1199999, 403});

    const auto back = importRailsFile(dir / "net.DXF");
    REQUIRE(back.size() == 1);
    CHECK(back[0].name == "ring");
    CHECK(back[0].curve.closed);
    CHECK(back[0].curve.points == t.s.rails.begin()->second.curve().spec().points);
}

TEST_CASE("DXF layer names keep letters, digits, - and _ of the name - colours are ACI") {
    CHECK(io::dxfLayerName("piece", 3, "") == "piece_3");
    CHECK(io::dxfLayerName("piece", 3, "piece 3") == "piece_3");
    CHECK(io::dxfLayerName("piece", 3, "piece 4") == "piece_3_piece_4");
    CHECK(io::dxfLayerName("rail", 12, "Top ring: north") == "rail_12_Top_ring__north");
    CHECK(io::dxfLayerName("piece", 1, "a<b>c\"d") == "piece_1_a_b_c_d");
    CHECK(io::dxfLayerName("piece", 2, "v\xC3\xA9lo") == "piece_2_v__lo"); // two UTF-8 bytes
    CHECK(io::dxfLayerName("rail", 1, std::string(300, 'x')).size() == 255);
    CHECK(io::nearestAci(1, 0, 0) == 10);
    CHECK(io::nearestAci(0, 1, 0) == 90);
    CHECK(io::nearestAci(0, 0, 1) == 170);
    CHECK(io::nearestAci(0.5, 0, 0.5) == 216); // magenta at value 0.5
    CHECK(io::nearestAci(1, 0.5, 0.5) == 11);  // red, half saturated
    CHECK(io::nearestAci(0.5, 0.5, 0.5) == 8);
    CHECK(io::nearestAci(1, 1, 1) == 7);
}

TEST_CASE("a sculpture's rails alone to DXF - other extensions refused naming the allowed ones") {
    const Tube t = tubeWithChild();
    const auto dir = outputDir("dxf-rails");
    exportRailsFile(t.s, dir / "rails.dxf");
    const Drawing d = readDrawing(dir / "rails.dxf");
    CHECK(d.all("LINE").empty());
    CHECK(polylines(d).size() == 1);
    CHECK_THROWS_WITH(exportRailsFile(t.s, dir / "rails.png"),
                      Contains("rails.png: rails are exported to .csv, .obj or .dxf, not .png"));
    CHECK_THROWS_WITH(checkRailsExport(dir / "rails"), Contains("not a file without extension"));
    CHECK_FALSE(std::filesystem::exists(dir / "rails.png"));
}
