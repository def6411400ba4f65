// Every command through the Document: apply, undo, redo restore the model (hash) and the compiled
// system bit for bit; merging; the clean index; every invalid input leaves model, history and
// journal untouched.

#include "CommandTestSupport.h"
#include "ShapeDistance.h"

#include "physics/Forces.h"
#include "physics/fast/NewtonRelaxer.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <set>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;

namespace {

struct Case {
    std::string name;
    std::function<void(Document&)> setup; ///< extra commands on the fixture before the one tested
    Command command;
};

/// Piece 1: a tube of 24 columns and 10 rows (bars 0.2 m) on a ring of radius 1 m at z = 3 m, in
/// real rope; piece 2 below it (gear 2, 8 rows, bars 0.16 m) tied to a ring of radius 1.3 m at
/// z = 1.2 m, like the installation's core and bell.
Document skirtTiedBelow() {
    Document doc;
    doc.execute(AddRailCommand{"top", polygonRail(24, 1.0, 3.0)});
    doc.execute(AddRailCommand{"tie", polygonRail(24, 1.3, 1.2)});
    doc.execute(attach(1, 24, 10, 0.2));
    doc.execute(hang(1, Gear{2, 1}, 8, 0.16));
    doc.execute(ConnectToRailCommand{PieceId(2), RailId(2), 0.0, false});
    return doc;
}

SetBarLengthCommand barLength(std::uint32_t piece, std::optional<int> column, std::optional<int> row, double l) {
    return SetBarLengthCommand{PieceId(piece), column, row, l};
}

std::vector<Case> everyCommand() {
    const auto none = [](Document&) {};
    const auto child = [](Document& d) { d.execute(hang(1, Gear{2, 1}, 4, 0.3)); };
    const auto connected = [](Document& d) { d.execute(ConnectToRailCommand{PieceId(1), RailId(3), 0.0, false}); };
    const auto split = [](Document& d) { d.execute(SplitCommand{PieceId(1), 5}); };
    Material material;
    material.stiffness = 1.5e5;
    material.compressionRatio = 0.02;
    material.knotMass = 0.003;
    material.linearDensity = 0.004;
    Material withBreakingLoad;
    withBreakingLoad.breakingLoad = 3000;
    ImportRailsCommand import{"rails.csv", {{"a", lineRail({0, 0, 5}, {1, 0, 5})}, {"b", polygonRail(8, 0.5, 5)}}};
    return {
        {"add_rail", none, AddRailCommand{"extra", polygonRail(7, 0.7, 4)}},
        {"add_rail (B-spline)", none, [] {
             CurveSpec spec = polygonRail(8, 1.2, 4);
             spec.spline = true;
             spec.degree = 3;
             return Command{AddRailCommand{"smooth", spec}};
         }()},
        {"import_rails", none, import},
        {"remove_rail", none, RemoveRailCommand{RailId(2)}},
        {"rename_rail", none, RenameRailCommand{RailId(1), "crown"}},
        {"attach_to_rail", none, attach(3, 12, 4, 0.35)},
        {"attach_to_rail (open rail)", none, attach(2, 9, 3, 0.4)},
        {"attach_to_piece gear 2", none, hang(1, Gear{2, 1}, 4, 0.3)},
        {"attach_to_piece gear 1/3", none, hang(1, Gear{1, 3}, 4, 0.8)},
        {"split", none, SplitCommand{PieceId(1), 4}},
        {"split with a child", child, SplitCommand{PieceId(1), 6}},
        {"set_rows", none, SetRowsCommand{PieceId(1), 9}},
        {"set_rows of a parent", child, SetRowsCommand{PieceId(1), 3}},
        {"set_columns", none, SetColumnsCommand{PieceId(1), 16}},
        {"set_columns below a piece", child, SetColumnsCommand{PieceId(2), 36}},
        {"set_gear", child, SetGearCommand{PieceId(2), Gear{3, 1}}},
        {"set_bar_length (whole piece)", none, barLength(1, std::nullopt, std::nullopt, 0.45)},
        {"set_bar_length (column, seamed)", split, barLength(1, 5, std::nullopt, 0.5)},
        {"set_bar_length (row)", none, barLength(1, std::nullopt, 5, 0.5)},
        {"connect_to_rail", none, ConnectToRailCommand{PieceId(1), RailId(3), 0.25, true}},
        {"disconnect", connected, DisconnectCommand{PieceId(1)}},
        {"set_material", none, SetMaterialCommand{PieceId(1), material}},
        {"set_material (breaking load alone)", none,
         SetMaterialCommand{PieceId(1), withBreakingLoad}},
        {"set_colour", none, SetColourCommand{PieceId(1), Colour{0.1, 0.2, 0.3}}},
        {"rename_piece", none, RenamePieceCommand{PieceId(1), "skirt"}},
        {"remove_piece", child, RemovePieceCommand{PieceId(1)}},
        {"set_gravity", none, SetGravityCommand{Vec3{0.5, 0, -9.7}}},
    };
}

} // namespace

