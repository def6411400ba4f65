// The studio's modes driven by scripted mouse events against a fixed camera: each gesture gives
// the expected command, the expected sculpture, and exactly one undo step.

#include "InteractionTestSupport.h"

#include "commands/Journal.h"
#include "model/Error.h"

using namespace netsculpt;
using namespace netsculpt::test;

namespace {

std::size_t journalEntries(const std::filesystem::path& path) { return readJournal(path).entries.size(); }

} // namespace

TEST_CASE("new net: a click on the third rail sphere hangs a default piece from that rail", "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::NewNet);
    std::vector<Handle> onCrown;
    for (const Handle& h : ui.handles())
        if (h.kind == HandleKind::RailPoint && h.rail == scene.crown) onCrown.push_back(h);
    REQUIRE(onCrown.size() == 12);
    const Handle third = onCrown[2];
    CHECK(third.t == Approx(2.0 / 12));
    const std::uint64_t before = scene.doc.hash();

    clickHandle(ui, third);

    const Sculpture& s = scene.doc.sculpture();
    REQUIRE(s.pieces.size() == 2);
    const Piece& p = s.pieces.rbegin()->second;
    const double length = s.rail(scene.crown).curve().length();
    CHECK(p.railTop().rail == scene.crown);
    CHECK(p.railTop().at == third.t);
    CHECK(p.columns == defaultColumns(length, true, 0.25));
    CHECK(p.columns == int(std::round(length / 0.25)));
    CHECK(p.rows == 10);
    CHECK(p.bar.at(0) == 0.25);
    CHECK(ui.selectedPiece() == p.id);
    // The crown already held the scene's net: the new piece hangs over it, and the status says so.
    CHECK_THAT(ui.message(), Catch::Matchers::Contains(toString(scene.crown) + " already holds " +
                                                       toString(scene.net)));

    scene.doc.undo(); // one command, one undo step
    CHECK(scene.doc.hash() == before);
}

TEST_CASE("new net: a click on an open rail spans it, a click on a last row hangs a piece with gear 1",
          "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::NewNet);
    clickHandle(ui, findHandle(ui, [&](const Handle& h) { return h.rail == scene.beam && h.t == 1; }));
    const Piece& sheet = scene.doc.sculpture().pieces.rbegin()->second;
    CHECK(sheet.railTop().rail == scene.beam);
    CHECK(sheet.railTop().at == 0);
    CHECK(sheet.columns == 2 / 0.25 + 1);
    CHECK_FALSE(sheet.closed);
    CHECK(ui.message() == "attach_to_rail"); // a free rail: nothing to warn of

    Material rope; // the crown net's rope, unlike the default
    rope.stiffness = 5e4;
    rope.linearDensity = 0.045;
    rope.breakingLoad = 1800;
    scene.doc.execute(SetMaterialCommand{scene.net, rope});
    clickHandle(ui, findHandle(ui, [&](const Handle& h) { return h.kind == HandleKind::LastRow && h.piece == scene.net; }));
    const Piece& child = scene.doc.sculpture().pieces.rbegin()->second;
    REQUIRE_FALSE(child.onRail());
    CHECK(child.parentTop().parents == std::vector<PieceId>{scene.net});
    CHECK(child.parentTop().gear == Gear{1, 1});
    CHECK(child.columns == 24);
    CHECK(child.bar.at(0) == 0.35);
    CHECK(child.material == rope); // knotted from its parent's rope
    // The crown net now has a child: it offers no last-row sphere any more.
    for (const Handle& h : ui.handles()) CHECK_FALSE((h.kind == HandleKind::LastRow && h.piece == scene.net));
}

