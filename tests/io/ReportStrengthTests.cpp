// The report's strength check (io/ReportStrength.cpp): each piece's largest tension against its
// breaking load, checked against a hanger solved by hand and against tensions recomputed from the
// compiled bars; the least safety factor; pieces without a breaking load named, never given one.

#include "IoTestSupport.h"

#include "commands/Document.h"
#include "io/IoText.h"
#include "io/Report.h"
#include "io/ReportSections.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <map>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
using nlohmann::json;

namespace {

const json& pieceOf(const json& report, PieceId id) {
    for (const json& p : report["pieces"])
        if (p["id"] == id.value)
            return p;
    FAIL("no piece " << id.value);
    return report;
}

/// Three two-bar hangers: a tube of 3 columns and 2 rows on a triangle rail. Each knot of row 1
/// hangs by two bars from two corners of the triangle, and from nothing else.
struct Hangers {
    Document doc;
    PieceId piece;
    double side = 0; ///< m, the triangle's side: the two bars' ends are this far apart
};

Hangers hangers(double radius, double bar, Material material) {
    Hangers h;
    const RailId rail =
        h.doc.execute(AddRailCommand{"triangle", polygonRail(3, radius, 4.0)}).rails.at(0);
    h.piece = h.doc.execute(AttachToRailCommand{{rail, 3, 0, 2, bar, 0, false}}).pieces.at(0);
    h.doc.execute(SetMaterialCommand{h.piece, material});
    h.side = radius * std::sqrt(3.0);
    return h;
}

/// The tension in each bar of a symmetric two-bar hanger, by hand: bars of rest length l and
/// stiffness EA from two points 2a apart, a knot of mass m at depth d below their middle. Its
/// bars are sqrt(a^2 + d^2) long with tension T = EA (L - l) / l, and 2 T d / L = m g. The
/// depth is found by bisection.
double hangerTension(double a, double l, double ea, double m, double g) {
    const auto tension = [&](double d) { return ea * (std::hypot(a, d) - l) / l; };
    const auto excess = [&](double d) { return 2 * tension(d) * d / std::hypot(a, d) - m * g; };
    double lo = std::sqrt(l * l - a * a), hi = l;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (excess(mid) < 0 ? lo : hi) = mid;
    }
    return tension(0.5 * (lo + hi));
}

std::string g6Text(const json& v) {
    return g6(v.get<double>());
}

} // namespace

TEST_CASE("a two-bar hanger's tension, utilisation and safety factor agree with a hand solution") {
    Material rope;            // the real rope: EA 2e5 N, 2 g knots, 6 g/m
    rope.breakingLoad = 0.16; // N: a thread, so that the hanger's own weight loads it
    const double bar = 0.6;
    Hangers h = hangers(0.5, bar, rope);
    REQUIRE(h.doc.relax().converged);
    const json r = buildReport(h.doc);

    // A row-1 knot weighs its knot and half of each of its two bars.
    const double mass = rope.knotMass + 0.5 * rope.linearDensity * 2 * bar;
    const double tension = hangerTension(h.side / 2, bar, rope.stiffness, mass, 9.81);
    CHECK(tension == Approx(0.0397).epsilon(0.01)); // about m g l / (2 d)
    const json& p = pieceOf(r, h.piece);
    CHECK(p["max_tension"].get<double>() == Approx(tension).epsilon(1e-6));
    CHECK(p["breaking_load"].get<double>() == 0.16);
    CHECK(p["material"]["breaking_load"].get<double>() == 0.16);
    CHECK(p["utilisation"].get<double>() == Approx(tension / 0.16).epsilon(1e-6));
    CHECK(p["safety_factor"].get<double>() == Approx(0.16 / tension).epsilon(1e-6));
    const json& at = p["max_tension_at"];
    CHECK(at["piece"] == h.piece.value);
    CHECK(at["a"]["row"].get<int>() + at["b"]["row"].get<int>() == 1); // a bar up from row 1
    CHECK(r["min_safety_factor"] == p["safety_factor"]);
    CHECK(r["min_safety_factor_at"] == at);
    CHECK(r["pieces_without_breaking_load"].empty());
    CHECK(r["units"]["utilisation"] == "fraction of the breaking load (0.25 = 25 %)");

    const std::string md = reportMarkdown(r);
    CHECK_THAT(md, Contains("| least safety factor | " + g6Text(p["safety_factor"]) +
                            " (piece 1, " + barPlaceText(at) + ": " + g6Text(p["max_tension"]) +
                            " N of a breaking load of 0.16 N) |\n"));
    CHECK_THAT(md, Contains("| pieces without a breaking load | none |\n"));
    CHECK_THAT(md, Contains("\n## Strength\n"));
    CHECK_THAT(md, Contains("| 1 | piece 1 | 0.16 | " + g6Text(p["max_tension"]) + " | " +
                            g6(100 * p["utilisation"].get<double>()) + " % | " +
                            g6Text(p["safety_factor"]) + " | " + barPlaceText(at) + " |\n"));
    CHECK_THAT(md, !Contains("below 1"));

    // A breaking load below the tension: a safety factor under 1, which the summary says.
    Material weak = rope;
    weak.breakingLoad = 0.03;
    h.doc.execute(SetMaterialCommand{h.piece, weak});
    REQUIRE(h.doc.relax().converged);
    const json broken = buildReport(h.doc);
    CHECK(broken["min_safety_factor"].get<double>() == Approx(0.03 / tension).epsilon(1e-6));
    CHECK_THAT(reportMarkdown(broken),
               Contains(" N of a breaking load of 0.03 N) **below 1: the tension computed is more "
                        "than the rope holds** |"));
}