TEST_CASE("every command applies, undoes and redoes bit for bit") {
    for (const Case& c : everyCommand()) {
        SECTION(c.name) {
            Document doc = fixtureDocument();
            c.setup(doc);
            const std::uint64_t before = doc.hash();
            const CompiledSculpture compiledBefore = doc.compiled();
            const std::string name = commandName(c.command);

            const CommandResult result = doc.execute(c.command);
            const std::uint64_t after = doc.hash();
            const CompiledSculpture compiledAfter = doc.compiled();
            CHECK(after != before);
            CHECK(doc.canUndo());
            CHECK_FALSE(doc.canRedo());
            if (name == "add_rail") CHECK(result.rails.size() == 1);
            if (name == "import_rails") CHECK(result.rails.size() == 2);
            if (name == "attach_to_rail" || name == "attach_to_piece") CHECK(result.pieces.size() == 1);
            if (name == "split") {
                REQUIRE(result.pieces.size() == 2);
                CHECK(result.pieces[0] == std::get<SplitCommand>(c.command).piece);
            }

            doc.undo();
            CHECK(doc.hash() == before);
            requireSameSystem(doc.compiled(), compiledBefore);
            CHECK(doc.canRedo());

            doc.redo();
            CHECK(doc.hash() == after);
            requireSameSystem(doc.compiled(), compiledAfter);

            // and once more, to be sure nothing accumulates
            doc.undo();
            doc.undo();
            doc.redo();
            doc.redo();
            CHECK(doc.hash() == after);
        }
    }
}

TEST_CASE("undo restores exactly the shape the document had, relaxed or not") {
    Document doc = fixtureDocument();
    // the tube's last row on a ring 1.4 m below the top one: a net that relaxes in well under a second
    doc.execute(AddRailCommand{"low", polygonRail(12, 1.0, 1.6)});
    const CompiledSculpture hanging = doc.compiled();
    doc.execute(ConnectToRailCommand{PieceId(1), RailId(4), 0.0, false});
    DocumentRelaxOptions options;
    options.backend = "rk4";
    options.solver.maxSeconds = 30;
    const RelaxResult relaxed = doc.relax(options);
    REQUIRE(relaxed.converged);
    CHECK(doc.isRelaxed());
    CHECK(doc.lastRelax().steps == relaxed.steps);
    const CompiledSculpture relaxedSystem = doc.compiled();
    const std::uint64_t hashBefore = doc.hash();

    doc.execute(SetRowsCommand{PieceId(1), 8});
    CHECK_FALSE(doc.isRelaxed());
    // the warm start: the knots that still exist keep their relaxed positions
    const auto& sys = doc.compiled().system;
    const std::uint32_t k = doc.compiled().knotOf(PieceId(1), 4, 3);
    CHECK(sameBits(sys.position[k], relaxedSystem.system.position[relaxedSystem.knotOf(PieceId(1), 4, 3)]));

    doc.undo();
    CHECK(doc.hash() == hashBefore);
    requireSameSystem(doc.compiled(), relaxedSystem);
    CHECK(doc.isRelaxed());
    doc.redo();
    CHECK(doc.compiled().system.knotCount() == 12 * 8);
    CHECK_FALSE(doc.isRelaxed());
    // back past the relaxation: that state had its initial geometry; forward again: relaxed
    doc.undo();
    doc.undo();
    requireSameSystem(doc.compiled(), hanging);
    CHECK_FALSE(doc.isRelaxed());
    doc.redo();
    requireSameSystem(doc.compiled(), relaxedSystem);
    CHECK(doc.isRelaxed());
}

TEST_CASE("positions relaxed elsewhere are adopted as the warm start of the next edit") {
    // The studio relaxes in a background thread and hands the shape it shows to the document.
    Document doc = fixtureDocument();
    std::vector<Vec3> shown = doc.compiled().system.position;
    const std::uint32_t k = doc.compiled().knotOf(PieceId(1), 4, 3);
    shown[k] += Vec3{0.01, -0.02, -0.03};
    const std::uint64_t hashBefore = doc.hash();

    // a wrong count is refused, naming both counts, and changes nothing
    std::vector<Vec3> tooFew(shown.begin(), shown.end() - 1);
    CHECK_THROWS_WITH(doc.adoptPositions(tooFew, false),
                      Contains(std::to_string(tooFew.size())) &&
                          Contains(std::to_string(shown.size()) + " knots"));
    CHECK_FALSE(sameBits(doc.compiled().system.position[k], shown[k]));

    doc.adoptPositions(shown, false);
    CHECK(doc.hash() == hashBefore); // the model is unchanged
    CHECK_FALSE(doc.isRelaxed());
    doc.execute(SetRowsCommand{PieceId(1), 8});
    const CompiledSculpture& next = doc.compiled();
    CHECK(sameBits(next.system.position[next.knotOf(PieceId(1), 4, 3)], shown[k]));

    doc.adoptPositions(doc.compiled().system.position, true);
    CHECK(doc.isRelaxed());
}