TEST_CASE("new net: a piece hung from a last row graded by row takes that row's bar length",
          "[interaction]") {
    // The crown net's bars run from 0.35 m at the top to 0.3 m at its last row (row 5): a piece
    // clicked below it continues with 0.3 m. (Read at the sphere's column, 12, as if the grading
    // ran by column, they were 0.35 - 0.05 * 12 / 5 = 0.23 m.)
    Scene scene;
    scene.doc.execute(SetBarLengthCommand{scene.net, std::nullopt, 5, 0.3});
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::NewNet);
    const Handle below = findHandle(ui, [&](const Handle& h) {
        return h.kind == HandleKind::LastRow && h.piece == scene.net;
    });
    REQUIRE(below.column == 12);
    clickHandle(ui, below);
    INFO(ui.message());
    REQUIRE(scene.doc.sculpture().pieces.size() == 2);
    const Piece& child = scene.doc.sculpture().pieces.rbegin()->second;
    CHECK(child.parentTop().parents == std::vector<PieceId>{scene.net});
    CHECK(child.bar.at(0) == 0.3);
    CHECK(child.bar.at(child.columns - 1) == 0.3);
}

TEST_CASE("rows: dragging a last-row sphere down 40 px adds 5 rows as one undo step", "[interaction]") {
    Scene scene;
    TempFile journal("rows.netj");
    scene.doc.attachJournal(journal.path);
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::Rows);
    REQUIRE(ui.handles().size() == 1);
    const std::uint64_t before = scene.doc.hash();
    const std::size_t entriesBefore = journalEntries(journal.path);

    dragHandle(ui, ui.handles().front(), 40);

    CHECK(scene.doc.sculpture().piece(scene.net).rows == 6 + 5);
    CHECK_FALSE(ui.gestureActive());
    CHECK(journalEntries(journal.path) > entriesBefore); // every step of the drag is journaled, merged
    const auto entries = readJournal(journal.path).entries;
    CHECK(entries.back().merge);

    scene.doc.undo();
    CHECK(scene.doc.hash() == before);
    CHECK(scene.doc.sculpture().piece(scene.net).rows == 6);
    scene.doc.redo();
    CHECK(scene.doc.sculpture().piece(scene.net).rows == 11);

    SECTION("a drag up removes rows, never below one") {
        dragHandle(ui, ui.handles().front(), -16);
        CHECK(scene.doc.sculpture().piece(scene.net).rows == 9);
        dragHandle(ui, ui.handles().front(), -400);
        CHECK(scene.doc.sculpture().piece(scene.net).rows == 1);
    }
    SECTION("a drag shorter than one row changes nothing and journals nothing") {
        const std::size_t n = journalEntries(journal.path);
        dragHandle(ui, ui.handles().front(), 7);
        CHECK(scene.doc.sculpture().piece(scene.net).rows == 11);
        CHECK(journalEntries(journal.path) == n);
    }
}

TEST_CASE("divide: a click on a top knot splits the piece at that column", "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::Divide);
    CHECK(ui.handles().size() == 23); // a closed piece of 24 columns splits at 1 .. 23
    const Handle at8 = findHandle(ui, [](const Handle& h) { return h.column == 8; });
    const std::size_t knots = scene.doc.compiled().system.knotCount();

    clickHandle(ui, at8);

    const Sculpture& s = scene.doc.sculpture();
    REQUIRE(s.pieces.size() == 2);
    const auto& created = ui.lastCreated().pieces;
    REQUIRE(created.size() == 2);
    CHECK(s.piece(created[0]).columns == 9);
    CHECK(s.piece(created[1]).columns == 24 - 8 + 1);
    CHECK(s.seams.size() == 2);
    CHECK(scene.doc.compiled().system.knotCount() == knots); // a split changes ownership only
}

