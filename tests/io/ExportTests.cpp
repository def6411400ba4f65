// Geometry and documents out (io/Export.h): the knots CSV, OBJ and PLY (lines and tubes), glb
// read back with tinygltf, the JSON document, options and errors, and atomic writes.

#include "IoTestSupport.h"

#include "io/Export.h"
#include "model/Error.h"

// tinygltf's implementation is compiled into the kernel (kernel/io/GltfExport.cpp) with these
// options; the test uses its loader through the same declarations.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <charconv>
#include <sstream>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;

namespace {

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        out.push_back(line);
    return out;
}

std::vector<std::string> fields(const std::string& line, char separator = ',') {
    std::vector<std::string> out(1);
    for (char c : line) {
        if (c == separator)
            out.emplace_back();
        else
            out.back().push_back(c);
    }
    return out;
}

double number(const std::string& text) {
    double value = 0;
    std::from_chars(text.data(), text.data() + text.size(), value);
    return value;
}

/// The float vertices of a glb's first primitive: x, y, z of its first vertex at [0], [1], [2].
const float* firstPrimitivePositions(const tinygltf::Model& model) {
    const tinygltf::Accessor& positions = model.accessors[std::size_t(
        model.meshes.at(0).primitives.at(0).attributes.at("POSITION"))];
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(positions.bufferView)];
    return reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset +
                                          positions.byteOffset);
}

/// Checks that the first bar's first end in a glb is knot barA[0] of `sys`, from its origin.
void checkFirstBarEnd(const tinygltf::Model& model, const MassSpringSystem& sys) {
    const float* data = firstPrimitivePositions(model);
    const Vec3& a = sys.position[sys.barA[0]];
    CHECK(data[0] == float(a.x));
    CHECK(data[1] == float(a.y));
    CHECK(data[2] == float(a.z));
}

std::size_t countPrefix(const std::string& text, const std::string& prefix) {
    std::size_t n = 0;
    for (const auto& line : lines(text))
        if (line.rfind(prefix, 0) == 0)
            ++n;
    return n;
}

} // namespace

TEST_CASE("knots CSV: the header and one line per (piece, row, column), positions bit for bit") {
    Tube t = tubeWithChild();
    const auto file = outputDir("export-csv") / "knots.csv";
    exportFile(t.s, t.compiled, {}, file);
    const auto rows = lines(readText(file));
    REQUIRE(!rows.empty());
    CHECK(rows[0] == "piece,row,column,x,y,z,fixed");
    std::size_t expected = 0;
    for (const auto& [id, p] : t.s.pieces)
        expected += std::size_t(p.rows) * p.columns;
    REQUIRE(rows.size() == 1 + expected); // shared knots once per piece holding them
    std::size_t fixed = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const auto f = fields(rows[i]);
        REQUIRE(f.size() == 7);
        const std::uint32_t k = t.compiled.knotOf(PieceId(std::uint32_t(std::stoul(f[0]))),
                                                  std::stoi(f[1]), std::stoi(f[2]));
        const Vec3 p{number(f[3]), number(f[4]), number(f[5])};
        CHECK(p == t.compiled.system.worldPosition(k));
        CHECK(f[6] == (t.compiled.system.fixed[k] ? "1" : "0"));
        fixed += f[6] == "1";
    }
    CHECK(fixed == 12); // the ring's top row
}

