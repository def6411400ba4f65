// The fabrication and load report (io/Report.h) on sculptures whose numbers can be checked by
// hand: counts and rope lengths from the staggering rule, masses, joins, and the force balance
// after a relaxation.

#include "IoTestSupport.h"

#include "commands/Document.h"
#include "io/Export.h"
#include "io/Report.h"
#include "physics/Forces.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using nlohmann::json;

namespace {

std::size_t lineCount(const std::string& text) {
    return std::size_t(std::count(text.begin(), text.end(), '\n'));
}

/// A piece of 10 columns and 6 rows on a ring of 10 points, in soft rope: relaxes in a moment.
void addSoftRing(Document& doc) {
    const RailId rail = doc.execute(AddRailCommand{"ring", polygonRail(10, 0.8, 2.0)}).rails.at(0);
    const PieceId piece =
        doc.execute(AttachToRailCommand{{rail, 10, 0, 6, 0.3, 0, false}}).pieces.at(0);
    doc.execute(SetMaterialCommand{piece, softRope()});
}

/// Splits `t` at column 12 and grades its left part from 0.25 m at column 0 to 0.2 m at the
/// seam; compiles it again. Returns the left part.
PieceId gradeLeftPart(SheetNet& t) {
    const PieceId left = edit(t.s, [&](Sculpture& s) {
        const PieceId part = netsculpt::split(s, t.piece, 12).first;
        setBarLength(s, part, 0, 0.25);
        setBarLength(s, part, 12, 0.2);
        return part;
    });
    t.compiled = compileSculpture(t.s);
    return left;
}

} // namespace

TEST_CASE("report of a single open sheet: counts, rope length and mass by hand") {
    // 6 rows x 5 columns on a 1 m rail (knots 0.25 m apart), bars of 0.3 m. Staggering rule: a
    // row below row 0 has 2 bars up per knot except one knot at an open edge: 2 * 5 - 1 = 9.
    const int rows = 6, columns = 5;
    const double bar = 0.3;
    SheetNet t = sheet(rows, columns, 1.0, bar);
    const json r = buildReport(t.s, t.compiled);
    const int bars = (rows - 1) * (2 * columns - 1);
    const double rope = bar * bars;
    const Material m;
    const double mass = m.linearDensity * rope + m.knotMass * rows * columns;

    CHECK(r["knots"] == rows * columns);
    CHECK(r["bars"] == bars);
    CHECK(r["rope_length"].get<double>() == Approx(rope).epsilon(1e-14));
    CHECK(r["total_mass"].get<double>() == Approx(mass).epsilon(1e-14));
    CHECK(r["total_weight"].get<double>() == Approx(mass * 9.81).epsilon(1e-14));
    CHECK(r["relaxed"] == false);
    CHECK(r["units"]["force"] == "N");
    CHECK(r["units"]["length"] == "m");
    CHECK(r["force_balance"]["relaxed"] == false);
    CHECK_THAT(r["force_balance"]["note"].get<std::string>(), Contains("not relaxed"));

    REQUIRE(r["pieces"].size() == 1);
    const json& p = r["pieces"][0];
    CHECK(p["id"] == t.piece.value);
    CHECK(p["knots"] == rows * columns);
    CHECK(p["bars"] == bars);
    CHECK(p["rope_length"].get<double>() == Approx(rope).epsilon(1e-14));
    CHECK(p["mass"].get<double>() == Approx(mass).epsilon(1e-14));
    CHECK(p["closed"] == false);
    CHECK(p["bar_axis"] == "column");
    CHECK(p["bar_lengths"] == std::vector<double>(columns, bar));
    CHECK(p["top"]["kind"] == "rail");
    CHECK(p["top"]["rail_name"] == "bar");
    CHECK(p["bottom"].is_null());
    CHECK(p["seams"].empty());

    REQUIRE(r["rails"].size() == 1);
    const json& rail = r["rails"][0];
    CHECK(rail["length"].get<double>() == 1.0);
    CHECK(rail["attachments"] == columns);
    REQUIRE(rail["points"].size() == std::size_t(columns));
    for (int c = 0; c < columns; ++c) {
        CHECK(rail["points"][std::size_t(c)]["column"] == c);
        CHECK(rail["points"][std::size_t(c)]["row"] == 0);
        CHECK(rail["points"][std::size_t(c)]["t"].get<double>() == Approx(c / 4.0).margin(1e-15));
        // where the load acts: on the rail from (0, 0, 0) to (1, 0, 0), at t
        const json& at = rail["points"][std::size_t(c)]["position"];
        CHECK(at["x"].get<double>() == Approx(c / 4.0).margin(1e-15));
        CHECK(at["y"].get<double>() == 0);
        CHECK(at["z"].get<double>() == 0);
    }
}