TEST_CASE("a relaxation that stops early says where the net has not settled") {
    Document doc = fixtureDocument();
    DocumentRelaxOptions options;
    options.backend = "rk4";
    options.solver.maxSteps = 3; // far from the equilibrium: the Eq. 2 start barely moved
    const RelaxResult stopped = doc.relax(options);
    REQUIRE_FALSE(stopped.converged);
    REQUIRE(stopped.unsettledAt.has_value());
    // the knot named is a free one whose residual is the run's residual (the largest)
    const CompiledSculpture& compiled = doc.compiled();
    const std::size_t knot = compiled.knotOf(stopped.unsettledAt->piece, stopped.unsettledAt->row,
                                             stopped.unsettledAt->column);
    CHECK_FALSE(compiled.system.fixed[knot]);
    const std::vector<double> residuals = knotResiduals(compiled.system);
    CHECK(residuals[knot] == stopped.residual);
    CHECK(residuals[knot] == *std::max_element(residuals.begin(), residuals.end()));
    CHECK(doc.lastRelax().unsettledAt == stopped.unsettledAt);

    options.solver.maxSteps = -1;
    options.solver.maxSeconds = 30;
    options.backend = "fast";
    const RelaxResult converged = doc.relax(options);
    REQUIRE(converged.converged);
    CHECK_FALSE(converged.unsettledAt.has_value());
}

TEST_CASE("a tolerance too loose for the shape's loads is refused, leaving the shape as it was") {
    Document doc = fixtureDocument();
    DocumentRelaxOptions options;
    options.solver.maxSteps = 1;
    (void)doc.relax(options); // a shape on its way, not relaxed
    REQUIRE_FALSE(doc.isRelaxed());
    const std::vector<Vec3> before = doc.compiled().system.position;
    for (const double loose : {2.0, 0.0101}) {
        options.solver.tolerance = loose;
        options.solver.maxSteps = -1;
        CHECK_THROWS_WITH(doc.relax(options), Contains("relax: tolerance = " + formatNumber(loose) +
                                                       "; expected a number > 0 and at most 0.01"));
        CHECK_FALSE(doc.isRelaxed());
        CHECK(doc.compiled().system.position == before);
    }
    options.solver.tolerance = kMaxTolerance; // the loosest that is taken
    const RelaxResult loosest = doc.relax(options);
    REQUIRE(loosest.converged);
    CHECK(loosest.residual < 0.01);
}

TEST_CASE("relaxing after an edit of a relaxed shape starts from the tensions it had") {
    // A tube on a ring with a skirt (gear 2) tied to a wider ring below, in real rope, like the
    // installation's core and bell. Lengthening the tube's bars by 5 % slackens the skirt and
    // leaves the whole net far out of balance (residual over a thousand knot weights).
    Document doc = skirtTiedBelow();
    DocumentRelaxOptions options;
    options.solver.maxSeconds = 60;
    REQUIRE(doc.relax(options).converged);

    doc.execute(barLength(1, std::nullopt, std::nullopt, 0.21));
    MassSpringSystem edited = doc.compiled().system; // the relaxed shape, carried
    const double startResidual = residual(edited);
    const RelaxResult hinted = doc.relax(options);
    FastRelaxer fresh; // the same start without the hint
    const RelaxResult unhinted = fresh.relax(edited, options.solver);
    INFO("start residual " << startResidual << "; hinted " << hinted.steps << " iterations, "
                           << hinted.seconds << " s; unhinted " << unhinted.steps << ", "
                           << unhinted.seconds << " s");
    CHECK(startResidual > 100); // beyond what the fast path calls a warm start on its own
    REQUIRE(hinted.converged);
    REQUIRE(unhinted.converged);
    CHECK(residual(doc.compiled().system) < options.solver.tolerance);
    CHECK(maxDistance(doc.compiled().system.position, edited.position) < 1e-6);
    CHECK(hinted.steps * 2 < unhinted.steps); // measured: 12 against 31
}

TEST_CASE("after an undo, the next relaxation's hint comes from the shape the undo restored") {
    // Relaxed, edited (bars 0.21 m), relaxed, undone: the shape is the first relaxation's again,
    // and an edit from there (bars 0.19 m) must relax exactly as it does without the detour.
    DocumentRelaxOptions options;
    options.solver.maxSeconds = 60;
    Document direct = skirtTiedBelow();
    REQUIRE(direct.relax(options).converged);
    direct.execute(barLength(1, std::nullopt, std::nullopt, 0.19));
    const RelaxResult expected = direct.relax(options);

    Document detour = skirtTiedBelow();
    REQUIRE(detour.relax(options).converged);
    detour.execute(barLength(1, std::nullopt, std::nullopt, 0.21));
    REQUIRE(detour.relax(options).converged);
    detour.undo();
    REQUIRE(detour.isRelaxed());
    detour.execute(barLength(1, std::nullopt, std::nullopt, 0.19));
    const RelaxResult result = detour.relax(options);
    REQUIRE(result.converged);
    CHECK(result.steps == expected.steps);
    CHECK(maxDistance(detour.compiled().system.position, direct.compiled().system.position) == 0);
}