TEST_CASE("divide: a piece graded by row has no spheres, and pointing at it says why",
          "[interaction]") {
    Scene scene;
    scene.doc.execute(SetBarLengthCommand{scene.net, std::nullopt, 5, 0.3}); // graded by row
    const PieceId sheet = attachPiece(scene.doc, scene.beam, 5, 4, 0.3);
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::Divide);
    // Only the sheet's: an open sheet of 5 columns splits at 1 .. 3.
    CHECK(ui.handles().size() == 3);
    for (const Handle& h : ui.handles())
        CHECK(h.piece == sheet);

    const MassSpringSystem& sys = scene.doc.compiled().system;
    const ScreenPoint knot =
        onScreen(scene.camera, sys.position[scene.doc.compiled().knotOf(scene.net, 3, 5)]);
    moveTo(ui, knot.x, knot.y);
    REQUIRE(ui.hoveredPiece() == scene.net);
    CHECK(ui.messageIsError());
    // Split's own words, naming the piece and what to do, and the studio's way to do it.
    CHECK_THAT(ui.message(),
               Catch::Matchers::StartsWith("split: piece 1 varies its bar length by row") &&
                   Catch::Matchers::Contains("set its bar length by column (or to one length)") &&
                   Catch::Matchers::Contains("bar top and bar last row one length"));
    moveTo(ui, 5, 5); // away from every net: the mode's hint is due again
    CHECK(ui.message().empty());
    CHECK_FALSE(ui.messageIsError());

    // One length again: the spheres come back, and pointing at the piece says nothing.
    scene.doc.execute(SetBarLengthCommand{scene.net, std::nullopt, 0, 0.3});
    ui.refresh();
    CHECK(ui.handles().size() == 3 + 23);
    moveTo(ui, knot.x, knot.y);
    CHECK(ui.message().empty());
}

TEST_CASE("columns: on a rail a drag up adds columns, below a piece it steps through the gears", "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::Columns);
    dragHandle(ui, ui.handles().front(), -20); // 4 px per column
    CHECK(scene.doc.sculpture().piece(scene.net).columns == 29);
    dragHandle(ui, ui.handles().front(), 36);
    CHECK(scene.doc.sculpture().piece(scene.net).columns == 20);

    AttachToPieceArgs args;
    args.parent = scene.net;
    args.gear = Gear{1, 1};
    args.rows = 4;
    args.bar = 0.8; // long enough for gear 1/2 (twice the parent's 0.63 m spacing, halved)
    const PieceId child = scene.doc.execute(AttachToPieceCommand{args}).pieces.front();
    ui.refresh();
    const Handle edge = findHandle(ui, [&](const Handle& h) { return h.piece == child; });
    const std::uint64_t before = scene.doc.hash();

    dragHandle(ui, edge, -24); // one step up: x2
    CHECK(scene.doc.sculpture().piece(child).parentTop().gear == Gear{2, 1});
    CHECK(scene.doc.sculpture().piece(child).columns == 40);
    dragHandle(ui, findHandle(ui, [&](const Handle& h) { return h.piece == child; }), -24); // x3
    CHECK(scene.doc.sculpture().piece(child).parentTop().gear == Gear{3, 1});
    dragHandle(ui, findHandle(ui, [&](const Handle& h) { return h.piece == child; }), 72); // 3 -> 1/2
    CHECK(scene.doc.sculpture().piece(child).parentTop().gear == Gear{1, 2});
    CHECK(scene.doc.sculpture().piece(child).columns == 10);
    scene.doc.undo();
    scene.doc.undo();
    scene.doc.undo();
    CHECK(scene.doc.hash() == before); // three drags, three undo steps
}

TEST_CASE("bar length: a drag down lengthens the bars, a seam moves both partners", "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::BarLength);
    REQUIRE(ui.handles().size() == 1);
    CHECK_FALSE(ui.handles().front().barColumn.has_value()); // one bar length for a piece alone
    dragHandle(ui, ui.handles().front(), 50); // 2 mm per px
    CHECK(scene.doc.sculpture().piece(scene.net).bar.at(0) == Approx(0.45).margin(1e-12));
    dragHandle(ui, ui.handles().front(), -25);
    CHECK(scene.doc.sculpture().piece(scene.net).bar.at(7) == Approx(0.40).margin(1e-12));

    const auto parts = scene.doc.execute(SplitCommand{scene.net, 12}).pieces;
    ui.refresh();
    CHECK(ui.handles().size() == 2); // the two seams of a split tube
    const Handle seam = findHandle(ui, [&](const Handle& h) { return h.piece == parts[0]; });
    REQUIRE(seam.barColumn == 12);
    dragHandle(ui, seam, -50);
    const Sculpture& s = scene.doc.sculpture();
    CHECK(s.piece(parts[0]).bar.at(12) == Approx(0.30).margin(1e-12));
    CHECK(s.piece(parts[1]).bar.at(0) == Approx(0.30).margin(1e-12));
    CHECK(s.piece(parts[0]).bar.at(0) == Approx(0.40).margin(1e-12));
}