TEST_CASE("per piece, the safety factor is the breaking load over the largest tension recomputed "
          "from the bars - pieces without one are named and not checked") {
    // A tube with a skirt geared x2 below it, in soft rope, relaxed. Only the tube has a
    // breaking load.
    Document doc;
    const RailId ring = doc.execute(AddRailCommand{"ring", polygonRail(12, 1.0, 3.0)}).rails.at(0);
    const PieceId tube =
        doc.execute(AttachToRailCommand{{ring, 12, 0, 5, 0.4, 0, false}}).pieces.at(0);
    const PieceId skirt =
        doc.execute(AttachToPieceCommand{{tube, Gear{2, 1}, 4, 0.25}}).pieces.at(0);
    Material strong = softRope();
    strong.breakingLoad = 2.5;
    doc.execute(SetMaterialCommand{tube, strong});
    doc.execute(SetMaterialCommand{skirt, softRope()});
    doc.execute(RenamePieceCommand{skirt, "skirt"});
    DocumentRelaxOptions options;
    options.backend = "rk4";
    REQUIRE(doc.relax(options).converged);
    const json r = buildReport(doc);

    // Every bar's tension from its ends and its stiffness in tension, largest per piece.
    const MassSpringSystem& sys = doc.compiled().system;
    std::map<std::uint32_t, double> largest;
    for (std::size_t b = 0; b < sys.barCount(); ++b) {
        const double stretch =
            distance(sys.position[sys.barA[b]], sys.position[sys.barB[b]]) - sys.restLength[b];
        if (stretch > 0)
            largest[sys.barPiece[b].value] =
                std::max(largest[sys.barPiece[b].value], sys.kTension[b] * stretch);
    }
    REQUIRE(largest.size() == 2);
    CHECK(largest[tube.value] > largest[skirt.value]); // the tube carries the skirt

    const json& top = pieceOf(r, tube);
    CHECK(top["max_tension"].get<double>() == Approx(largest[tube.value]).epsilon(1e-12));
    CHECK(top["safety_factor"].get<double>() == Approx(2.5 / largest[tube.value]).epsilon(1e-12));
    CHECK(top["utilisation"].get<double>() == Approx(largest[tube.value] / 2.5).epsilon(1e-12));
    // The bar named is one with that tension.
    const json& at = top["max_tension_at"];
    const std::size_t b = at["bar"].get<std::size_t>();
    CHECK(sys.barPiece[b] == tube);
    CHECK(sys.kTension[b] * (distance(sys.position[sys.barA[b]], sys.position[sys.barB[b]]) -
                             sys.restLength[b]) ==
          Approx(largest[tube.value]).epsilon(1e-12));

    const json& below = pieceOf(r, skirt);
    CHECK(below["max_tension"].get<double>() == Approx(largest[skirt.value]).epsilon(1e-12));
    CHECK(below["max_tension_at"]["piece"] == skirt.value);
    CHECK(below["breaking_load"].is_null()); // no default strength is made up
    CHECK(below["material"]["breaking_load"].is_null());
    CHECK(below["utilisation"].is_null());
    CHECK(below["safety_factor"].is_null());
    // The least safety factor is over the pieces that have a breaking load: the tube's, though
    // the skirt has none.
    CHECK(r["min_safety_factor"] == top["safety_factor"]);
    CHECK(r["min_safety_factor_at"] == at);
    CHECK(r["pieces_without_breaking_load"] == json::array({skirt.value}));

    const std::string md = reportMarkdown(r);
    CHECK_THAT(md, Contains("| pieces without a breaking load | 2 (skirt): not checked |\n"));
    CHECK_THAT(md,
               Contains("| 2 | skirt | none | " + g6Text(below["max_tension"]) +
                        " | - | not checked | " + barPlaceText(below["max_tension_at"]) + " |\n"));

    const std::string csv = reportPiecesCsv(r);
    CHECK_THAT(csv, Contains(",knots_tied,breaking_load,utilisation,safety_factor,"
                             "max_tension_at,seams,load_case\n"));
    const auto field = [](const json& v) { return io::numberText(v.get<double>()); };
    CHECK_THAT(csv,
               Contains(",2.5," + field(top["utilisation"]) + "," + field(top["safety_factor"]) +
                        "," + barPlaceText(at) + ",,weight alone\n"));
    CHECK_THAT(csv, Contains(",,,," + barPlaceText(below["max_tension_at"]) + ",,weight alone\n"));

    // No piece with a breaking load: no least safety factor, and every piece named.
    doc.undo(); // the skirt's name
    doc.undo(); // the skirt's material
    doc.undo(); // the tube's breaking load
    const json none = buildReport(doc);
    CHECK(none["min_safety_factor"].is_null());
    CHECK(none["min_safety_factor_at"].is_null());
    CHECK(none["pieces_without_breaking_load"] == json::array({tube.value, skirt.value}));
    CHECK_THAT(reportMarkdown(none),
               Contains("| least safety factor | none: no piece has a breaking load |\n"
                        "| pieces without a breaking load | 1 (piece 1), 2 (piece 2): not "
                        "checked |\n"));
}

