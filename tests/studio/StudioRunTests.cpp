// netsculpt-studio itself, under Xvfb: it replays tests/data/studio/add_rows.events on the demo,
// then the test reads the journal the studio wrote (the expected commands, one undo step) and the
// screenshot (the net is drawn, in the piece colours, where the fixed camera projects its knots);
// hold_rows.events checks when the studio refines; a connect drag released over a panel
// connects nothing.

#include "commands/Journal.h"
#include "interaction/DemoScenes.h"
#include "interaction/Handles.h"
#include "Panels.h" // tools/studio: the panels the studio frames around

#include <catch2/catch.hpp>
#include <stb_image.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

using namespace netsculpt;
namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 1280, kHeight = 800;

struct Image {
    int width = 0, height = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> pixels{nullptr, stbi_image_free};
    const unsigned char* at(int x, int y) const { return pixels.get() + (std::size_t(y) * width + x) * 3; }
};

Image readPng(const fs::path& path) {
    Image image;
    int channels = 0;
    image.pixels.reset(stbi_load(path.string().c_str(), &image.width, &image.height, &channels, 3));
    REQUIRE(image.pixels);
    return image;
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

/// An empty output folder for the run `name`.
fs::path outputFolder(const std::string& name) {
    const fs::path out = fs::path(NETSCULPT_BINARY_DIR) / "tests" / "studio" / name;
    fs::remove_all(out);
    fs::create_directories(out);
    return out;
}

/// Runs the studio under Xvfb with `arguments`, its output in `out`/log.txt, journaling to
/// `out`/out.netj; requires that it exits cleanly and returns what it printed.
std::string runUnderXvfb(const fs::path& out, const std::string& arguments) {
    const std::string command = "xvfb-run -a -s \"-screen 0 1280x800x24\" \"" +
                                std::string(NETSCULPT_STUDIO_EXE) + "\" " + arguments +
                                " --journal \"" + (out / "out.netj").string() + "\" > \"" +
                                (out / "log.txt").string() + "\" 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream log(out / "log.txt");
    std::stringstream text;
    text << log.rdbuf();
    INFO(command << "\n" << text.str());
    REQUIRE(status == 0);
    return text.str();
}

/// Runs the studio on the demo with the add_rows events; returns the folder of its outputs.
fs::path runStudio(const std::string& name, const std::string& extra) {
    const fs::path out = outputFolder(name);
    const fs::path events = fs::path(NETSCULPT_SOURCE_DIR) / "tests/data/studio/add_rows.events";
    runUnderXvfb(out, "--demo --play \"" + events.string() + "\" --screenshot \"" +
                          (out / "out.png").string() +
                          "\" --exit-after-frames 40 --size 1280x800 " + extra);
    REQUIRE(fs::exists(out / "out.png"));
    REQUIRE(fs::exists(out / "out.netj"));
    return out;
}

/// The camera the studio starts with: the demo framed in a 1280 x 800 window.
Camera studioCamera() {
    Document demo;
    buildDemoSculpture(demo);
    Camera camera(kWidth, kHeight);
    camera.frameInset = studio::Panels::kFrameInset;
    const auto [lo, hi] = sceneBounds(demo.sculpture(), demo.compiled());
    camera.frame(lo, hi);
    return camera;
}

/// The pixel has the hue of one of the colours (shading and fog change brightness, not hue).
bool netColoured(const unsigned char* p, const std::vector<Colour>& colours) {
    const double mean = (p[0] + p[1] + p[2]) / 3.0;
    const double v[3] = {p[0] - mean, p[1] - mean, p[2] - mean};
    const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (norm < 20) return false; // grey: background, grid, rails
    for (const Colour& c : colours) {
        const double m = (c.r + c.g + c.b) / 3;
        const double w[3] = {c.r - m, c.g - m, c.b - m};
        const double cosine = (v[0] * w[0] + v[1] * w[1] + v[2] * w[2]) /
                              (norm * std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]));
        if (cosine > 0.85) return true;
    }
    return false;
}

std::vector<Colour> pieceColours(const Sculpture& s) {
    std::vector<Colour> colours;
    for (const auto& [id, p] : s.pieces) colours.push_back(p.colour);
    return colours;
}

/// The part of the window no panel covers: between the inspector, the solver and the bars.
constexpr int kViewLeft = 330, kViewRight = 990, kViewTop = 80, kViewBottom = 760;