TEST_CASE("exports in site coordinates: the CSV in the sculpture's, the glb's floats from the "
          "system's origin, which its root node adds back") {
    const Vec3 site{512345.678, 5412345.678, 231.5};
    const Tube near = tubeWithChild(), far = tubeWithChild(12, 5, 1.0, 0.4, site);
    const MassSpringSystem& sys = far.compiled.system;
    REQUIRE(sys.origin == Vec3{512346, 5412346, 235}); // the ring's centre, 234.5 m up, rounded
    const auto dir = outputDir("export-site");
    exportFile(far.s, far.compiled, {}, dir / "knots.csv");
    const auto rows = lines(readText(dir / "knots.csv"));
    REQUIRE(rows.size() == 1 + 12 * 5 + 24 * 3);
    double worst = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const auto f = fields(rows[i]);
        const std::uint32_t k = far.compiled.knotOf(PieceId(std::uint32_t(std::stoul(f[0]))),
                                                    std::stoi(f[1]), std::stoi(f[2]));
        const Vec3 p{number(f[3]), number(f[4]), number(f[5])};
        CHECK(p == sys.worldPosition(k));
        worst = std::max(worst, distance(p - site, near.compiled.system.position[k]));
    }
    CHECK(worst < 1e-8); // the same net, moved to the site (rounded there to 9.3e-10 m)

    // The JSON document carries the origin and each knot's place from it, every bit of it.
    exportFile(far.s, far.compiled, {}, dir / "net.json");
    const auto doc = nlohmann::json::parse(readText(dir / "net.json"));
    CHECK(doc.at("origin") == nlohmann::json::array({512346.0, 5412346.0, 235.0}));
    for (std::size_t k = 0; k < sys.knotCount(); ++k) {
        const auto& local = doc.at("knots").at(k).at("local");
        CHECK(Vec3{local.at(0), local.at(1), local.at(2)} == sys.position[k]);
    }
    const Tube home = tubeWithChild();
    exportFile(home.s, home.compiled, {}, dir / "home.json");
    const auto atHome = nlohmann::json::parse(readText(dir / "home.json"));
    CHECK_FALSE(atHome.contains("origin")); // about (0, 0, 0) the positions are the local ones
    CHECK_FALSE(atHome.at("knots").at(0).contains("local"));

    exportFile(far.s, far.compiled, {}, dir / "net.glb");
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    REQUIRE(loader.LoadBinaryFromFile(&model, &error, &warning, (dir / "net.glb").string()));
    REQUIRE(model.nodes.size() == 4); // the root, the two pieces, the rail
    // z up turned to glTF's y up: (x, y, z) -> (x, z, -y), the translation too.
    CHECK(model.nodes[0].translation == std::vector<double>{512346, 235, -5412346});
    checkFirstBarEnd(model, sys);
    // within the ring's metre of the origin, where floats hold 1e-7 m
    CHECK(std::abs(firstPrimitivePositions(model)[0]) < 2);
}

TEST_CASE("OBJ and PLY: knots and bars as lines, or bars as tubes") {
    Tube t = tubeWithChild();
    const auto& sys = t.compiled.system;
    const auto dir = outputDir("export-mesh");
    exportFile(t.s, t.compiled, {}, dir / "net.obj");
    const std::string obj = readText(dir / "net.obj");
    CHECK(countPrefix(obj, "v ") == sys.knotCount() + 12); // the ring's 12 points
    CHECK_THAT(obj, Contains(" " + std::to_string(sys.knotCount() + 12) + " " +
                             std::to_string(sys.knotCount() + 1) + "\n"));
    CHECK(countPrefix(obj, "l ") == sys.barCount() + t.s.rails.size());
    CHECK(countPrefix(obj, "o piece_") == t.s.pieces.size());
    CHECK_THAT(obj, Contains("o piece_1_upper\n"));

    ExportOptions tubes;
    tubes.tubeRadius = 0.004;
    exportFile(t.s, t.compiled, {}, dir / "tubes.obj", tubes);
    const std::string tubeObj = readText(dir / "tubes.obj");
    CHECK(countPrefix(tubeObj, "f ") == 2 * 8 * sys.barCount());
    CHECK(countPrefix(tubeObj, "l ") == t.s.rails.size());

    exportFile(t.s, t.compiled, {}, dir / "net.ply");
    const std::string ply = readText(dir / "net.ply");
    const std::size_t railPoints = t.s.rails.begin()->second.curve().spec().points.size();
    CHECK_THAT(ply,
               Contains("element vertex " + std::to_string(sys.knotCount() + railPoints) + "\n"));
    CHECK_THAT(ply, Contains("element edge " + std::to_string(sys.barCount() + railPoints) + "\n"));
    const auto plyLines = lines(ply);
    const auto header = std::find(plyLines.begin(), plyLines.end(), "end_header");
    REQUIRE(header != plyLines.end());
    CHECK(std::size_t(plyLines.end() - header - 1) ==
          sys.knotCount() + railPoints + sys.barCount() + railPoints);
    const auto first = fields(*(header + 1), ' ');
    CHECK(Vec3{number(first[0]), number(first[1]), number(first[2])} == sys.position[0]);

    exportFile(t.s, t.compiled, {}, dir / "tubes.ply", tubes);
    CHECK_THAT(readText(dir / "tubes.ply"),
               Contains("element face " + std::to_string(16 * sys.barCount()) + "\n"));
}