TEST_CASE("a piece with a breaking load and no bar in tension has no safety factor") {
    Material rope;
    rope.breakingLoad = 100;
    const json slack = pieceStrength(rope, 0);
    CHECK(slack["breaking_load"].get<double>() == 100);
    CHECK(slack["utilisation"].get<double>() == 0);
    CHECK(slack["safety_factor"].is_null()); // nothing pulls: not an infinite number in JSON
    const json pieces = json::array({{{"id", 1},
                                      {"breaking_load", 100},
                                      {"safety_factor", nullptr},
                                      {"max_tension_at", nullptr}}});
    const json summary = strengthSummary(pieces);
    CHECK(summary["min_safety_factor"].is_null());
    CHECK(summary["pieces_without_breaking_load"].empty());

    json report = summary;
    report["pieces"] = json::array({{{"id", 1},
                                     {"name", "loose"},
                                     {"breaking_load", 100.0},
                                     {"max_tension", 0.0},
                                     {"max_tension_at", nullptr},
                                     {"utilisation", 0.0},
                                     {"safety_factor", nullptr}}});
    CHECK_THAT(strengthSummaryMarkdown(report),
               Contains("| least safety factor | none: no bar of a piece with a breaking load is "
                        "in tension |"));
    CHECK_THAT(strengthMarkdown(report),
               Contains("| 1 | loose | 100 | 0 | 0 % | - (no bar in tension) | - |\n"));
}