TEST_CASE("after a relaxation the rail reactions carry the total weight, to the tolerance") {
    SheetNet t = sheet(7, 6, 1.2, 0.2, /*soft=*/true);
    RelaxOptions options;
    options.tolerance = 1e-7;
    const RelaxResult result = relaxRk4(t.compiled.system, options);
    REQUIRE(result.converged);
    const json r = buildReport(t.s, t.compiled, RelaxStatus{true, result, options.tolerance, {}});

    const double weight = r["total_weight"].get<double>();
    const json& fb = r["force_balance"];
    CHECK(r["relaxed"] == true);
    CHECK(r["residual"].get<double>() < options.tolerance);
    CHECK(fb["within_tolerance"] == true);
    CHECK(fb["relative_difference"].get<double>() <= options.tolerance);
    CHECK(fb["reaction_sum"]["z"].get<double>() == Approx(weight).epsilon(options.tolerance));
    CHECK(std::abs(fb["reaction_sum"]["x"].get<double>()) <= options.tolerance * weight);
    CHECK(std::abs(fb["reaction_sum"]["y"].get<double>()) <= options.tolerance * weight);

    const json& rail = r["rails"][0];
    double sumZ = 0, largest = 0;
    for (const json& p : rail["points"]) {
        sumZ += p["reaction"]["z"].get<double>();
        largest = std::max(largest, p["magnitude"].get<double>());
        CHECK(p["reaction"]["z"].get<double>() > 0); // the rail holds the net up
    }
    CHECK(rail["reaction"]["z"].get<double>() == Approx(sumZ).epsilon(1e-12));
    CHECK(rail["max_reaction"].get<double>() == largest);
    // Every held knot is listed once, with its reaction -F_j.
    const auto reactions = netsculpt::reactions(t.compiled.system);
    CHECK(rail["points"].size() == 6);
    CHECK(rail["points"][2]["reaction"]["z"].get<double>() ==
          reactions[t.compiled.knotOf(t.piece, 0, 2)].z);

    // The largest tension is a bar of row 1 (the top rows carry the most weight), in tension.
    const auto tensions = barTensions(t.compiled.system);
    CHECK(r["max_tension"].get<double>() == *std::max_element(tensions.begin(), tensions.end()));
    CHECK(r["max_tension"].get<double>() > 0);
    const json& at = r["max_tension_at"];
    CHECK(at["piece"] == t.piece.value);
    CHECK(std::min(at["a"]["row"].get<int>(), at["b"]["row"].get<int>()) == 0);
    CHECK(std::abs(at["a"]["row"].get<int>() - at["b"]["row"].get<int>()) == 1);
}