TEST_CASE("rows added to a piece tied to a rail below start between its last row and the rail") {
    // The skirt of the test above, 8 -> 11 rows: its rail row moves down the piece. The rows from
    // the old rail row down are placed between the knots they hang from, a step nearer the rail.
    Document doc = skirtTiedBelow();
    DocumentRelaxOptions options;
    options.solver.maxSeconds = 60;
    REQUIRE(doc.relax(options).converged);
    const Vec3 keptKnot = doc.compiled().system.position[doc.compiled().knotOf(PieceId(2), 6, 0)];

    doc.execute(SetRowsCommand{PieceId(2), 11});
    const CompiledSculpture& c = doc.compiled();
    const MassSpringSystem& s = c.system;
    double maxStrain = 0;
    for (std::size_t b = 0; b < s.barCount(); ++b)
        maxStrain = std::max(maxStrain, distance(s.position[s.barA[b]], s.position[s.barB[b]]) /
                                                s.restLength[b] - 1);
    CHECK(maxStrain < 0.02); // moved with the old rail row, the new rows started 20-30 % off
    CHECK(sameBits(s.position[c.knotOf(PieceId(2), 6, 0)], keptKnot)); // the kept rows stay
    const Vec3 rail = s.position[c.knotOf(PieceId(2), 10, 0)];
    double before = distance(keptKnot, rail);
    for (int row = 7; row < 10; ++row) { // each row nearer the rail than the one above it
        const double now = distance(s.position[c.knotOf(PieceId(2), row, 0)], rail);
        CHECK(now < before);
        before = now;
    }
    const RelaxResult relaxed = doc.relax(options);
    CHECK(relaxed.converged);
}

TEST_CASE("sixty rows added below a relaxed piece still relax from where the edit left them") {
    // The README's example (a 48 x 30 tube, bars 0.25 m, a 20-row skirt geared x2, real rope),
    // relaxed, then 60 more rows. The hinted iterations cannot fit so large an edit; the state
    // they reach (1.6e8 knot weights, the new rows thrown about) was kept because it was below
    // the start's residual, and from it the run did not converge in 60 s.
    Document doc;
    CurveSpec square;
    square.points = {{2, 0, 6}, {0, 2, 6}, {-2, 0, 6}, {0, -2, 6}};
    square.closed = true;
    doc.execute(AddRailCommand{"top", square});
    doc.execute(attach(1, 48, 30, 0.25));
    doc.execute(hang(1, Gear{2, 1}, 20, 0.2));
    DocumentRelaxOptions options;
    options.solver.maxSeconds = 60;
    REQUIRE(doc.relax(options).converged);
    doc.execute(SetRowsCommand{PieceId(1), 90});
    // Measured: built for AVX-512, 198 iterations (2-7 s), and with the old rule 1,079 in 30 s
    // and not converged in 60 s; built for AVX2 (other rounding, another path through the slack
    // skirt's creep), 1,076 iterations, and 1,341 with the old rule. A step limit, not a time
    // limit, so that a sanitizer build judges the same.
    options.solver.maxSteps = 2000;
    options.solver.maxSeconds = 600;
    const RelaxResult result = doc.relax(options);
    INFO(result.steps << " iterations, " << result.seconds << " s, " << result.stopReason);
    CHECK(result.converged);
}

TEST_CASE("a split keeps the relaxed shape: it renames knots, it does not move them") {
    // A ring of 24 columns with a geared child, relaxed, then split at column 8: the right
    // part's (row, c) is the ring's (row, c + 8), so every knot keeps its relaxed place and the
    // next relaxation has nothing to do (before, the ring started again from Eq. 2).
    Document doc;
    doc.execute(AddRailCommand{"ring", ringRail({0, 0, 5}, 1.2, 48)});
    doc.execute(attach(1, 24, 10, 0.2));
    doc.execute(hang(1, Gear{2, 1}, 5, 0.15));
    REQUIRE(doc.relax().converged);
    const std::vector<Vec3> relaxed = doc.compiled().system.position;
    doc.execute(SplitCommand{PieceId(1), 8});
    CHECK(residual(doc.compiled().system) < 1e-6);
    const RelaxResult again = doc.relax();
    CHECK(again.converged);
    CHECK(again.steps == 0);
    // The same knots (a split changes none) at the same places, whatever their order.
    std::vector<Vec3> now = doc.compiled().system.position, before = relaxed;
    const auto order = [](const Vec3& a, const Vec3& b) {
        return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    };
    std::sort(now.begin(), now.end(), order);
    std::sort(before.begin(), before.end(), order);
    CHECK(now == before);
}