TEST_CASE("bar length: a piece graded by row has a sphere for its top and its last row, and a "
          "drag keeps the grading", "[interaction]") {
    Scene scene;
    scene.doc.execute(SetBarLengthCommand{scene.net, std::nullopt, 5, 0.3}); // 0.35 m -> 0.3 m
    scene.doc.endGesture();
    const std::uint64_t graded = scene.doc.hash();
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::BarLength);
    REQUIRE(ui.handles().size() == 2);
    const Handle lastRow = findHandle(ui, [](const Handle& h) { return h.barRow == 5; });
    CHECK(lastRow.row == 5);
    CHECK_FALSE(lastRow.barColumn.has_value());
    dragHandle(ui, lastRow, 10); // 2 mm per px
    const BarProfile& bar = scene.doc.sculpture().piece(scene.net).bar;
    CHECK(bar.axis == BarAxis::Row);
    CHECK(bar.at(0) == 0.35);
    CHECK(bar.at(5) == Approx(0.32).margin(1e-12));
    ui.refresh();
    const Handle top = findHandle(ui, [](const Handle& h) { return h.barRow == 0; });
    CHECK(top.row == 1); // where the top bars end
    dragHandle(ui, top, 25);
    CHECK(scene.doc.sculpture().piece(scene.net).bar.at(0) == Approx(0.40).margin(1e-12));
    CHECK(scene.doc.sculpture().piece(scene.net).bar.at(5) == Approx(0.32).margin(1e-12));
    ui.undo();
    ui.undo(); // two drags, two undo steps
    CHECK(scene.doc.hash() == graded);
}

namespace {

/// Drags handle `h` by `dy` pixels in one move, as a fast mouse does between two frames.
void jumpHandle(Interaction& ui, const Handle& h, double dy) {
    const ScreenPoint sp = onScreen(ui.camera(), h.position);
    moveTo(ui, sp.x, sp.y);
    ui.handle(MousePress{MouseButton::Left, {}});
    moveTo(ui, sp.x, sp.y + dy);
    ui.handle(MouseRelease{MouseButton::Left, {}});
}

} // namespace

TEST_CASE("bar length: a drag past the shortest allowed bar stops there and names the limit",
          "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::BarLength);
    const std::uint64_t before = scene.doc.hash();
    jumpHandle(ui, ui.handles().front(), -170); // 2 mm per px: 0.34 m shorter, to 0.01 m
    const double stopped = scene.doc.sculpture().piece(scene.net).bar.at(0);
    const long long millimetres = std::llround(stopped * 1000);
    CHECK(millimetres < 350);                     // it moved ...
    CHECK(stopped == double(millimetres) / 1000); // ... to whole millimetres, written as such
    CHECK(ui.messageIsError());
    const double beyond = double(millimetres - 1) / 1000;
    CHECK_THAT(ui.message(),
               Catch::Matchers::Contains("bar length " + formatNumber(beyond) + " m at row"));
    // One millimetre shorter is refused: the drag stopped at the limit, not short of it.
    CHECK_THROWS_AS(
        scene.doc.execute(SetBarLengthCommand{scene.net, std::nullopt, std::nullopt, beyond}),
        UserError);
    scene.doc.undo(); // one undo step, the search's tries included
    CHECK(scene.doc.hash() == before);
}

TEST_CASE("rows: a drag to one row of a piece tied by its last row stops at two, saying why",
          "[interaction]") {
    Scene scene;
    scene.doc.execute(ConnectToRailCommand{scene.net, scene.ring, 0, false});
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::Rows);
    jumpHandle(ui, ui.handles().front(), -200); // 8 px a row: far past one row
    CHECK(scene.doc.sculpture().piece(scene.net).rows == 2);
    CHECK(ui.messageIsError());
    CHECK_THAT(ui.message(),
               Catch::Matchers::Contains("has 1 row, so its last row is its top row"));
}