TEST_CASE("report of joined pieces: gears, seams, shared knots counted once in the mass") {
    Tube t = tubeWithChild(12, 5, 1.0, 0.4);
    auto [a, b] = edit(t.s, [&](Sculpture& s) { return split(s, t.piece, 4); });
    t.compiled = compileSculpture(t.s);
    const json r = buildReport(t.s, t.compiled);
    REQUIRE(r["pieces"].size() == 3);
    double massSum = 0, ropeSum = 0;
    std::size_t barSum = 0;
    for (const json& p : r["pieces"]) {
        massSum += p["mass"].get<double>();
        ropeSum += p["rope_length"].get<double>();
        barSum += p["bars"].get<std::size_t>();
    }
    CHECK(massSum == Approx(r["total_mass"].get<double>()).epsilon(1e-13));
    CHECK(ropeSum == Approx(r["rope_length"].get<double>()).epsilon(1e-13));
    CHECK(barSum == r["bars"].get<std::size_t>());

    const auto piece = [&](PieceId id) {
        for (const json& p : r["pieces"])
            if (p["id"] == id.value)
                return p;
        FAIL("no piece " << id.value);
        return json();
    };
    // The child: gear 2 below the (now split) ring: 24 columns, 3 rows; its 12 new row-0 knots
    // hang from 2 bars each, rows 1 and 2 of a tube have 2 bars up per knot.
    const json child = piece(t.child);
    CHECK(child["columns"] == 24);
    CHECK(child["knots"] == 72);
    CHECK(child["bars"] == 12 * 2 + 2 * 24 * 2);
    CHECK(child["rope_length"].get<double>() ==
          Approx(0.25 * (12 * 2 + 2 * 24 * 2)).epsilon(1e-14));
    CHECK(child["top"]["kind"] == "piece");
    CHECK(child["top"]["gear"] == "2");
    CHECK(child["top"]["parents"].size() == 2);
    // The split parts are joined by seams at both ends (the ring's seam at column 0 and the cut).
    const json left = piece(a), right = piece(b);
    CHECK(left["name"] == "upper");
    REQUIRE(left["seams"].size() == 2);
    REQUIRE(right["seams"].size() == 2);
    for (const json& seam : left["seams"])
        CHECK(seam["piece"] == b.value);
    for (const json& seam : right["seams"])
        CHECK(seam["piece"] == a.value);
    CHECK(left["knots"].get<int>() + right["knots"].get<int>() ==
          5 * (12 + 2)); // seam columns in both
    CHECK(r["rails"][0]["attachments"] == 12);
}

TEST_CASE("report as Markdown and CSV tables") {
    SheetNet t = sheet(4, 3, 0.8, 0.3);
    const json r = buildReport(t.s, t.compiled);
    const std::string md = reportMarkdown(r);
    CHECK_THAT(md, Contains("# netsculpt report"));
    CHECK_THAT(md, Contains("**not relaxed**"));
    CHECK_THAT(md, Contains("| knots | 12 |"));
    CHECK_THAT(md, Contains("| bars | 15 |"));
    CHECK_THAT(md, Contains("| rope length | 4.5 m |"));
    CHECK_THAT(md, Contains("## Force balance"));
    CHECK_THAT(md, Contains("against the weight (0, 0, ")); // not "-0": the weight to carry
    CHECK_THAT(md, Contains("| 1 | piece 1 | 4 x 3 | no | 12 | 12 | 15 | 4.5 |"));
    CHECK_THAT(md, Contains("| 1 | bar | 0.8 | no | 3 |"));

    const std::string pieces = reportPiecesCsv(r);
    CHECK(pieces.rfind("id,name,rows,columns,closed,knots,bars,rope_length,mass,bar_axis,bar_min,"
                       "bar_max,bar_first,bar_last,max_tension,top,last_row,knots_tied,"
                       "breaking_load,utilisation,safety_factor,max_tension_at,seams,load_case\n",
                       0) == 0);
    CHECK(lineCount(pieces) == 2);
    CHECK_THAT(pieces, Contains("\n1,piece 1,4,3,0,12,15,"));
    CHECK_THAT(pieces, Contains(",column,0.3,0.3,0.3,0.3,"));
    CHECK_THAT(pieces, Contains(",\"rail 1 (bar), from 0.0000 m along it (t = 0)\",free,12,"));
    const std::string points = reportAttachmentsCsv(r);
    CHECK(points.rfind("rail,piece,row,column,t,x,y,z,fx,fy,fz,magnitude,along,load_case\n", 0) ==
          0);
    CHECK(lineCount(points) == 1 + 3);
    CHECK_THAT(pieces, EndsWith(",,weight alone\n")); // no seam
    CHECK_THAT(points, EndsWith(",weight alone\n"));
    CHECK_THAT(points, Contains("\n1,1,0,2,1,"));
    // Every attachment point in the Markdown too, after the rails' sign convention.
    CHECK_THAT(md, Contains("the load on the rail is its opposite"));
    CHECK_THAT(md, Contains("### Rail 1 (bar)"));
    CHECK_THAT(md, Contains("\n| 1 | 0 | 0 | 0 | 0.0000 | (0.0000, 0.0000, 0.0000) | ("));
    CHECK_THAT(md, Contains("\n| 1 | 0 | 2 | 1 | 0.8000 | (0.8000, 0.0000, 0.0000) | ("));
}

