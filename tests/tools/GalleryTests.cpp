// The gallery (scripts/): every script runs through `netsculpt run` (quick: NETSCULPT_QUICK=1,
// short relaxations) and the numbers its figure is about are checked from the files it wrote.

#include "CliSupport.h"

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace netsculpt::test;
using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// One line of a knots CSV (DESIGN.md: piece,row,column,x,y,z,fixed); the text of x, y, z is kept
/// to compare positions bit for bit.
struct Knot {
    int piece = 0, row = 0, column = 0;
    double x = 0, y = 0, z = 0;
    bool fixed = false;
    std::string position;
};

std::vector<Knot> readKnots(const fs::path& file) {
    std::ifstream in(file);
    REQUIRE(in);
    std::string line;
    std::getline(in, line);
    REQUIRE(line == "piece,row,column,x,y,z,fixed");
    std::vector<Knot> knots;
    while (std::getline(in, line)) {
        std::stringstream fields(line);
        std::string f[7];
        for (std::string& field : f)
            std::getline(fields, field, ',');
        Knot k{std::stoi(f[0]), std::stoi(f[1]), std::stoi(f[2]), std::stod(f[3]),
               std::stod(f[4]), std::stod(f[5]), f[6] == "1",     f[3] + "," + f[4] + "," + f[5]};
        knots.push_back(k);
    }
    return knots;
}

json readJson(const fs::path& file) {
    std::ifstream in(file);
    REQUIRE(in);
    return json::parse(in);
}

/// Runs scripts/<script> into a fresh folder and returns the folder.
fs::path runGallery(const std::string& script, const std::string& extra = "") {
    const fs::path out = freshFolder("gallery-" + fs::path(script).stem().string());
    const fs::path file = fs::path(NETSCULPT_SCRIPTS_DIR) / script;
    const Ran ran = runCli("run " + quoted(file) + " --out " + quoted(out) + " --quiet" + extra,
                           "NETSCULPT_QUICK=1");
    INFO(ran.output);
    REQUIRE(ran.exitCode == 0);
    return out;
}

/// A relaxed figure tied between rails must hang as rope can: no bar stretched by more than the
/// report's limit (2 %). The figures tied to a lower rail once pulled theirs 7 %, 57 % and 27 %.
/// (Only a relaxed shape says so; a sanitizer build may not relax within the quick cap.)
void checkHangsAsRope(const json& report) {
    if (report["relaxed"] != true) {
        WARN("not relaxed within the quick cap: how it hangs is not checked");
        return;
    }
    CHECK(report["overstretched_bars"] == 0);
    CHECK(report["max_strain"].get<double>() < 1e-4);
}

std::vector<Knot> ofPiece(const std::vector<Knot>& knots, int piece) {
    std::vector<Knot> out;
    std::copy_if(knots.begin(), knots.end(), std::back_inserter(out),
                 [&](const Knot& k) { return k.piece == piece; });
    return out;
}

int countIf(const std::vector<Knot>& knots, bool (*pred)(const Knot&)) {
    return int(std::count_if(knots.begin(), knots.end(), pred));
}

/// rows x columns of a piece's knots in the CSV (max index + 1), checking the grid is complete.
std::pair<int, int> gridOf(const std::vector<Knot>& knots) {
    int rows = 0, columns = 0;
    for (const Knot& k : knots)
        rows = std::max(rows, k.row + 1), columns = std::max(columns, k.column + 1);
    CHECK(int(knots.size()) == rows * columns);
    return {rows, columns};
}

const json& pieceNamed(const json& report, const std::string& name) {
    for (const json& p : report["pieces"])
        if (p["name"] == name)
            return p;
    FAIL("no piece named " << name);
    throw std::logic_error("unreachable");
}

double minZ(const std::vector<Knot>& knots) {
    double z = INFINITY;
    for (const Knot& k : knots)
        z = std::min(z, k.z);
    return z;
}

/// The README's first Lua example, as a reader would copy it.
std::string readmeExample() {
    std::ifstream in(fs::path(NETSCULPT_SOURCE_DIR) / "README.md");
    REQUIRE(in);
    std::string line, script;
    bool inside = false;
    while (std::getline(in, line)) {
        if (!inside && line == "```lua") {
            inside = true;
        } else if (inside && line == "```") {
            return script;
        } else if (inside) {
            script += line + "\n";
        }
    }
    FAIL("README.md has no ```lua block");
    return script;
}

} // namespace