TEST_CASE("connect: a last row dropped on a rail sphere connects there", "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::Connect);
    REQUIRE(ui.handles().size() == 1);
    const Handle source = ui.handles().front();
    const ScreenPoint from = onScreen(scene.camera, source.position);
    moveTo(ui, from.x, from.y);
    ui.handle(MousePress{MouseButton::Left, {}});
    REQUIRE(ui.dragged().has_value());
    // While dragging, the spheres are the rail positions it may join (closed rails for a tube).
    for (const Handle& h : ui.handles()) CHECK(h.kind == HandleKind::ConnectTarget);
    for (const Handle& h : ui.handles()) CHECK(h.rail != scene.beam);
    const Handle target = findHandle(ui, [&](const Handle& h) { return h.rail == scene.ring && h.t == 0.25; });
    const ScreenPoint to = onScreen(scene.camera, target.position);
    for (int i = 1; i <= 10; ++i) moveTo(ui, from.x + (to.x - from.x) * i / 10, from.y + (to.y - from.y) * i / 10);
    REQUIRE(ui.hovered() >= 0);
    CHECK(ui.handles()[std::size_t(ui.hovered())].t == 0.25);
    ui.handle(MouseRelease{MouseButton::Left, {}});

    const Piece& p = scene.doc.sculpture().piece(scene.net);
    REQUIRE(p.bottom.has_value());
    CHECK(p.bottom->rail == scene.ring);
    CHECK(p.bottom->at == 0.25);
    CHECK_FALSE(p.bottom->reverse); // the ring winds the way the net does
    CHECK(ui.handles().empty());    // connected: no free last row left
}

namespace {

/// A connect drag begun on the net's last-row sphere, in a journaled scene.
struct ConnectDrag {
    Scene scene;
    TempFile journal;
    Interaction ui{scene.doc, scene.camera};
    std::uint64_t hash = 0;
    std::uintmax_t bytes = 0;

    explicit ConnectDrag(const std::string& journalName) : journal(journalName) {
        scene.doc.attachJournal(journal.path);
        ui.setMode(Mode::Connect);
        hash = scene.doc.hash();
        bytes = std::filesystem::file_size(journal.path);
        const ScreenPoint from = onScreen(scene.camera, ui.handles().front().position);
        moveTo(ui, from.x, from.y);
        ui.handle(MousePress{MouseButton::Left, {}});
    }
    /// The sculpture and its journal as they were before the drag, the net not connected.
    void checkNothingChanged() {
        CHECK(scene.doc.hash() == hash);
        CHECK(std::filesystem::file_size(journal.path) == bytes);
        CHECK_FALSE(scene.doc.sculpture().piece(scene.net).bottom.has_value());
    }
};

} // namespace

TEST_CASE("connect: a drop away from every rail changes nothing and journals nothing",
          "[interaction]") {
    ConnectDrag drag("connect.netj");
    Interaction& ui = drag.ui;
    moveTo(ui, 5, 5); // the window's corner: no rail there
    CHECK(ui.hovered() == -1);
    ui.handle(MouseRelease{MouseButton::Left, {}});
    drag.checkNothingChanged();
    CHECK(ui.handles().size() == 1); // back to the sources
}

TEST_CASE("connect: a drop over a panel changes nothing, though a rail sphere lies behind it",
          "[interaction]") {
    ConnectDrag drag("connect-panel.netj");
    Interaction& ui = drag.ui;
    const Scene& scene = drag.scene;
    const Handle target =
        findHandle(ui, [&](const Handle& h) { return h.rail == scene.ring && h.t == 0.25; });
    const ScreenPoint to = onScreen(scene.camera, target.position);
    moveTo(ui, to.x, to.y);
    REQUIRE(ui.hovered() >= 0); // in the view the sphere takes the drop ...
    ui.setPointerOverPanel(true);
    moveTo(ui, to.x, to.y);
    CHECK(ui.hovered() == -1); // ... behind a panel it is not offered
    ui.handle(MouseRelease{MouseButton::Left, {}});
    drag.checkNothingChanged();
    CHECK_FALSE(ui.messageIsError());
    CHECK_THAT(ui.message(), Catch::Matchers::StartsWith("connect: dropped over a panel; nothing "
                                                         "changed"));
    CHECK(ui.handles().size() == 1); // back to the sources
}