TEST_CASE("merged commands are one undo step and equal doing both") {
    Document merged = fixtureDocument();
    Document separate = fixtureDocument();
    const std::uint64_t start = merged.hash();
    for (int rows : {7, 8, 9, 10}) {
        merged.execute(SetRowsCommand{PieceId(1), rows}, true);
        separate.execute(SetRowsCommand{PieceId(1), rows});
    }
    CHECK(merged.hash() == separate.hash());
    requireSameSystem(merged.compiled(), separate.compiled());
    merged.undo();
    CHECK(merged.hash() == start); // the whole gesture at once
    merged.redo();
    CHECK(merged.hash() == separate.hash());

    SECTION("endGesture closes the run") {
        merged.endGesture();
        merged.execute(SetRowsCommand{PieceId(1), 11}, true);
        merged.undo();
        CHECK(merged.hash() == separate.hash());
    }
    SECTION("another piece, another kind or merge = false start a new step") {
        merged.execute(hang(1, Gear{1, 1}, 3, 0.4));
        merged.execute(SetRowsCommand{PieceId(2), 4}, true); // follows a create: its own step
        merged.execute(SetRowsCommand{PieceId(1), 12}, true); // another piece
        merged.execute(SetBarLengthCommand{PieceId(1), std::nullopt, std::nullopt, 0.5}, true); // another kind
        merged.execute(SetBarLengthCommand{PieceId(1), std::nullopt, std::nullopt, 0.55}, true); // merges
        merged.execute(SetBarLengthCommand{PieceId(1), std::nullopt, std::nullopt, 0.6}, false);
        int steps = 0;
        while (merged.canUndo()) {
            merged.undo();
            ++steps;
        }
        CHECK(steps == 4 + 1 + 5); // fixture (4), the rows gesture (1), then 5 steps
    }
    SECTION("canMerge") {
        CHECK(canMerge(SetGearCommand{PieceId(2), Gear{2, 1}}, SetGearCommand{PieceId(2), Gear{3, 1}}));
        CHECK(canMerge(SetColumnsCommand{PieceId(2), 3}, SetColumnsCommand{PieceId(2), 4}));
        CHECK_FALSE(canMerge(SetColumnsCommand{PieceId(2), 3}, SetColumnsCommand{PieceId(3), 4}));
        CHECK_FALSE(canMerge(SetColumnsCommand{PieceId(2), 3}, SetRowsCommand{PieceId(2), 4}));
        CHECK_FALSE(canMerge(RenamePieceCommand{PieceId(2), "a"}, RenamePieceCommand{PieceId(2), "b"}));
    }
}

TEST_CASE("the clean index follows undo and redo") {
    Document doc = fixtureDocument();
    doc.markClean();
    CHECK(doc.isClean());
    doc.execute(SetRowsCommand{PieceId(1), 7});
    CHECK_FALSE(doc.isClean());
    doc.undo();
    CHECK(doc.isClean());
    doc.redo();
    CHECK_FALSE(doc.isClean());
    doc.undo();
    doc.undo();
    CHECK_FALSE(doc.isClean());
    doc.redo();
    CHECK(doc.isClean());

    SECTION("a new branch after the clean point keeps it reachable") {
        doc.execute(SetRowsCommand{PieceId(1), 9});
        CHECK_FALSE(doc.isClean());
        doc.undo();
        CHECK(doc.isClean());
    }
    SECTION("dropping the branch that held the clean state loses it") {
        doc.execute(SetRowsCommand{PieceId(1), 9});
        doc.markClean();
        doc.undo();
        doc.execute(SetRowsCommand{PieceId(1), 10}); // the clean state was on the dropped branch
        doc.undo();
        CHECK_FALSE(doc.isClean());
        doc.execute(SetRowsCommand{PieceId(1), 9}); // the same model again, but not the saved state
        CHECK_FALSE(doc.isClean());
    }
    SECTION("merging into the clean step makes the document dirty") {
        doc.execute(SetRowsCommand{PieceId(1), 9}, true);
        doc.markClean();
        doc.execute(SetRowsCommand{PieceId(1), 10}, true);
        CHECK_FALSE(doc.isClean());
        doc.undo();
        CHECK_FALSE(doc.isClean());
    }
    SECTION("save marks clean") {
        TempDir dir;
        doc.execute(SetRowsCommand{PieceId(1), 9});
        doc.save(dir / "a.netj");
        CHECK(doc.isClean());
    }
}