TEST_CASE("the report gives bar lengths as they are knotted, first to last") {
    // A sheet split at column 12, its left part shorter towards the seam: listed from column 0,
    // not smallest first.
    SheetNet split = sheet(5, 25, 4.8, 0.3);
    const PieceId left = gradeLeftPart(split);
    json r = buildReport(split.s, split.compiled);
    REQUIRE(r["pieces"][0]["id"] == left.value);
    CHECK(r["pieces"][0]["bar_lengths_between_rows"].empty());
    CHECK_THAT(reportMarkdown(r), Contains("| 0.25 at column 0 to 0.2 at column 12 |"));
    CHECK_THAT(reportPiecesCsv(r), Contains(",column,0.2,0.25,0.25,0.2,"));
    // Which columns the seam ties together, as the Markdown says it: the left part's last
    // (column 12 of 13) is the right part's first, in all 5 rows, its 4 bars made once.
    const std::string seam = "its column 12, rows 0 to 4, is column 0 of piece 2 (the 4 bars";
    CHECK_THAT(reportPiecesCsv(r), Contains("\"piece 2 to the right: " + seam));
    CHECK_THAT(reportMarkdown(r), Contains("piece 2 to the right: " + seam));

    SheetNet t = sheet(5, 13, 2.4, 0.3);

    // By row, 0.2 at row 0 to 0.4 at row 4: every bar between two rows has the mean of theirs,
    // so the net maker knots 0.225 to 0.375, which the compiled bars must have.
    edit(t.s, [&](Sculpture& s) {
        setBarLengthByRow(s, t.piece, 0, 0.2);
        setBarLengthByRow(s, t.piece, 4, 0.4);
        return 0;
    });
    t.compiled = compileSculpture(t.s);
    r = buildReport(t.s, t.compiled);
    const json& between = r["pieces"][0]["bar_lengths_between_rows"];
    REQUIRE(between.size() == 4);
    const MassSpringSystem& sys = t.compiled.system;
    for (std::size_t b = 0; b < sys.barCount(); ++b) {
        const int upper = std::min(sys.refs[sys.refStart[sys.barA[b]]].row,
                                   sys.refs[sys.refStart[sys.barB[b]]].row);
        CHECK(sys.restLength[b] == Approx(between[upper].get<double>()).epsilon(1e-14));
    }
    CHECK(between[0].get<double>() == Approx(0.225).epsilon(1e-14));
    CHECK(between[3].get<double>() == Approx(0.375).epsilon(1e-14));
    CHECK_THAT(reportMarkdown(r),
               Contains("| 0.225 between rows 0 and 1 to 0.375 between rows 3 and 4 |"));
    // bar_min and bar_max are lengths bars have, not the rows' 0.2 and 0.4.
    CHECK_THAT(reportPiecesCsv(r), Contains(",row,0.225,0.375,0.225,0.375,"));
}

TEST_CASE("the report says where split parts start on their rail and who makes a seam's bars") {
    // A ring of 12 columns split at 4: the part from column 4 starts a third of the way round.
    Tube t = tubeWithChild(12, 5, 1.0, 0.4);
    auto [a, b] = edit(t.s, [&](Sculpture& s) { return split(s, t.piece, 4); });
    t.compiled = compileSculpture(t.s);
    const json r = buildReport(t.s, t.compiled);
    const double ring = r["rails"][0]["length"].get<double>();
    const std::string md = reportMarkdown(r);
    CHECK_THAT(md, Contains("rail 1 (ring), from 0.0000 m along it (t = 0)"));
    char second[80];
    std::snprintf(second, sizeof second, "rail 1 (ring), from %.4f m along it (t = 0.333333)",
                  ring / 3);
    CHECK_THAT(md, Contains(second));
    // Each seam column's 4 bars (5 rows) are made once: counted in one of the two parts, and
    // the parts' bars with the child's add up to the sculpture's.
    const MassSpringSystem& sys = t.compiled.system;
    std::size_t counted = 0;
    for (const json& p : r["pieces"])
        for (const json& seam : p["seams"]) {
            CHECK(seam["shared_bars"] == 4);
            const PieceId owner{seam["shared_bars_counted_in"].get<std::uint32_t>()};
            CHECK((owner == a || owner == b));
            counted += owner.value == p["id"].get<std::uint32_t>() ? 1 : 0;
        }
    CHECK(counted == 2); // each of the two seams once from the side that owns its bars
    CHECK_THAT(md, Contains("(the 4 bars along the seam counted in piece"));
    // The largest tension of the pieces is the sculpture's.
    double largest = 0;
    for (const json& p : r["pieces"])
        largest = std::max(largest, p["max_tension"].get<double>());
    CHECK(largest == r["max_tension"].get<double>());
    CHECK(sys.barCount() == r["bars"].get<std::size_t>());
}

