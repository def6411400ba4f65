// The report's strength check (ReportSections.h): each piece's largest tension against its
// material's breaking load, the least safety factor over the sculpture, and the pieces that have
// no breaking load, so the engineer sees what is not checked. No strength is ever assumed.

#include "io/ReportSections.h"

#include <nlohmann/json.hpp>

#include <string>

namespace netsculpt {

namespace {

using nlohmann::json;

/// "1 (tube), 2 (skirt)" for piece ids.
std::string pieceNames(const json& report, const json& ids) {
    std::string text;
    for (const json& id : ids)
        text += (text.empty() ? "" : ", ") + integerText(id) + " (" +
                reportPiece(report, id)["name"].get<std::string>() + ")";
    return text;
}

/// "6.52 (piece 1, row 0 column 3 to row 1 column 3: 460 N of a breaking load of 3000 N)".
std::string leastSafetyText(const json& report) {
    const json& at = report["min_safety_factor_at"];
    const json& piece = reportPiece(report, at["piece"]);
    const double factor = report["min_safety_factor"].get<double>();
    return g6(factor) + " (piece " + integerText(at["piece"]) + ", " + barPlaceText(at) + ": " +
           g6(piece["max_tension"].get<double>()) + " N of a breaking load of " +
           g6(piece["breaking_load"].get<double>()) + " N)" +
           (factor < 1 ? " **below 1: the tension computed is more than the rope holds**" : "");
}

std::string strengthRow(const json& p) {
    const bool checked = p["breaking_load"].is_number();
    const bool pulled = !p["max_tension_at"].is_null();
    const std::string factor = !checked ? "not checked"
                               : pulled ? g6(p["safety_factor"].get<double>())
                                        : "- (no bar in tension)";
    return "| " + integerText(p["id"]) + " | " + markdownCell(p["name"].get<std::string>()) +
           " | " + (checked ? g6(p["breaking_load"].get<double>()) : std::string("none")) + " | " +
           g6(p["max_tension"].get<double>()) + " | " +
           (checked ? g6(100 * p["utilisation"].get<double>()) + " %" : std::string("-")) + " | " +
           factor + " | " + (pulled ? barPlaceText(p["max_tension_at"]) : std::string("-")) +
           " |\n";
}

} // namespace

json pieceStrength(const Material& material, double maxTension) {
    if (!material.breakingLoad)
        return {{"breaking_load", nullptr}, {"utilisation", nullptr}, {"safety_factor", nullptr}};
    const double breakingLoad = *material.breakingLoad;
    return {{"breaking_load", breakingLoad},
            {"utilisation", maxTension / breakingLoad},
            {"safety_factor", maxTension > 0 ? json(breakingLoad / maxTension) : json(nullptr)}};
}

json strengthSummary(const json& pieces) {
    json least = nullptr, at = nullptr, without = json::array();
    for (const json& p : pieces) {
        if (p["breaking_load"].is_null())
            without.push_back(p["id"]);
        else if (p["safety_factor"].is_number() &&
                 (least.is_null() || p["safety_factor"].get<double>() < least.get<double>()))
            least = p["safety_factor"], at = p["max_tension_at"];
    }
    return {{"min_safety_factor", least},
            {"min_safety_factor_at", at},
            {"pieces_without_breaking_load", without}};
}

std::string strengthSummaryMarkdown(const json& report) {
    const json& without = report["pieces_without_breaking_load"];
    std::string least;
    if (report["min_safety_factor"].is_number())
        least = leastSafetyText(report);
    else if (without.size() == report["pieces"].size())
        least = "none: no piece has a breaking load";
    else
        least = "none: no bar of a piece with a breaking load is in tension";
    return "| least safety factor | " + least + " |\n| pieces without a breaking load | " +
           (without.empty() ? std::string("none")
                            : markdownCell(pieceNames(report, without)) + ": not checked") +
           " |\n";
}

std::string strengthMarkdown(const json& report) {
    std::string md =
        "\n## Strength\n\nEach piece's largest bar tension, in the load case and shape above, "
        "against its breaking load: a bar's as knotted, with the knots' loss of strength in it "
        "(set_material's breaking_load). Utilisation is the largest tension over the breaking "
        "load, the safety factor the breaking load over the largest tension. A piece without a "
        "breaking load is not checked: no strength is assumed for it.\n\n"
        "| id | name | breaking load (N) | largest tension (N) | utilisation | safety factor | "
        "where |\n|---|---|---|---|---|---|---|\n";
    for (const json& p : report["pieces"])
        md += strengthRow(p);
    return md;
}

} // namespace netsculpt