/// Share of the view's pixels in a piece colour (the panels are left out: ImGui's blue is a hue too).
double netColouredFraction(const Image& image, const std::vector<Colour>& colours) {
    std::size_t hits = 0;
    for (int y = kViewTop; y < kViewBottom; ++y)
        for (int x = kViewLeft; x < kViewRight; ++x) hits += netColoured(image.at(x, y), colours);
    return double(hits) / (double(kViewRight - kViewLeft) * (kViewBottom - kViewTop));
}

/// The journal holds the demo's seven commands, then set_rows on piece 2 up to 8 + 5 = 13 rows, merged
/// into one undo step.
void checkJournal(const fs::path& journal) {
    const JournalContents contents = readJournal(journal);
    CHECK(contents.warnings.empty());
    const auto& e = contents.entries;
    REQUIRE(e.size() >= 8);
    const char* demo[] = {"add_rail",       "add_rail",        "add_rail",      "attach_to_rail",
                          "attach_to_piece", "connect_to_rail", "attach_to_rail"};
    for (std::size_t i = 0; i < 7; ++i) CHECK(commandName(e[i].command) == demo[i]);
    for (std::size_t i = 7; i < e.size(); ++i) {
        REQUIRE(e[i].kind == JournalEntry::Kind::Command);
        const auto* rows = std::get_if<SetRowsCommand>(&e[i].command);
        REQUIRE(rows);
        CHECK(rows->piece == PieceId(2));
        CHECK(e[i].merge == (i > 7)); // the first step of the drag opens the undo step
    }
    CHECK(std::get<SetRowsCommand>(e.back().command).rows == 13);

    Document replayed = Document::open(journal);
    CHECK(replayed.sculpture().piece(PieceId(2)).rows == 13);
    replayed.undo();
    CHECK(replayed.sculpture().piece(PieceId(2)).rows == 8); // the whole drag was one undo step
}

} // namespace

TEST_CASE("studio: the add_rows events add five rows with one undo step and the net is drawn", "[studio]") {
    const fs::path out = runStudio("relaxing", "");
    checkJournal(out / "out.netj");
    const Image image = readPng(out / "out.png");
    REQUIRE(image.width == kWidth);
    REQUIRE(image.height == kHeight);
    Document replayed = Document::open(out / "out.netj");
    // Not blank: a good share of the view is net (about 10 % for the demo at this size).
    CHECK(netColouredFraction(image, pieceColours(replayed.sculpture())) > 0.03);
}

TEST_CASE("studio: without relaxation the net is drawn exactly where the camera projects its knots", "[studio]") {
    const fs::path out = runStudio("still", "--no-relax");
    checkJournal(out / "out.netj");
    const Image image = readPng(out / "out.png");
    REQUIRE(image.width == kWidth);
    const Document replayed = Document::open(out / "out.netj"); // the same positions: Eq. 1-2, carried
    const std::vector<Colour> colours = pieceColours(replayed.sculpture());
    const Camera camera = studioCamera();
    const MassSpringSystem& sys = replayed.compiled().system;
    std::size_t checked = 0, drawn = 0;
    for (std::size_t j = 0; j < sys.knotCount(); ++j) {
        if (sys.fixed[j]) continue; // under the rails' thick lines
        const ScreenPoint sp = camera.project(sys.position[j]);
        if (!sp.visible || sp.x < kViewLeft || sp.x > kViewRight || sp.y < kViewTop || sp.y > kViewBottom) continue;
        ++checked;
        bool found = false;
        for (int dy = -2; dy <= 2 && !found; ++dy)
            for (int dx = -2; dx <= 2 && !found; ++dx)
                found = netColoured(image.at(int(sp.x) + dx, int(sp.y) + dy), colours);
        drawn += found;
    }
    INFO(drawn << " of " << checked << " knots show in a piece colour");
    CHECK(checked > 500);
    CHECK(double(drawn) / double(checked) > 0.95);
    // And away from the net (the top-left of the view, above the crown) there is none.
    std::size_t stray = 0;
    for (int y = 90; y < 180; ++y)
        for (int x = 330; x < 420; ++x) stray += netColoured(image.at(x, y), colours);
    CHECK(stray == 0);
}