TEST_CASE("the report flags bars stretched beyond what rope does, with the largest strain") {
    // 6 rows x 5 columns, bars of 0.3 m, knots placed by hand on the regular stagger: row r at
    // x = 0.25 c (+ 0.125 on odd rows), z = -s v r with v = sqrt(0.3^2 - 0.125^2). Every bar joins
    // neighbouring rows half a spacing apart, so every bar is sqrt(0.125^2 + s^2 v^2) long.
    const double bar = 0.3, across = 0.125, down = std::sqrt(bar * bar - across * across);
    const SheetNet t = sheet(6, 5, 1.0, bar);
    const std::size_t bars = t.compiled.system.barCount();
    RelaxStatus relaxed;
    relaxed.relaxed = true; // the check speaks only of a shape that hangs

    for (const double s : {1.0, 1.01, 1.1}) {
        CAPTURE(s);
        CompiledSculpture c = t.compiled;
        for (int r = 0; r < 6; ++r)
            for (int col = 0; col < 5; ++col)
                c.system.position[c.knotOf(t.piece, r, col)] =
                    Vec3{0.25 * col + (r % 2 ? across : 0.0), 0, -s * down * r};
        const double strain = std::sqrt(across * across + s * s * down * down) / bar - 1;
        const json r = buildReport(t.s, c, relaxed);
        CHECK(r["max_strain"].get<double>() == Approx(strain).margin(1e-14));
        const bool over = strain > kOverstretchStrain; // 0, 0.83 % and 8.3 %
        CHECK(r["overstretched_bars"].get<std::size_t>() == (over ? bars : 0));
        const std::string md = reportMarkdown(r);
        const std::string warning =
            "**Check the design:** " + std::to_string(bars) + " bars are stretched";
        CHECK((md.find(warning) != std::string::npos) == over);
        if (s > 1) {
            CHECK(r["max_strain_at"]["piece"] == t.piece.value);
            char percent[40];
            std::snprintf(percent, sizeof percent, "%.6g", 100 * strain);
            CHECK_THAT(md, Contains("| largest strain | " + std::string(percent) + " %"));
        }
        // Not relaxed (an Eq. 2 start or a shape still moving): counted, not called a design flaw.
        const json moving = buildReport(t.s, c);
        CHECK(moving["overstretched_bars"] == r["overstretched_bars"]);
        CHECK(reportMarkdown(moving).find("**Check the design:**") == std::string::npos);
        CHECK(countOverstretchedBars(c.system) == r["overstretched_bars"].get<std::size_t>());
        // A run stopped short ("precision limit", a looser tolerance) but near its equilibrium:
        // its strains are final, so the design is checked.
        json nearly = moving;
        nearly["residual"] = 0.5 * kSettledResidual;
        CHECK((reportMarkdown(nearly).find(warning) != std::string::npos) == over);
    }
}

TEST_CASE("a Document's report and export say whether its shape is relaxed") {
    Document doc;
    addSoftRing(doc);
    CHECK(buildReport(doc)["relaxed"] == false);

    DocumentRelaxOptions options;
    options.backend = "rk4";
    options.solver.tolerance = 1e-6;
    REQUIRE(doc.relax(options).converged);
    const nlohmann::json r = buildReport(doc);
    CHECK(r["relaxed"] == true);
    CHECK(r["relax"]["converged"] == true);
    CHECK(r["force_balance"]["within_tolerance"] == true);
    CHECK(r["rails"][0]["attachments"] == 10);
    CHECK(r["pieces"][0]["bars"] == 2 * 10 * 5);

    const auto dir = outputDir("document");
    exportFile(doc, dir / "doc.json");
    const auto json = nlohmann::json::parse(readText(dir / "doc.json"));
    CHECK(json["relaxed"] == true);
    CHECK(json["report"]["force_balance"]["within_tolerance"] == true);
    const auto& p = json["knots"][20]["position"];
    CHECK(Vec3{p[0].get<double>(), p[1].get<double>(), p[2].get<double>()} ==
          doc.compiled().system.position[20]);
}