TEST_CASE("every invalid input is refused with its value, leaving model, history and journal as they were") {
    struct Bad {
        Command command;
        std::string mentions;
    };
    const double nan = std::nan("");
    const double inf = std::numeric_limits<double>::infinity();
    Material negativeStiffness;
    negativeStiffness.stiffness = -3;
    Material badRatio;
    badRatio.compressionRatio = 2.5;
    Material nanMass;
    nanMass.knotMass = nan;
    const auto breakingLoad = [](double newtons) {
        Material m;
        m.breakingLoad = newtons;
        return m;
    };
    CurveSpec onePoint;
    onePoint.points = {{0, 0, 1}};
    CurveSpec nanPoint = lineRail({0, 0, 1}, {nan, 0, 1});
    AttachToRailArgs both;
    both.rail = RailId(1);
    both.columns = 12;
    both.spacing = 0.3;
    const std::vector<Bad> cases = {
        {attach(1, 12, 0, 0.4), "got 0"},
        {attach(1, 12, -2, 0.4), "-2"},
        {attach(1, 12, 100001, 0.4), "100001"},
        {attach(1, 2, 5, 0.4), "got 2"},
        {attach(1, 12, 5, 0.25), "0.25"},  // bar <= s/2 (s ~ 0.518 m)
        {attach(1, 12, 5, -1), "-1"},
        {attach(1, 12, 5, nan), "nan"},
        {attach(1, 12, 5, 0.0), "got 0"},
        {attach(9, 12, 5, 0.4), "rail 9"},
        {attach(0, 12, 5, 0.4), "null rail"},
        {AttachToRailCommand{both}, "0.3"},
        {hang(1, Gear{5, 1}, 4, 0.3), "gear 5"},
        {hang(1, Gear{2, 3}, 4, 0.3), "gear 2/3"},
        {hang(1, Gear{1, 3}, 4, 0.5), "0.5"},      // s = 3 x 0.518: bar must exceed 0.777
        {hang(1, Gear{1, 2}, 0, 0.6), "got 0"},
        {hang(42, Gear{2, 1}, 4, 0.3), "piece 42"},
        {SplitCommand{PieceId(1), 0}, "got 0"},
        {SplitCommand{PieceId(1), 12}, "got 12"},
        {SplitCommand{PieceId(1), -4}, "-4"},
        {SplitCommand{PieceId(7), 3}, "piece 7"},
        {SetRowsCommand{PieceId(1), 0}, "got 0"},
        {SetRowsCommand{PieceId(1), -1}, "-1"},
        {SetColumnsCommand{PieceId(1), 2}, "got 2"},
        {SetColumnsCommand{PieceId(1), -5}, "-5"},
        {SetGearCommand{PieceId(1), Gear{2, 1}}, "piece 1"}, // hangs from a rail
        {SetBarLengthCommand{PieceId(1), std::nullopt, std::nullopt, 0.2}, "0.2"},
        {SetBarLengthCommand{PieceId(1), std::nullopt, std::nullopt, -0.4}, "-0.4"},
        {SetBarLengthCommand{PieceId(1), std::nullopt, std::nullopt, nan}, "nan"},
        {SetBarLengthCommand{PieceId(1), 5, std::nullopt, 0.5}, "got 5"},
        {SetBarLengthCommand{PieceId(1), std::nullopt, 3, 0.5}, "got 3"},
        {SetBarLengthCommand{PieceId(1), 0, 0, 0.5}, "column 0, row 0"},
        {ConnectToRailCommand{PieceId(1), RailId(3), nan, false}, "nan"},
        {ConnectToRailCommand{PieceId(1), RailId(2), 0, false}, "rail 2"}, // a tube on an open rail
        {ConnectToRailCommand{PieceId(1), RailId(8), 0, false}, "rail 8"},
        {DisconnectCommand{PieceId(1)}, "piece 1"},
        {SetMaterialCommand{PieceId(1), negativeStiffness}, "-3"},
        {SetMaterialCommand{PieceId(1), badRatio}, "2.5"},
        {SetMaterialCommand{PieceId(1), nanMass}, "nan"},
        {SetMaterialCommand{PieceId(1), breakingLoad(0)},
         "breaking_load must be a finite number of newtons above 0 (or none), got 0"},
        {SetMaterialCommand{PieceId(1), breakingLoad(-250)}, "got -250"},
        {SetMaterialCommand{PieceId(1), breakingLoad(nan)}, "breaking_load must be a finite"},
        {SetMaterialCommand{PieceId(1), breakingLoad(inf)}, "got inf"},
        {SetColourCommand{PieceId(1), Colour{1.5, 0, 0}}, "1.5"},
        {SetColourCommand{PieceId(1), Colour{0, nan, 0}}, "nan"},
        {RenamePieceCommand{PieceId(1), "two\nlines"}, "two"},
        {RenamePieceCommand{PieceId(3), "x"}, "piece 3"},
        {RenameRailCommand{RailId(5), "x"}, "rail 5"},
        {RemovePieceCommand{PieceId(42)}, "piece 42"},
        {RemovePieceCommand{PieceId(0)}, "null piece"},
        {RemoveRailCommand{RailId(1)}, "rail 1"}, // in use by piece 1
        {RemoveRailCommand{RailId(77)}, "rail 77"},
        {SetGravityCommand{Vec3{0, 0, 0}}, "gravity"},
        {SetGravityCommand{Vec3{0, nan, -9.81}}, "nan"},
        {SetGravityCommand{Vec3{0, 0, -1e300}}, "-1e+300"},
        {AddRailCommand{"one point", onePoint}, "rail"},
        {AddRailCommand{"nan", nanPoint}, "nan"},
        {ImportRailsCommand{"empty.dxf", {}}, "empty.dxf"},
    };
    TempDir dir;
    Document doc = fixtureDocument();
    doc.execute(attach(3, 12, 2, 0.4)); // piece 2; removed so that "piece 2 was removed" is testable
    doc.execute(RemovePieceCommand{PieceId(2)});
    doc.attachJournal(dir / "j.netj");
    doc.markClean();
    const std::string journalBefore = readBytes(dir / "j.netj");
    const std::uint64_t hashBefore = doc.hash();
    const std::string luaBefore = doc.toLua();
    const CompiledSculpture compiledBefore = doc.compiled();
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const Bad& bad = cases[i];
        INFO("case " << i << ": " << commandName(bad.command));
        std::string message;
        try {
            doc.execute(bad.command, true);
        } catch (const UserError& e) {
            message = e.what();
        }
        INFO("message: " << message);
        REQUIRE_FALSE(message.empty());
        CHECK_THAT(message, Contains(bad.mentions));
        CHECK(doc.hash() == hashBefore);
        CHECK(readBytes(dir / "j.netj") == journalBefore);
        CHECK(doc.isClean());
        CHECK_FALSE(doc.canRedo());
    }
    CHECK(doc.toLua() == luaBefore);
    requireSameSystem(doc.compiled(), compiledBefore);
    // a removed piece is named as removed
    CHECK_THROWS_WITH(doc.execute(SetRowsCommand{PieceId(2), 3}), Contains("piece 2 was removed"));
    // undo/redo past the ends
    Document empty;
    CHECK_THROWS_AS(empty.undo(), UserError);
    CHECK_THROWS_AS(empty.redo(), UserError);
    // the history still works after all those failures
    doc.undo();
    doc.redo();
    CHECK(doc.hash() == hashBefore);
}