TEST_CASE("glb loads back with tinygltf: two vertices per bar, colours, tension, rails") {
    Tube t = tubeWithChild();
    const auto& sys = t.compiled.system;
    const auto file = outputDir("export-glb") / "net.glb";
    exportFile(t.s, t.compiled, {}, file);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    REQUIRE(loader.LoadBinaryFromFile(&model, &error, &warning, file.string()));
    INFO(error << warning);
    // A mesh and a node per piece (the ring and its child), then the rails, under one root.
    REQUIRE(model.meshes.size() == 3);
    CHECK(model.meshes[0].name == "piece 1 (upper)");
    CHECK(model.meshes[2].name == "rails");
    std::size_t barVertices = 0;
    for (std::size_t m = 0; m < 2; ++m) {
        REQUIRE(model.meshes[m].primitives.size() == 1);
        const tinygltf::Primitive& net = model.meshes[m].primitives[0];
        CHECK(net.mode == TINYGLTF_MODE_LINE);
        const tinygltf::Accessor& positions =
            model.accessors[std::size_t(net.attributes.at("POSITION"))];
        CHECK(positions.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT);
        CHECK(model.accessors[std::size_t(net.attributes.at("COLOR_0"))].count == positions.count);
        CHECK(model.accessors[std::size_t(net.attributes.at("_TENSION"))].count ==
              positions.count);
        barVertices += positions.count;
    }
    CHECK(barVertices == 2 * sys.barCount());
    // The ring of 12 columns and 5 rows has 12 x 2 x 4 bars; its child the rest.
    CHECK(model.accessors[std::size_t(model.meshes[0].primitives[0].attributes.at("POSITION"))]
              .count == 2 * 12 * 2 * 4);
    checkFirstBarEnd(model, sys); // the first bar's first end is where the knot is (a float)
    const tinygltf::Primitive& rails = model.meshes[2].primitives[0];
    CHECK(model.accessors[std::size_t(rails.attributes.at("POSITION"))].count ==
          2 * 12); // the ring's 12 segments
    REQUIRE(model.nodes.size() == 4);
    CHECK(model.nodes[0].rotation.size() == 4);
    CHECK(model.nodes[0].children == std::vector<int>{1, 2, 3});
    CHECK(model.nodes[1].mesh == 0);
    CHECK(model.nodes[1].name == "piece 1 (upper)");

    ExportOptions tubes;
    tubes.tubeRadius = 0.005;
    exportFile(t.s, t.compiled, {}, file, tubes);
    tinygltf::Model tubeModel;
    REQUIRE(loader.LoadBinaryFromFile(&tubeModel, &error, &warning, file.string()));
    std::size_t tubeVertices = 0, tubeIndices = 0;
    for (std::size_t m = 0; m < 2; ++m) {
        const tinygltf::Primitive& mesh = tubeModel.meshes[m].primitives.at(0);
        CHECK(mesh.mode == TINYGLTF_MODE_TRIANGLES);
        tubeVertices += tubeModel.accessors[std::size_t(mesh.attributes.at("POSITION"))].count;
        tubeIndices += tubeModel.accessors[std::size_t(mesh.indices)].count;
    }
    CHECK(tubeVertices == 16 * sys.barCount());
    CHECK(tubeIndices == 3 * 16 * sys.barCount());
}