TEST_CASE("the report of an opened snapshot says it was relaxed, without inventing a run") {
    Document doc;
    addSoftRing(doc);
    DocumentRelaxOptions options;
    options.backend = "fast";
    REQUIRE(doc.relax(options).converged);
    CHECK(buildReport(doc)["relax"]["backend"] == "fast");
    const auto file = outputDir("snapshot") / "relaxed.nets";
    doc.saveSnapshot(file);

    const Document opened = Document::load(file);
    const nlohmann::json r = buildReport(opened);
    CHECK(r["relaxed"] == true);
    CHECK(r["relax"].is_null()); // no run since it was opened: no backend, steps or time to show
    CHECK(r["residual"].get<double>() < 1e-6);
    const std::string text = reportMarkdown(r);
    CHECK_THAT(text, Contains("Shape: **relaxed** (residual "));
    CHECK_THAT(text, Contains("| load case | weight alone |"));
    CHECK_THAT(text, Contains("relaxed before the file was saved"));
    CHECK_THAT(text, !Contains("steps"));
}

TEST_CASE("the report of a snapshot relaxed to a loose tolerance checks its balance against it") {
    Document doc;
    addSoftRing(doc);
    DocumentRelaxOptions options;
    options.backend = "rk4"; // stops as soon as the residual is below the tolerance
    options.solver.tolerance = 1e-2;
    REQUIRE(doc.relax(options).converged);
    const auto file = outputDir("snapshot") / "loose.nets";
    doc.saveSnapshot(file);

    const Document opened = Document::load(file);
    CHECK(opened.shapeTolerance() == 1e-2);
    const json r = buildReport(opened);
    REQUIRE(r["relaxed"] == true);
    REQUIRE(r["residual"].get<double>() > 1e-4); // far above the default tolerance, 1e-6
    CHECK(r["residual"].get<double>() < 1e-2);
    const json& fb = r["force_balance"];
    CHECK(fb["tolerance"].get<double>() == 1e-2);
    // The rails' sum is off the weight by at most the free knots' unbalanced forces.
    CHECK(fb["relative_difference"].get<double>() <= r["residual"].get<double>());
    CHECK(fb["within_tolerance"] == true);
    CHECK_THAT(reportMarkdown(r), Contains("for the tolerance 0.01; relaxed before the file") &&
                                      Contains("within the tolerance 0.01."));
}

TEST_CASE("a shape relaxed under wind: the report's residual and force balance carry its load, "
          "and its snapshot keeps it",
          "[wind]") {
    Document doc;
    addSoftRing(doc);
    DocumentRelaxOptions options;
    options.solver.wind = Wind{{1, 0, 0}, 0.5}; // 0.5 N per metre of rope, blowing along +x
    REQUIRE(doc.relax(options).converged);
    const json r = buildReport(doc);
    const json& fb = r["force_balance"];
    CHECK(r["residual"].get<double>() < 1e-6);
    CHECK(fb["within_tolerance"] == true);
    // The rails hold the net against the wind: their reactions' x is the wind's load, opposed.
    const double windX = r["wind"]["force"]["x"].get<double>();
    CHECK(windX > 0.1 * r["total_weight"].get<double>());
    CHECK(fb["reaction_sum"]["x"].get<double>() == Approx(-windX).epsilon(1e-6));
    CHECK_THAT(reportMarkdown(r), Contains("against the weight and the wind (0.5 N/m towards"));
    // The summary says which load case its tensions are of.
    CHECK_THAT(reportMarkdown(r),
               Contains("| load case | weight and a wind of 0.5 N/m towards (1, 0, 0) |"));
    // So does every line of the CSVs, an engineer's file that travels without the summary.
    const std::string windy = ",\"weight and a wind of 0.5 N/m towards (1, 0, 0)\"\n";
    CHECK_THAT(reportPiecesCsv(r), EndsWith(windy));
    CHECK_THAT(reportAttachmentsCsv(r), EndsWith(windy));
    // Judged under gravity alone, the same shape is out of balance by the wind's load.
    const json still = buildReport(doc.sculpture(), doc.compiled(),
                                   RelaxStatus{true, doc.lastRelax(), 1e-6, {}});
    CHECK(still["force_balance"]["within_tolerance"] == false);
    CHECK(still["residual"].get<double>() > 1);

    const auto file = outputDir("wind") / "windy.nets";
    doc.saveSnapshot(file);
    const Document opened = Document::load(file);
    REQUIRE(opened.shapeWind().has_value());
    CHECK(opened.shapeWind()->pressure == 0.5);
    CHECK(buildReport(opened)["force_balance"]["within_tolerance"] == true);
}