TEST_CASE("default.lua: the Quick start sculpture", "[gallery]") {
    const fs::path out = runGallery("default.lua");
    for (const char* file : {"knots.csv", "bars.obj", "sculpture.glb", "sculpture.png",
                             "report.json", "report.md", "default.netj"}) {
        INFO(file);
        CHECK(fs::file_size(out / file) > 100);
    }
    const json report = readJson(out / "report.json");
    CHECK(report["pieces"].size() == 2);
    CHECK(pieceNamed(report, "tube")["columns"] == 48);
    CHECK(pieceNamed(report, "skirt")["columns"] == 96); // gear 2
    const int knots = report["knots"];
    CHECK(knots == 48 * 20 + 96 * 16 - 48); // the skirt's top row shares 48 knots with the tube
    CHECK(readKnots(out / "knots.csv").size() == 48 * 20 + 96 * 16);
}

TEST_CASE("site.lua: a net in a surveyor's coordinates relaxes, and its files keep them",
          "[gallery]") {
    const fs::path out = runGallery("site.lua");
    const double east = 691050, north = 5335980, ground = 519.5; // as the script has them
    const std::vector<Knot> knots = readKnots(out / "knots.csv");
    REQUIRE(knots.size() == 40 * 48);
    int held = 0;
    for (const Knot& k : knots) {
        CHECK(k.x > east - 1);
        CHECK(k.x < east + 9);
        CHECK(k.y > north - 1);
        CHECK(k.y < north + 8);
        CHECK(k.z > ground);
        CHECK(k.z < ground + 8 + 1e-9);
        held += k.fixed;
    }
    CHECK(held == 2 * 40); // the top row on the upper beam, the last on the lower one
    const json report = readJson(out / "report.json");
    REQUIRE(report["relaxed"] == true);
    checkHangsAsRope(report);
    CHECK(report["force_balance"]["relative_difference"].get<double>() < 1e-9);
    // The sheet's rope is checked against the breaking load the script gives it.
    const json& sheet = report["pieces"][0];
    REQUIRE(sheet["breaking_load"] == 2200.0);
    const double tension = sheet["max_tension"].get<double>();
    CHECK(tension > 1); // the net weighs 81 N and hangs from 80 knots
    CHECK(report["min_safety_factor"].get<double>() == Approx(2200 / tension).epsilon(1e-12));
    CHECK(report["pieces_without_breaking_load"].empty());
    // Where the loads act: the upper beam's attachments 8 m above the ground, along the beam.
    const json& upper = report["rails"][0];
    REQUIRE(upper["points"].size() == 40);
    for (const json& p : upper["points"]) {
        CHECK(p["position"]["z"].get<double>() == Approx(ground + 8).margin(1e-9));
        CHECK(p["position"]["x"].get<double>() >= east - 1e-9);
        CHECK(p["position"]["x"].get<double>() <= east + 8 + 1e-9);
    }
}

TEST_CASE("README: the Lua example runs, and its net hangs from its two rails", "[gallery]") {
    const fs::path out = freshFolder("readme-example");
    {
        std::ofstream script(out / "example.lua");
        script << readmeExample() << "doc:write_report(\"report.json\")\n";
    }
    const Ran ran = runCli("run " + quoted(out / "example.lua") + " --out " + quoted(out));
    INFO(ran.output);
    REQUIRE(ran.exitCode == 0);
    CHECK(fs::file_size(out / "view.png") > 1000);
    CHECK(readKnots(out / "knots.csv").size() == 48 * 30 + 96 * 20);
    const json report = readJson(out / "report.json");
    CHECK(report["knots"] == 48 * 30 + 96 * 20 - 48); // gear 2 shares 48 of the skirt's top row
    REQUIRE(report["relaxed"] == true);
    checkHangsAsRope(report);
    double lifted = 0;
    for (const json& rail : report["rails"])
        lifted += rail["reaction"]["z"].get<double>();
    const double weight = report["total_weight"];
    CHECK(lifted == Approx(weight).epsilon(1e-9));
    CHECK(report["rails"][1]["reaction"]["z"].get<double>() > 1); // the skirt sags into its ring
}