TEST_CASE("JSON document: rails, pieces, knots and bars with round-trip numbers, and the report") {
    Tube t = tubeWithChild();
    const auto& sys = t.compiled.system;
    const auto file = outputDir("export-json") / "design.json";
    exportFile(t.s, t.compiled, {}, file);
    const nlohmann::json doc = nlohmann::json::parse(readText(file));
    CHECK(doc["format"] == "netsculpt-export");
    CHECK(doc["units"] == "m");
    REQUIRE(doc["knots"].size() == sys.knotCount());
    REQUIRE(doc["bars"].size() == sys.barCount());
    for (std::size_t k = 0; k < sys.knotCount(); ++k) {
        const auto& p = doc["knots"][k]["position"];
        CHECK(Vec3{p[0].get<double>(), p[1].get<double>(), p[2].get<double>()} == sys.position[k]);
    }
    CHECK(doc["bars"][5]["rest_length"].get<double>() == sys.restLength[5]);
    CHECK(doc["pieces"].size() == 2);
    CHECK(doc["pieces"][0]["knots"].size() == 60);
    CHECK(doc["rails"][0]["closed"] == true);
    CHECK(doc["rails"][0]["points"].size() == 12);
    CHECK(doc["report"]["knots"] == sys.knotCount());
    CHECK(doc["report"]["pieces"].size() == 2);
}

TEST_CASE("export refuses unknown formats and bad options, and never leaves a partial file") {
    SheetNet t = sheet(3, 3, 1.0, 0.4);
    const auto dir = outputDir("export-errors");
    CHECK_THROWS_WITH(exportFile(t.s, t.compiled, {}, dir / "net.stl"),
                      Contains("net.stl") && Contains(".stl") &&
                          Contains("csv, obj, ply, glb, json, svg, png"));
    CHECK_THROWS_WITH(exportFile(t.s, t.compiled, {}, dir / "net"), Contains("without extension"));
    ExportOptions bad;
    bad.width = 8;
    CHECK_THROWS_WITH(exportFile(t.s, t.compiled, {}, dir / "net.png", bad),
                      Contains("width") && Contains("got 8"));
    bad = {};
    bad.view = "bottom";
    CHECK_THROWS_WITH(exportFile(t.s, t.compiled, {}, dir / "net.svg", bad),
                      Contains("view") && Contains("bottom"));
    bad = {};
    bad.colourBy = "mood";
    CHECK_THROWS_WITH(exportFile(t.s, t.compiled, {}, dir / "net.png", bad),
                      Contains("\"piece\" or \"tension\""));
    bad = {};
    bad.tubeRadius = -1;
    CHECK_THROWS_WITH(exportFile(t.s, t.compiled, {}, dir / "net.obj", bad),
                      Contains("tube_radius"));
    // A failed export leaves an existing file as it was, and no temporary files behind.
    writeText(dir / "net.png", "previous");
    bad = {};
    bad.height = 100000;
    CHECK_THROWS(exportFile(t.s, t.compiled, {}, dir / "net.png", bad));
    CHECK(readText(dir / "net.png") == "previous");
    CHECK_THROWS_WITH(exportFile(t.s, t.compiled, {}, dir / "missing" / "net.csv"),
                      Contains("cannot create"));
    exportFile(t.s, t.compiled, {}, dir / "net.png");
    CHECK(readText(dir / "net.png").rfind("\x89PNG", 0) == 0);
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        files += entry.is_regular_file();
    CHECK(files == 1);
}