TEST_CASE("the report measures rail places as a tape along the rail does, to a tenth of a mm") {
    // A rail sampled by parameter: segments of 1 m and 3 m each take half of t, so the five top
    // knots (t = 0, 0.25, ..., 1) are 0, 0.5, 1, 2.5 and 4 m along it, not t x 4 m.
    Sculpture s;
    CurveSpec spec;
    spec.points = {{0, 0, 5}, {1, 0, 5}, {4, 0, 5}};
    spec.sampling = Sampling::Parameter;
    const RailId rail = edit(s, [&](Sculpture& x) { return addRail(x, "beam", spec); });
    edit(s, [&](Sculpture& x) { return attachToRail(x, {rail, 5, 0, 2, 1.0, 0, false}); });
    const CompiledSculpture c = compileSculpture(s);
    const json r = buildReport(s, c);
    const json& points = r["rails"][0]["points"];
    REQUIRE(points.size() == 5);
    const double along[] = {0, 0.5, 1, 2.5, 4};
    for (std::size_t i = 0; i < 5; ++i)
        CHECK(points[i]["along"].get<double>() == Approx(along[i]).margin(1e-12));
    CHECK(r["rails"][0]["sampling"] == "parameter");
    CHECK_THAT(reportMarkdown(r),
               Contains("| 1 | 0 | 3 | 0.75 | 2.5000 | (2.5000, 0.0000, 5.0000)"));

    // Site coordinates: 500 km east, 5,400 km north. Six significant digits would print the
    // ring's knots 0.52 m apart at one place; a tenth of a millimetre tells every one apart.
    Tube site = tubeWithChild(12, 5, 1.0, 0.4, {500000, 5400000, 0});
    const json siteReport = buildReport(site.s, site.compiled);
    const std::string md = reportMarkdown(siteReport);
    std::set<std::string> places;
    for (const json& p : siteReport["rails"][0]["points"]) {
        char place[96];
        std::snprintf(place, sizeof place, "(%.4f, %.4f, %.4f)", p["position"]["x"].get<double>(),
                      p["position"]["y"].get<double>(), p["position"]["z"].get<double>());
        CHECK_THAT(md, Contains(place));
        places.insert(place);
    }
    CHECK(places.size() == 12); // every knot of the ring at a place of its own
}