TEST_CASE("fig01: two imported closed rails and a tube between them", "[gallery]") {
    const fs::path out = runGallery("paper/fig01_two_rails.lua");
    const json report = readJson(out / "report.json");
    REQUIRE(report["rails"].size() == 2);
    for (const json& rail : report["rails"])
        CHECK(rail["closed"] == true);
    CHECK(report["rails"][0]["length"].get<double>() == Approx(2 * M_PI * 1.5).epsilon(1e-4));
    const auto knots = readKnots(out / "knots.csv");
    CHECK(gridOf(knots) == std::pair{16, 40});
    CHECK(countIf(knots, [](const Knot& k) { return k.fixed; }) == 80);
    CHECK(countIf(knots, [](const Knot& k) {
              return k.row == 15 && k.fixed && std::abs(k.z - 2.0) < 1e-9;
          }) == 40);
    CHECK(fs::is_regular_file(out / "rails.png"));
    checkHangsAsRope(report);
}

TEST_CASE("fig03: a piece below a piece shares the parent's last row", "[gallery]") {
    const fs::path out = runGallery("paper/fig03_piece_below.lua");
    const auto knots = readKnots(out / "knots.csv");
    const auto parent = ofPiece(knots, 1), child = ofPiece(knots, 2);
    CHECK(gridOf(parent) == std::pair{10, 36});
    CHECK(gridOf(child) == std::pair{8, 36});
    std::map<int, std::string> lastRow;
    for (const Knot& k : parent)
        if (k.row == 9)
            lastRow[k.column] = k.position;
    for (const Knot& k : child)
        if (k.row == 0)
            CHECK(k.position == lastRow.at(k.column));
    CHECK(readJson(out / "report.json")["knots"] == 36 * 10 + 36 * 8 - 36);
}

TEST_CASE("fig04: a split changes ownership, never the net", "[gallery]") {
    const fs::path out = runGallery("paper/fig04_split.lua");
    const auto before = readKnots(out / "before.csv"), after = readKnots(out / "after.csv");
    CHECK(gridOf(before) == std::pair{12, 48});
    CHECK(gridOf(ofPiece(after, 1)) == std::pair{12, 13});
    CHECK(gridOf(ofPiece(after, 2)) == std::pair{12, 37});
    std::set<std::string> a, b;
    for (const Knot& k : before)
        a.insert(k.position);
    for (const Knot& k : after)
        b.insert(k.position);
    CHECK(a == b);
    const json report = readJson(out / "report.json");
    for (const json& p : report["pieces"])
        CHECK(p["closed"] == false);
}

TEST_CASE("fig05: rows", "[gallery]") {
    const fs::path out = runGallery("paper/fig05_rows.lua");
    const auto knots = readKnots(out / "knots.csv");
    double previous = INFINITY;
    for (int piece = 1; piece <= 3; ++piece) {
        const auto mine = ofPiece(knots, piece);
        CHECK(gridOf(mine) == std::pair{6 * piece, 24});
        CHECK(minZ(mine) < previous); // more rows hang lower
        previous = minZ(mine);
    }
}

TEST_CASE("fig06: columns", "[gallery]") {
    const fs::path out = runGallery("paper/fig06_columns.lua");
    const double ringLength = 120 * 2 * 1.2 * std::sin(M_PI / 120);
    for (int columns : {24, 36, 60}) {
        INFO(columns << " columns");
        const auto knots = readKnots(out / ("knots_" + std::to_string(columns) + ".csv"));
        CHECK(gridOf(knots) == std::pair{10, columns});
        std::vector<Knot> top;
        for (const Knot& k : knots)
            if (k.row == 0)
                top.push_back(k);
        double perimeter = 0;
        for (std::size_t i = 0; i < top.size(); ++i) {
            const Knot &p = top[i], &q = top[(i + 1) % top.size()];
            perimeter += std::hypot(q.x - p.x, q.y - p.y, q.z - p.z);
        }
        CHECK(perimeter / columns ==
              Approx(ringLength / columns).epsilon(1e-2)); // chords cut the corners
    }
}

TEST_CASE("fig07: gears multiply the columns", "[gallery]") {
    const fs::path out = runGallery("paper/fig07_gears.lua");
    const json report = readJson(out / "report.json");
    const auto knots = readKnots(out / "knots.csv");
    const std::pair<const char*, int> expected[] = {
        {"gear 3", 72}, {"gear 2", 48}, {"gear 1", 24}, {"gear 1/2", 12}, {"gear 1/3", 8}};
    for (const auto& [name, columns] : expected) {
        INFO(name);
        const json& child = pieceNamed(report, name);
        CHECK(child["columns"] == columns);
        CHECK(gridOf(ofPiece(knots, child["id"])) == std::pair{6, columns});
    }
}

