// The netsculpt program's loads: what `relax`, `report` and `export` give an engineer for a
// document whose shape carries a load case (wind) or was relaxed loosely.

#include "CliSupport.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>

using namespace netsculpt::test;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// A tube of 24 columns and 12 rows of 0.2 m bars on a ring: 11 x 24 knots below row 0, each with
// two bars up, so 528 bars and 105.6 m of rope. Saved as a snapshot relaxed in a wind of
// 0.05 N/m towards +y (converged) and as one whose wind relaxation stopped after a step.
const char* const kWindyTube = R"(local ns = require "netsculpt"
local doc = ns.new()
local ring = doc:add_rail{name = "ring", closed = true,
                          points = ns.circle{radius = 1, points = 48, centre = {0, 0, 5}}}
doc:attach_to_rail{rail = ring, columns = 24, rows = 12, bar = 0.2}
local wind = {direction = {0, 1, 0}, pressure = 0.05}
print("partial", doc:relax{wind = wind, max_steps = 1}.converged)
doc:save_snapshot("partial.nets")
print("converged", doc:relax{wind = wind}.converged)
doc:save_snapshot("windy.nets")
)";
constexpr double kRope = 528 * 0.2;             // m
constexpr double kPressure = 0.05;              // N/m
constexpr double kMostWind = kPressure * kRope; // N: every bar square to the wind

nlohmann::json reportOf(const fs::path& document) {
    const Ran ran = runCli("report " + quoted(document) + " --json -q");
    INFO(ran.output);
    REQUIRE(ran.exitCode == 0);
    return nlohmann::json::parse(ran.output);
}

/// The rails' reactions of a report against the weight and the wind it names.
void checkWindBalance(const nlohmann::json& report) {
    REQUIRE(report["wind"].is_object());
    CHECK(report["wind"]["pressure"].get<double>() == kPressure);
    const nlohmann::json& sum = report["force_balance"]["reaction_sum"];
    // The wind pushes the net towards +y, so the ring holds it back towards -y, by the wind's
    // load on the rope: at most q times the rope, and most of that on a tube standing across it.
    CHECK(sum["y"].get<double>() < -0.5 * kMostWind);
    CHECK(sum["y"].get<double>() > -kMostWind);
    CHECK(sum["y"].get<double>() == Approx(-report["wind"]["force"]["y"].get<double>()));
    CHECK(report["force_balance"]["within_tolerance"].get<bool>());
    CHECK_THAT(report["force_balance"]["note"].get<std::string>(),
               Contains("carry the total weight and the wind"));
}

} // namespace

TEST_CASE("relax, report and export keep the wind a snapshot's shape was relaxed under", "[cli]") {
    const fs::path dir = freshFolder("cli-wind");
    const fs::path script = dir / "windy.lua";
    std::ofstream(script) << kWindyTube;
    const Ran ran = runCli("run " + quoted(script) + " --out " + quoted(dir) + " -q");
    INFO(ran.output);
    REQUIRE(ran.exitCode == 0);
    REQUIRE_THAT(ran.output, Contains("partial\tfalse") && Contains("converged\ttrue"));

    // The wind's relaxation stopped short: report relaxes it again, in the same wind.
    const Ran told = runCli("report " + quoted(dir / "partial.nets"));
    INFO(told.output);
    CHECK(told.exitCode == 0);
    CHECK_THAT(told.output, Contains("relaxed it for the report (its wind, 0.05 N/m towards "
                                     "(0, 1, 0)): converged"));
    checkWindBalance(reportOf(dir / "partial.nets"));

    // relax of the relaxed snapshot writes a shape in the same wind, and says so.
    const Ran relaxed = runCli("relax " + quoted(dir / "windy.nets") + " --tolerance 1e-7 --out " +
                               quoted(dir / "again"));
    INFO(relaxed.output);
    CHECK(relaxed.exitCode == 0);
    CHECK_THAT(relaxed.output, Contains("windy.nets (its wind, 0.05 N/m towards (0, 1, 0)): "
                                        "converged"));
    checkWindBalance(reportOf(dir / "again" / "windy.nets"));

    // export's JSON of the stopped-short snapshot: relaxed in its wind before writing.
    const fs::path json = dir / "partial.json";
    REQUIRE(
        runCli("export " + quoted(dir / "partial.nets") + " " + quoted(json) + " -q").exitCode ==
        0);
    std::ifstream in(json);
    checkWindBalance(nlohmann::json::parse(in)["report"]);
}

TEST_CASE("relax to a tolerance finer than the coordinates allow says so, not that the net is big",
          "[cli]") {
    // The windy tube is 2 m across: its knots cannot be placed closer to the equilibrium than a
    // few 1e-8 of their weight at the rope's stiffness, whatever the tolerance asked.
    const fs::path dir = freshFolder("cli-precision");
    const fs::path script = dir / "windy.lua";
    std::ofstream(script) << kWindyTube;
    REQUIRE(runCli("run " + quoted(script) + " --out " + quoted(dir) + " -q").exitCode == 0);
    const Ran ran = runCli("relax " + quoted(dir / "windy.nets") + " --tolerance 1e-30 --out " +
                           quoted(dir / "fine"));
    INFO(ran.output);
    CHECK(ran.exitCode == 3);
    CHECK_THAT(ran.output, Contains("stopped (precision limit)") &&
                               Contains("which is above the tolerance 1e-30: relax with a "
                                        "tolerance above the residual"));
    CHECK_THAT(ran.output, !Contains("100 m"));
}