TEST_CASE("the report says how a child is knotted into its parent and every graded bar length") {
    // The ring of 12 columns and 5 rows with its gear-2 child of 24 columns and 3 rows: the
    // child's even knots of row 0 are the ring's last row (row 4), so the child ties 72 - 12.
    Tube t = tubeWithChild(12, 5, 1.0, 0.4);
    const json r = buildReport(t.s, t.compiled);
    std::size_t tied = 0;
    for (const json& p : r["pieces"])
        tied += p["knots_tied"].get<std::size_t>();
    CHECK(tied == r["knots"].get<std::size_t>());
    CHECK(r["pieces"][1]["knots_tied"] == 60);
    const std::string md = reportMarkdown(r);
    CHECK_THAT(md, Contains("## Joins"));
    CHECK_THAT(md, Contains("knot (0, c) of piece 2 with c a multiple of 2 is knot (4, c / 2) of "
                            "piece 1; the knot between two of them is new"));
    CHECK_THAT(md, Contains("It adds rows 1 to 2 below (60 knots tied)."));
    // Below split parts the row is theirs joined: 5 + 9 columns, the cut's seam knot once and
    // the ring's once, 12 knots, counted round the ring.
    Tube split = tubeWithChild(12, 5, 1.0, 0.4);
    edit(split.s, [&](Sculpture& s) { return netsculpt::split(s, split.piece, 4); });
    split.compiled = compileSculpture(split.s);
    CHECK_THAT(reportMarkdown(buildReport(split.s, split.compiled)),
               Contains("is knot c / 2 of that joined row (12 knots: 0 to 4 are knots (4, 0) to "
                        "(4, 4) of piece 1, 5 to 11 are knots (4, 1) to (4, 7) of piece 3; a seam "
                        "knot counted once, in the part before it, round the ring"));
    CHECK_THAT(md, !Contains("## Bar lengths")); // one length everywhere: nothing to list

    // A sheet split at column 12, its left part graded 0.25 at column 0 to 0.2 at column 12: a
    // bar to the next column takes the mean of the two columns' lengths, 0.25 - 0.05 / 24 from
    // column 0.
    SheetNet graded = sheet(5, 25, 4.8, 0.3);
    const PieceId left = gradeLeftPart(graded);
    const std::string gradedMd = reportMarkdown(buildReport(graded.s, graded.compiled));
    CHECK_THAT(gradedMd, Contains("### Piece " + std::to_string(left.value) + " ("));
    CHECK_THAT(gradedMd, Contains("), graded by column"));
    CHECK_THAT(gradedMd, Contains("\n| 0 | 0.25 | 0.247917 |\n"));
    CHECK_THAT(gradedMd, Contains("\n| 12 | 0.2 | - |\n"));
    CHECK_THAT(gradedMd, !Contains("## Joins"));
}

TEST_CASE("the report sums the loads of pieces tied at the same rail points") {
    // Two pieces of 10 columns on one ring of 10 points, tied at the same places: each point
    // carries a knot of each, and the rail there the sum of their reactions.
    Document doc;
    const RailId rail = doc.execute(AddRailCommand{"ring", polygonRail(10, 0.8, 2.0)}).rails.at(0);
    std::vector<PieceId> pieces;
    for (int rows : {6, 3}) {
        pieces.push_back(
            doc.execute(AttachToRailCommand{{rail, 10, 0, rows, 0.3, 0, false}}).pieces.at(0));
        doc.execute(SetMaterialCommand{pieces.back(), softRope()});
    }
    DocumentRelaxOptions options;
    options.backend = "rk4";
    REQUIRE(doc.relax(options).converged);
    const json r = buildReport(doc);
    const json& ring = r["rails"][0];
    CHECK(ring["attachments"] == 20);
    CHECK(ring["shared_points"] == 10);
    CHECK(ring["max_point_load_knots"] == 2);

    // By hand: each column's two top knots' reactions, summed.
    const auto& c = doc.compiled();
    const auto reactions = netsculpt::reactions(c.system);
    double pointLoad = 0, knotLoad = 0;
    for (int column = 0; column < 10; ++column) {
        const Vec3 a = reactions[c.knotOf(pieces[0], 0, column)];
        const Vec3 b = reactions[c.knotOf(pieces[1], 0, column)];
        CHECK((c.system.position[c.knotOf(pieces[0], 0, column)] -
               c.system.position[c.knotOf(pieces[1], 0, column)])
                  .norm() < 1e-12);
        pointLoad = std::max(pointLoad, (a + b).norm());
        knotLoad = std::max({knotLoad, a.norm(), b.norm()});
    }
    CHECK(ring["max_point_load"].get<double>() == Approx(pointLoad).epsilon(1e-12));
    CHECK(ring["max_reaction"].get<double>() == Approx(knotLoad).epsilon(1e-12));
    CHECK(pointLoad > 1.2 * knotLoad); // the longer piece's knot alone is not the point's load
    CHECK_THAT(reportMarkdown(r), Contains(" (2 knots; 10 points shared) |"));

    // One piece alone: every point holds one knot, its load the knot's reaction.
    doc.execute(RemovePieceCommand{pieces[1]});
    REQUIRE(doc.relax(options).converged);
    const json alone = buildReport(doc)["rails"][0];
    CHECK(alone["shared_points"] == 0);
    CHECK(alone["max_point_load_knots"] == 1);
    CHECK(alone["max_point_load"].get<double>() == alone["max_reaction"].get<double>());
}