TEST_CASE("fig08: bar length graded by row", "[gallery]") {
    const fs::path out = runGallery("paper/fig08_bar_length.lua");
    const json report = readJson(out / "report.json");
    for (double l : pieceNamed(report, "constant")["bar_lengths"])
        CHECK(l == 0.2);
    const json& graded = pieceNamed(report, "graded by row");
    CHECK(graded["bar_axis"] == "row");
    const auto& lengths = graded["bar_lengths"];
    REQUIRE(lengths.size() == 12);
    for (std::size_t row = 0; row < 12; ++row)
        CHECK(lengths[row].get<double>() == Approx(0.12 + 0.2 * double(row) / 11));
}

TEST_CASE("fig09: equal bar lengths at every seam", "[gallery]") {
    const fs::path out = runGallery("paper/fig09_seams.lua");
    const json report = readJson(out / "report.json");
    std::map<int, json> byId;
    for (const json& p : report["pieces"])
        byId[p["id"]] = p;
    int seams = 0;
    for (const auto& [id, p] : byId)
        for (const json& seam : p["seams"])
            if (seam["side"] == "right") {
                const json& right = byId.at(seam["piece"]);
                CHECK(p["bar_lengths"].back() == right["bar_lengths"].front());
                ++seams;
            }
    CHECK(seams == 3);
    CHECK(pieceNamed(report, "part a")["bar_lengths"].back() == 0.3);
    CHECK(pieceNamed(report, "part b")["bar_lengths"].back() == 0.15);
    CHECK(pieceNamed(report, "part c")["bar_lengths"].back() == 0.2);
}

TEST_CASE("fig10: before and after relaxation", "[gallery]") {
    const fs::path out = runGallery("paper/fig10_relax.lua");
    const json before = readJson(out / "before.json"), after = readJson(out / "after.json");
    CHECK(before["relaxed"] == false);
    CHECK(after["relaxed"] == true);
    CHECK(after["residual"].get<double>() < 1e-4);
    const double weight = after["total_weight"];
    CHECK(after["force_balance"]["reaction_sum"]["z"].get<double>() ==
          Approx(weight).epsilon(1e-3));
    const auto a = readKnots(out / "before.csv"), b = readKnots(out / "after.csv");
    REQUIRE(a.size() == b.size());
    double moved = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        moved = std::max(moved, std::hypot(a[i].x - b[i].x, a[i].y - b[i].y, a[i].z - b[i].z));
    CHECK(moved > 0.05);
    checkHangsAsRope(after);
    CHECK(fs::is_regular_file(out / "before.png"));
    CHECK(fs::is_regular_file(out / "after.png"));
}

TEST_CASE("fig11: last rows connected to rails", "[gallery]") {
    const fs::path out = runGallery("paper/fig11_connect.lua");
    const auto knots = readKnots(out / "knots.csv");
    for (int piece = 1; piece <= 2; ++piece) {
        const auto mine = ofPiece(knots, piece);
        CHECK(gridOf(mine) == std::pair{20, 30});
        CHECK(countIf(mine, [](const Knot& k) { return k.fixed; }) == 60);
    }
    const json report = readJson(out / "report.json");
    for (const json& rail : report["rails"])
        CHECK(rail["attachments"] == 30);
    const json& twisted = pieceNamed(report, "twisted");
    CHECK(twisted["bottom"]["reverse"] == true);
    CHECK(twisted["bottom"]["at"].get<double>() == Approx(1.0 / 6));
    checkHangsAsRope(report);
}

TEST_CASE("installation.lua: an installation of 50,000+ knots", "[gallery]") {
    const fs::path out = runGallery("installation.lua");
    const json report = readJson(out / "report.json");
    CHECK(report["knots"].get<int>() >= 50000);
    CHECK(report["pieces"].size() >= 5);
    CHECK(report["rails"].size() == 5);
    int seams = 0, gears = 0;
    for (const json& p : report["pieces"]) {
        seams += int(p["seams"].size());
        if (p["top"]["kind"] == "piece" && p["top"]["gear"] != "1")
            ++gears;
    }
    CHECK(seams >= 6); // three seams, seen from both sides
    CHECK(gears >= 2);
    std::set<long> heights;
    for (const Knot& k : readKnots(out / "knots.csv"))
        if (k.fixed && k.row == 0)
            heights.insert(std::lround(k.z));
    CHECK(heights.size() >= 3);
    CHECK(report["relaxed"] == false); // CI skips the relaxation
}