TEST_CASE("gear junctions and seams share knots in the compiled system") {
    const double bars[] = {0.8, 0.8, 0.4, 0.3, 0.3}; // by gear: 1/3, 1/2, 1, 2, 3
    const Gear gears[] = {{1, 3}, {1, 2}, {1, 1}, {2, 1}, {3, 1}};
    for (int g = 0; g < 5; ++g) {
        const Gear gear = gears[g];
        SECTION("gear " + toString(gear)) {
            Document doc = fixtureDocument();
            const std::size_t parentKnots = doc.compiled().system.knotCount();
            doc.execute(hang(1, gear, 3, bars[g]));
            const CompiledSculpture& c = doc.compiled();
            const int childColumns = 12 * gear.num / gear.den;
            CHECK(c.pieces.at(PieceId(2)).columns == childColumns);
            // gear up: every g-th top knot is the parent's; gear down: all are, every g-th parent knot
            int shared = 0;
            std::set<std::uint32_t> parentLast;
            for (int col = 0; col < 12; ++col) parentLast.insert(c.knotOf(PieceId(1), 5, col));
            for (int col = 0; col < childColumns; ++col) {
                const std::uint32_t k = c.knotOf(PieceId(2), 0, col);
                const bool isShared = parentLast.count(k) > 0;
                shared += isShared;
                if (gear.den == 1) {
                    CHECK(isShared == (col % gear.num == 0));
                    if (isShared) CHECK(k == c.knotOf(PieceId(1), 5, col / gear.num));
                } else {
                    CHECK(k == c.knotOf(PieceId(1), 5, col * gear.den));
                }
            }
            CHECK(shared == std::min(12, childColumns));
            const std::size_t newKnots = std::size_t(childColumns) * 3 - std::size_t(shared);
            CHECK(c.system.knotCount() == parentKnots + newKnots);
        }
    }
}