TEST_CASE("a click released over a panel does nothing, a value drag keeps what it changed",
          "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    const std::uint64_t hash = scene.doc.hash();
    // A press on a sphere in the view, the release over a panel (a sphere at a panel's edge):
    // no new net, no split.
    for (Mode mode : {Mode::NewNet, Mode::Divide}) {
        ui.setMode(mode);
        const ScreenPoint sp = onScreen(scene.camera, ui.handles().front().position);
        ui.setPointerOverPanel(false);
        moveTo(ui, sp.x, sp.y);
        ui.handle(MousePress{MouseButton::Left, {}});
        ui.setPointerOverPanel(true);
        moveTo(ui, sp.x + 3, sp.y); // within a click's slop
        ui.handle(MouseRelease{MouseButton::Left, {}});
        INFO(modeName(mode));
        CHECK(scene.doc.hash() == hash);
        CHECK(ui.message() ==
              std::string(modeName(mode)) + ": released over a panel; nothing changed");
    }
    // A click on the net released over a panel selects nothing.
    ui.setMode(Mode::View);
    ui.select(PieceId{}); // the presses on the spheres above selected their piece
    const ScreenPoint knot = onScreen(
        scene.camera,
        scene.doc.compiled().system.position[scene.doc.compiled().knotOf(scene.net, 3, 5)]);
    ui.setPointerOverPanel(false);
    moveTo(ui, knot.x, knot.y);
    ui.handle(MousePress{MouseButton::Left, {}});
    ui.setPointerOverPanel(true);
    ui.handle(MouseRelease{MouseButton::Left, {}});
    CHECK(ui.selectedPiece() == PieceId{});
    // A rows drag changes the rows as it moves, over a panel too; its release adds nothing.
    ui.setMode(Mode::Rows);
    const ScreenPoint end = onScreen(scene.camera, ui.handles().front().position);
    ui.setPointerOverPanel(false);
    moveTo(ui, end.x, end.y);
    ui.handle(MousePress{MouseButton::Left, {}});
    moveTo(ui, end.x, end.y + 8);
    ui.setPointerOverPanel(true);
    moveTo(ui, end.x, end.y + 16);
    ui.handle(MouseRelease{MouseButton::Left, {}});
    CHECK(scene.doc.sculpture().piece(scene.net).rows == 8);
    CHECK(ui.message() == "set_rows");
    ui.undo(); // one undo step
    CHECK(scene.doc.hash() == hash);
}

TEST_CASE("a mode switch clears the message about the old mode's work", "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::Rows);
    dragHandle(ui, ui.handles().front(), 16);
    CHECK(ui.message() == "set_rows");
    ui.handle(KeyPress{'R', {}}); // the mode it is in: the message stays
    CHECK(ui.message() == "set_rows");
    ui.handle(KeyPress{'J', {}});
    CHECK(ui.mode() == Mode::Connect);
    CHECK(ui.message().empty()); // the status line shows connect's hint, not "set_rows"
    // A refusal too, and its error colour.
    ui.setMode(Mode::Rows);
    CHECK_FALSE(ui.execute(SetRowsCommand{scene.net, 0}));
    REQUIRE(ui.messageIsError());
    ui.handle(KeyPress{keys::Escape, {}});
    CHECK(ui.message().empty());
    CHECK_FALSE(ui.messageIsError());
}