TEST_CASE(
    "studio: no refine starts while a handle is held - it starts once the handle is released") {
    // hold_rows.events drags piece 2's last row down two rows and holds the button: the preview
    // settles at its soft stiffness and stays there (a refine would be cut short by the drag's
    // next step). Released, the studio refines. --settle waits, at the last frame, for the runs.
    const fs::path events = fs::path(NETSCULPT_SOURCE_DIR) / "tests/data/studio/hold_rows.events";
    const fs::path held = outputFolder("hold");
    const std::string heldLog = runUnderXvfb(
        held, "--demo --play \"" + events.string() + "\" --exit-after-frames 260 --settle 60");
    CHECK_THAT(heldLog, Catch::Matchers::Contains("relaxation converged") &&
                            Catch::Matchers::Contains("at stiffness x0.01"));
    std::ifstream in(events);
    std::stringstream text;
    text << in.rdbuf() << "release left\nframe 2\n";
    const fs::path released = outputFolder("release");
    std::ofstream(released / "release.events") << text.str();
    const std::string releasedLog =
        runUnderXvfb(released, "--demo --play \"" + (released / "release.events").string() +
                                   "\" --exit-after-frames 260 --settle 60");
    CHECK_THAT(releasedLog, Catch::Matchers::Contains("relaxation converged") &&
                                Catch::Matchers::Contains("at stiffness x1\n"));
    // Both journals hold the same drag: two rows more on piece 2.
    CHECK(Document::open(held / "out.netj").sculpture().piece(PieceId(2)).rows == 10);
    CHECK(Document::open(released / "out.netj").sculpture().piece(PieceId(2)).rows == 10);
}

TEST_CASE("studio: a Lua script's commands become the session's journal") {
    const fs::path out = outputFolder("script");
    const fs::path script = fs::path(NETSCULPT_SOURCE_DIR) / "scripts/paper/fig07_gears.lua";
    runUnderXvfb(out, "--script \"" + script.string() + "\" --exit-after-frames 5 --no-relax");
    // fig07 hangs one child below each of five tubes of 24 columns, through gears 3, 2, 1, 1/2, 1/3.
    const JournalContents journal = readJournal(out / "out.netj");
    std::vector<std::string> gears;
    for (const JournalEntry& entry : journal.entries)
        if (const auto* attach = std::get_if<AttachToPieceCommand>(&entry.command))
            gears.push_back(toString(attach->args.gear));
    CHECK(gears == std::vector<std::string>{"3", "2", "1", "1/2", "1/3"});
}

TEST_CASE("studio: a --journal that holds work is kept, never journaled over unasked") {
    const fs::path out = outputFolder("journal-kept");
    Document demo;
    buildDemoSculpture(demo);
    demo.save(out / "design.netj");
    fs::copy_file(out / "design.netj", out / "out.netj");
    const std::string work = readFile(out / "out.netj");
    // No design given: the studio asks whether to go on with it, and leaves it as it is.
    runUnderXvfb(out, "--exit-after-frames 3 --no-relax");
    CHECK(readFile(out / "out.netj") == work);
    CHECK_FALSE(fs::exists(out / "out.previous.netj"));
    // A design given: the work is kept beside it before the session journals afresh.
    const std::string log = runUnderXvfb(out, "--demo --exit-after-frames 3 --no-relax");
    CHECK_THAT(log, Catch::Matchers::Contains("held work: it is kept as"));
    CHECK(readFile(out / "out.previous.netj") == work);
    CHECK(readJournal(out / "out.netj").entries.size() == 7); // the demo's, journaled anew
}

TEST_CASE("studio: a relaxed snapshot opens as it is, without a soft preview") {
    const fs::path out = outputFolder("snapshot");
    Document demo;
    buildDemoSculpture(demo);
    REQUIRE(demo.relax().converged);
    demo.saveSnapshot(out / "demo.nets");
    const std::string log =
        runUnderXvfb(out, "--open \"" + (out / "demo.nets").string() + "\" --exit-after-frames 20");
    // No frame was drawn while relaxing: the live relaxation had nothing to do.
    CHECK_THAT(log, Catch::Matchers::Contains("while relaxing (0 frames"));
    // The session journal holds the snapshot's history.
    CHECK(readJournal(out / "out.netj").entries.size() == 7);
}