TEST_CASE("a split through the document changes no knot, bar or rest length") {
    Document doc = fixtureDocument();
    doc.execute(hang(1, Gear{2, 1}, 3, 0.3));
    doc.execute(ConnectToRailCommand{PieceId(2), RailId(3), 0.0, false});
    const CompiledSculpture before = doc.compiled();
    const CommandResult parts = doc.execute(SplitCommand{PieceId(1), 5});
    REQUIRE(parts.pieces.size() == 2);
    doc.execute(SplitCommand{parts.pieces[1], 3});
    const CompiledSculpture after = doc.compiled();
    REQUIRE(after.system.knotCount() == before.system.knotCount());
    REQUIRE(after.system.barCount() == before.system.barCount());
    const auto pairs = [](const CompiledSculpture& c) {
        std::multiset<std::pair<std::array<double, 3>, std::array<double, 6>>> out;
        const auto& s = c.system;
        for (std::size_t b = 0; b < s.barCount(); ++b) {
            Vec3 a = s.position[s.barA[b]], z = s.position[s.barB[b]];
            if (std::tie(a.x, a.y, a.z) > std::tie(z.x, z.y, z.z)) std::swap(a, z);
            out.insert({{s.restLength[b], s.kTension[b], s.kCompression[b]}, {a.x, a.y, a.z, z.x, z.y, z.z}});
        }
        return out;
    };
    CHECK(pairs(after) == pairs(before));
    std::multiset<std::array<double, 4>> knotsBefore, knotsAfter;
    for (std::size_t k = 0; k < before.system.knotCount(); ++k) {
        const Vec3& p = before.system.position[k];
        knotsBefore.insert({p.x, p.y, p.z, before.system.mass[k]});
        const Vec3& q = after.system.position[k];
        knotsAfter.insert({q.x, q.y, q.z, after.system.mass[k]});
    }
    CHECK(knotsAfter == knotsBefore);
    // three parts now; the seam at column 0 of the closed piece makes a ring of seams
    CHECK(doc.sculpture().seams.size() == 3);
    doc.undo();
    doc.undo();
    requireSameSystem(doc.compiled(), before);
}

TEST_CASE("split parts that share a seam knot hold it at one place, on one rail") {
    Document doc = fixtureDocument(); // a 12-column tube on the ring "top"
    const CommandResult parts = doc.execute(SplitCommand{PieceId(1), 6});
    REQUIRE(parts.pieces.size() == 2);
    const PieceId left = parts.pieces[0], right = parts.pieces[1];
    // The left part's last row on the ring "bottom" from t = 0 puts its column 6, the seam
    // knot, at t = 0.5: the right part in line with it is tied there too.
    doc.execute(ConnectToRailCommand{left, RailId(3), 0.0, false});
    const std::uint64_t hashBefore = doc.hash();
    const std::vector<std::pair<ConnectToRailCommand, std::string>> refused = {
        {ConnectToRailCommand{right, RailId(3), 0.25, false}, "rail 3 (bottom) would hold it"},
        {ConnectToRailCommand{right, RailId(2), 0.0, false}, "rail 2 (line) would hold it"},
    };
    for (const auto& [command, mentions] : refused) {
        INFO(mentions);
        CHECK_THROWS_WITH(doc.execute(command),
                          Contains("the knot at row 5, column 0 is shared with piece 1 (a seam), "
                                   "which holds it on rail 3 (bottom)") &&
                              Contains(mentions));
        CHECK(doc.hash() == hashBefore);
    }
    doc.execute(ConnectToRailCommand{right, RailId(3), 0.5, false});
    const MassSpringSystem& sys = doc.compiled().system;
    const PieceKnots& rightKnots = doc.compiled().pieces.at(right);
    const std::uint32_t seam = rightKnots.at(5, 0);
    CHECK(seam == doc.compiled().pieces.at(left).at(5, 6));
    CHECK(sys.fixed[seam]);
    CHECK(sys.hold[seam].rail == RailId(3));
    CHECK(std::count(sys.fixed.begin(), sys.fixed.end(), 1) == 12 + 12);
}

TEST_CASE("a relaxed shape carried across an edit that moves the system's origin stays where it "
          "hung") {
    // A ring at a site 700 m east, relaxed; then a second ring 60 m further east holds a new
    // piece, so the middle of the rails that hold pieces, and the origin with it, moves by 30 m.
    const Vec3 site{700, 0, 10};
    Document doc;
    addRingWithTube(doc, site, 1);
    DocumentRelaxOptions options;
    REQUIRE(doc.relax(options).converged);
    const MassSpringSystem before = doc.compiled().system;
    CHECK(before.origin == Vec3{700, 0, 0}); // 10 m up is within 32 m: z stays

    addRingWithTube(doc, site + Vec3{60, 0, 0}, 2);
    const MassSpringSystem& after = doc.compiled().system;
    CHECK(after.origin == Vec3{730, 0, 0});
    double worst = 0;
    for (int r = 0; r < 8; ++r)
        for (int c = 0; c < 12; ++c) {
            const std::uint32_t was = doc.compiled().knotOf(PieceId(1), r, c); // the same order
            worst = std::max(worst, distance(after.worldPosition(was), before.worldPosition(was)));
        }
    CHECK(worst < 1e-14); // moved by 30 m exactly, rounded once to 3.6e-15 m
    // The first piece is still balanced: only the new one has to settle.
    const RelaxResult settled = doc.relax(options);
    INFO(settled.stopReason << ", residual " << settled.residual << " after " << settled.steps);
    REQUIRE(settled.converged);
    const std::uint32_t k = doc.compiled().knotOf(PieceId(1), 7, 0);
    CHECK(distance(doc.compiled().system.worldPosition(k), before.worldPosition(k)) < 1e-7);
}