TEST_CASE("keys: ctrl+z undoes, ctrl+shift+z and ctrl+y redo, letters choose modes", "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.handle(KeyPress{'R', {}});
    CHECK(ui.mode() == Mode::Rows);
    dragHandle(ui, ui.handles().front(), 16);
    CHECK(scene.doc.sculpture().piece(scene.net).rows == 8);
    const std::uint64_t version = ui.version();
    ui.handle(KeyPress{'Z', {false, true, false}});
    CHECK(scene.doc.sculpture().piece(scene.net).rows == 6);
    CHECK(ui.version() > version);
    CHECK(ui.message() == "undo set_rows"); // what was undone
    ui.handle(KeyPress{'Z', {true, true, false}});
    CHECK(scene.doc.sculpture().piece(scene.net).rows == 8);
    CHECK(ui.message() == "redo set_rows");
    ui.handle(KeyPress{'Z', {false, true, false}});
    ui.handle(KeyPress{'Y', {false, true, false}});
    CHECK(scene.doc.sculpture().piece(scene.net).rows == 8);
    ui.handle(KeyPress{'4', {}});
    CHECK(ui.mode() == Mode::Rows);
    ui.handle(KeyPress{'J', {}});
    CHECK(ui.mode() == Mode::Connect);
    ui.handle(KeyPress{keys::Escape, {}});
    CHECK(ui.mode() == Mode::View);
    CHECK(ui.handles().empty());
}

TEST_CASE("hover, selection and a refused command", "[interaction]") {
    Scene scene;
    Interaction ui(scene.doc, scene.camera);
    ui.setMode(Mode::Rows);
    const ScreenPoint sp = onScreen(scene.camera, ui.handles().front().position);
    moveTo(ui, sp.x + 5, sp.y - 5);
    CHECK(ui.hovered() == 0);
    CHECK(ui.hoveredPiece() == scene.net);
    moveTo(ui, sp.x + 40, sp.y);
    CHECK(ui.hovered() == -1);

    ui.setMode(Mode::View); // a click on the net selects its piece
    const ScreenPoint knot = onScreen(scene.camera, scene.doc.compiled().system.position[scene.doc.compiled().knotOf(scene.net, 3, 5)]);
    moveTo(ui, knot.x, knot.y);
    ui.handle(MousePress{MouseButton::Left, {}});
    ui.handle(MouseRelease{MouseButton::Left, {}});
    CHECK(ui.selectedPiece() == scene.net);

    const std::uint64_t hash = scene.doc.hash();
    CHECK_FALSE(ui.execute(SetRowsCommand{scene.net, 0}));
    CHECK(ui.messageIsError());
    CHECK_THAT(ui.message(), Catch::Matchers::Contains("rows"));
    CHECK(scene.doc.hash() == hash);
}

TEST_CASE("connect: a sheet running against an open rail is offered only places where its row fits",
          "[interaction]") {
    // A sheet of 5 knots 0.25 m apart hangs from a 1 m rail above the beam that runs the other
    // way (-y; the beam runs +y): its last row is tied to the beam reversed, from the drop
    // point back towards the beam's start, so it fits from t = 0.5 (1 m of the 2 m beam) to 1.
    Scene scene;
    const RailId upper = scene.doc.execute(AddRailCommand{"upper",
                             lineRail({2.5, 0.5, 5}, {2.5, -0.5, 5})}).rails.front();
    const PieceId sheet = attachPiece(scene.doc, upper, 5, 4, 0.3);
    Interaction ui(scene.doc, scene.camera);
    const std::vector<Handle> targets =
        connectTargets(scene.doc.sculpture(), scene.doc.compiled(), sheet);
    std::vector<double> onBeam;
    for (const Handle& h : targets) {
        if (h.rail != scene.beam) continue;
        CHECK(h.reverse);
        onBeam.push_back(h.t);
        INFO("t = " << h.t);
        // Every sphere offered is a drop the model takes.
        const bool connected = ui.execute(ConnectToRailCommand{sheet, h.rail, h.t, h.reverse});
        INFO(ui.message());
        CHECK(connected);
        if (connected) ui.undo();
    }
    REQUIRE(onBeam.size() == 12);
    CHECK(onBeam.front() == Approx(0.5));
    CHECK(onBeam.back() == Approx(1.0));
}