namespace {

/// Window pixels that one of the studio's side panels covers whatever it shows: the inspector
/// (left; its piece fields once a press has selected a piece) and the solver (right).
bool underSidePanel(const ScreenPoint& p) {
    const bool inspector = p.x > 40 && p.x < 270 && p.y > 90 && p.y < 290;
    const bool solver = p.x > 1020 && p.x < 1260 && p.y > 50 && p.y < 115;
    return p.visible && (inspector || solver);
}

/// Window pixels well inside the view, clear of every panel.
bool inOpenView(const ScreenPoint& p) {
    return p.visible && p.x > kViewLeft + 20 && p.x < kViewRight - 20 && p.y > kViewTop + 40 &&
           p.y < kViewBottom - 40;
}

/// A camera on the demo (the studio's, zoomed in by `notches`) where the sheet's last-row sphere
/// (piece 3, the demo's one free last row) shows in the view, with the rail positions it may
/// connect to: one behind a side panel, one in the view.
struct ConnectScene {
    int notches = 0;
    ScreenPoint source, behindPanel, inView;
};

std::optional<ConnectScene> findConnectScene() {
    Document demo;
    buildDemoSculpture(demo);
    const Handle source = handlesForMode(Mode::Connect, demo.sculpture(), demo.compiled()).front();
    const std::vector<Handle> targets =
        connectTargets(demo.sculpture(), demo.compiled(), source.piece);
    for (int notches = 0; notches <= 8; ++notches) {
        Camera camera = studioCamera();
        camera.zoom(notches);
        ConnectScene scene{notches, camera.project(source.position), {}, {}};
        if (!inOpenView(scene.source))
            continue;
        bool behind = false, open = false;
        for (const Handle& t : targets) {
            const ScreenPoint p = camera.project(t.position);
            if (!behind && underSidePanel(p))
                scene.behindPanel = p, behind = true;
            if (!open && inOpenView(p))
                scene.inView = p, open = true;
        }
        if (behind && open)
            return scene;
    }
    return std::nullopt;
}

/// Events: zoom in, connect mode, the last row carried from its sphere to `to` in ten moves (a
/// frame each) and released there.
std::string connectDragEvents(const ConnectScene& scene, const ScreenPoint& to) {
    std::ostringstream events;
    events << "frame 3\n";
    if (scene.notches > 0)
        events << "scroll " << scene.notches << "\nframe 2\n";
    events << "key j\nframe 2\nmove " << scene.source.x << ' ' << scene.source.y
           << "\nframe 2\npress left\nframe 2\n";
    for (int i = 1; i <= 10; ++i)
        events << "move " << scene.source.x + (to.x - scene.source.x) * i / 10 << ' '
               << scene.source.y + (to.y - scene.source.y) * i / 10 << "\nframe 1\n";
    events << "frame 2\nrelease left\nframe 3\n";
    return events.str();
}

/// Runs the demo (no relaxation) with `events`; returns the journal's entries.
std::vector<JournalEntry> runDemoEvents(const std::string& name, const std::string& events) {
    const fs::path out = outputFolder(name);
    std::ofstream(out / "drag.events") << events;
    runUnderXvfb(out, "--demo --no-relax --size 1280x800 --play \"" +
                          (out / "drag.events").string() + "\" --exit-after-frames 40 " +
                          "--screenshot \"" + (out / "out.png").string() + "\"");
    return readJournal(out / "out.netj").entries;
}

} // namespace

TEST_CASE("studio: a connect drop released over a panel connects nothing, though a rail sphere "
          "lies behind it") {
    const std::optional<ConnectScene> scene = findConnectScene();
    REQUIRE(scene);
    INFO("zoomed in " << scene->notches << " notches; the sheet's sphere at " << scene->source.x
                      << ", " << scene->source.y);
    // Dropped on a rail sphere in the view, the row connects: the drag reaches the rails.
    const auto connected =
        runDemoEvents("connect-in-view", connectDragEvents(*scene, scene->inView));
    REQUIRE(connected.size() == 8); // the demo's seven commands, and the drop's
    CHECK(commandName(connected.back().command) == "connect_to_rail");
    // Dropped where a panel covers a rail sphere, nothing changes and nothing is journaled.
    INFO("dropped at " << scene->behindPanel.x << ", " << scene->behindPanel.y);
    const auto dropped =
        runDemoEvents("connect-over-panel", connectDragEvents(*scene, scene->behindPanel));
    CHECK(dropped.size() == 7);
}
