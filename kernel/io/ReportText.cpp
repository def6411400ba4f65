// The report as text: a Markdown summary for people (numbers rounded to 6 significant digits)
// and CSV tables for programs (numbers with round-trip precision).

#include "io/Report.h"

#include "io/IoText.h"
#include "io/ReportSections.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace netsculpt {

std::string g6(double value) {
    if (value == 0)
        value = 0; // no "-0"
    char text[40];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

std::string markdownCell(const std::string& text) {
    std::string out;
    for (char c : text)
        out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

std::string barPlaceText(const nlohmann::json& at) {
    return "row " + integerText(at["a"]["row"]) + " column " + integerText(at["a"]["column"]) +
           " to row " + integerText(at["b"]["row"]) + " column " + integerText(at["b"]["column"]);
}

std::string integerText(const nlohmann::json& v) {
    return std::to_string(v.get<long long>());
}

const nlohmann::json& reportPiece(const nlohmann::json& report, const nlohmann::json& id) {
    for (const nlohmann::json& p : report["pieces"])
        if (p["id"] == id)
            return p;
    throw std::logic_error("report: no piece " + integerText(id));
}

namespace {

using netsculpt::g6; // beside the JSON overload below, so that a double finds the double one
using nlohmann::json;

std::string g6(const json& v) {
    return v.is_number() ? g6(v.get<double>()) : "-";
}

/// A place or a distance to a tenth of a millimetre, however far from the origin (site
/// coordinates are hundreds of kilometres from it).
std::string metres(double value) {
    if (std::abs(value) < 5e-5)
        value = 0; // no "-0.0000"
    char text[48];
    std::snprintf(text, sizeof text, "%.4f", value);
    return text;
}

std::string vecText(const json& v) {
    return io::concat({"(", g6(v["x"]), ", ", g6(v["y"]), ", ", g6(v["z"]), ")"});
}

std::string placeText(const json& v) {
    return io::concat({"(", metres(v["x"].get<double>()), ", ", metres(v["y"].get<double>()), ", ",
                       metres(v["z"].get<double>()), ")"});
}

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos)
        return text;
    std::string out = "\"";
    for (char c : text)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string num(const json& v) {
    return v.is_number_integer() ? std::to_string(v.get<long long>())
                                 : io::numberText(v.get<double>());
}

/// "piece P, row R column C to row R' column C'" for a max_tension_at / max_strain_at entry.
std::string barText(const json& at) {
    return "piece " + num(at["piece"]) + ", " + barPlaceText(at);
}

/// Where an edge on a rail starts: "rail 1 (crown), from 10.0000 m along it (t = 0.333)", and
/// ", backwards" when its columns run against the rail's direction.
std::string railEdgeText(const json& edge) {
    return "rail " + num(edge["rail"]) + " (" + edge["rail_name"].get<std::string>() + "), from " +
           metres(edge["start_along"].get<double>()) + " m along it (t = " + g6(edge["start"]) +
           ")" + (edge["reverse"].get<bool>() ? ", backwards" : "");
}

std::string topText(const json& top) {
    if (top["kind"] == "rail")
        return railEdgeText(top);
    std::string parents;
    for (const auto& p : top["parents"])
        parents += io::concat({parents.empty() ? "" : "+", std::to_string(p.get<int>())});
    const int offset = top["offset"].get<int>();
    return "piece " + parents + ", gear " + top["gear"].get<std::string>() +
           (offset > 0 ? ", from " + childStartText(top) : "");
}

std::string seamsText(const json& seams) {
    std::string text;
    for (const json& seam : seams)
        text += (text.empty() ? "" : "; ") + std::string("piece ") + num(seam["piece"]) +
                " to the " + seam["side"].get<std::string>() + ": its column " +
                num(seam["column"]) + ", rows 0 to " + std::to_string(seam["rows"].get<int>() - 1) +
                ", is column " + num(seam["other_column"]) + " of piece " + num(seam["piece"]) +
                " (the " + num(seam["shared_bars"]) + " bars along the seam counted in piece " +
                num(seam["shared_bars_counted_in"]) + ")";
    return text.empty() ? "-" : text;
}

/// A piece's bar lengths as knotted: between its rows when its length varies by row, else per
/// column.
const json& knottedLengths(const json& p) {
    const json& byRow = p["bar_lengths_between_rows"];
    return byRow.empty() ? p["bar_lengths"] : byRow;
}

/// Whether a piece graded by row hangs from a gear-up: its new knots of row 0 hang by bars of
/// row 0's length, which no length between two rows is.
bool rowGearBars(const json& p) {
    return gearsUp(p) && !p["bar_lengths_between_rows"].empty();
}

/// The bar lengths as knotted, first to last: "0.25 at column 0 to 0.2 at column 12", or
/// between rows for a piece whose length varies by row (and its gear's bars in row 0).
std::string barLengthText(const json& p) {
    const json& lengths = knottedLengths(p);
    const double first = lengths.front().get<double>(), last = lengths.back().get<double>();
    if (first == last)
        return g6(first);
    if (!p["bar_lengths_between_rows"].empty())
        return g6(first) + " between rows 0 and 1 to " + g6(last) + " between rows " +
               std::to_string(lengths.size() - 1) + " and " + std::to_string(lengths.size()) +
               (rowGearBars(p) ? ", " + g6(p["bar_lengths"][0]) + " in row 0 (the gear's new knots)"
                               : std::string());
    return g6(first) + " at column 0 to " + g6(last) + " at column " +
           std::to_string(lengths.size() - 1);
}

/// "first,last": the knotted bar lengths at the first and last column (or between the first
/// and the last two rows), round-trip precision.
std::string knottedEnds(const json& p) {
    const json& lengths = knottedLengths(p);
    return num(lengths.front()) + "," + num(lengths.back());
}

std::string piecesMarkdown(const json& r) {
    std::string md =
        "## Pieces\n\nBar lengths as knotted, first to last (every bar's length under Bar "
        "lengths below), from knot centre to knot centre. A seam's two pieces share the knots of "
        "one column, and a piece hanging from another shares its row 0 with the other's last row "
        "(Joins below): such knots are tied once, counted under \"knots tied\" in one piece, and "
        "the bars along a seam are made once, with the piece they are counted in. Rope lengths "
        "are the bars' lengths summed, without the rope a knot or a tie to a rail takes.\n\n"
        "| id | name | rows x columns | closed | knots | knots tied | bars | rope (m) | mass (kg) "
        "| bar length (m) | largest tension (N) | top | last row | seams |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const json& p : r["pieces"])
        md += "| " + num(p["id"]) + " | " + markdownCell(p["name"].get<std::string>()) + " | " +
              num(p["rows"]) + " x " + num(p["columns"]) + " | " +
              (p["closed"].get<bool>() ? "yes" : "no") + " | " + num(p["knots"]) + " | " +
              num(p["knots_tied"]) + " | " + num(p["bars"]) + " | " + g6(p["rope_length"]) + " | " +
              g6(p["mass"]) + " | " + barLengthText(p) + " | " + g6(p["max_tension"]) + " | " +
              markdownCell(topText(p["top"])) + " | " +
              markdownCell(p["bottom"].is_null() ? "free" : railEdgeText(p["bottom"])) + " | " +
              seamsText(p["seams"]) + " |\n";
    return md;
}

/// "0.789 (2 knots; 24 points shared)", or the one knot's reaction where no point is shared.
std::string pointLoadText(const json& rail) {
    const std::string load = g6(rail["max_point_load"]);
    const std::size_t shared = rail["shared_points"].get<std::size_t>();
    if (shared == 0)
        return load;
    return load + " (" + num(rail["max_point_load_knots"]) + " knots; " + std::to_string(shared) +
           (shared == 1 ? " point" : " points") + " shared)";
}

std::string railsMarkdown(const json& r) {
    std::string md =
        "\n## Rails\n\nA reaction is the force the rail exerts on the net, in newtons along the "
        "sculpture's axes (z up); the load on the rail is its opposite. The largest reaction is "
        "that of one knot; pieces tied at the same rail points load each point with the sum of "
        "their knots' reactions, and the largest load at a point is the largest such sum "
        "(Attachment points below list every knot).\n\n"
        "| id | name | length (m) | closed | attachments | reaction sum (N) | largest reaction "
        "(N) | largest load at a point (N) |\n|---|---|---|---|---|---|---|---|\n";
    for (const json& rail : r["rails"])
        md += "| " + num(rail["id"]) + " | " + markdownCell(rail["name"].get<std::string>()) +
              " | " + g6(rail["length"]) + " | " + (rail["closed"].get<bool>() ? "yes" : "no") +
              " | " + num(rail["attachments"]) + " | " + vecText(rail["reaction"]) + " | " +
              g6(rail["max_reaction"]) + " | " + pointLoadText(rail) + " |\n";
    return md;
}

/// Where a tape laid along the rail starts and which way it runs: "along" is measured from there.
std::string railStartText(const json& rail) {
    return "Distances along the rail are measured from its start, " + placeText(rail["start"]) +
           " m, the way it runs from there: towards " + vecText(rail["direction"]) +
           " (a unit vector)" +
           (rail["closed"].get<bool>() ? ", and round the ring back to its start" : "") + ".";
}

/// Every point where the net is held, rail by rail, in the order of t.
std::string attachmentsMarkdown(const json& r) {
    std::string md = "\n## Attachment points\n";
    for (const json& rail : r["rails"]) {
        if (rail["points"].empty())
            continue;
        md += "\n### Rail " + num(rail["id"]) + " (" +
              markdownCell(rail["name"].get<std::string>()) + ")\n\n" + railStartText(rail) +
              "\n\n| piece | row | column | t | along the rail (m) | position (m) | reaction (N) "
              "| magnitude (N) |\n|---|---|---|---|---|---|---|---|\n";
        for (const json& p : rail["points"])
            md += "| " + num(p["piece"]) + " | " + num(p["row"]) + " | " + num(p["column"]) +
                  " | " + g6(p["t"]) + " | " + metres(p["along"].get<double>()) + " | " +
                  placeText(p["position"]) + " | " + vecText(p["reaction"]) + " | " +
                  g6(p["magnitude"]) + " |\n";
    }
    return md;
}

/// "breaking_load,utilisation,safety_factor,max_tension_at": a field is empty where the report
/// has null (no breaking load; no bar in tension).
std::string strengthCsv(const json& p) {
    const auto optional = [](const json& v) { return v.is_null() ? std::string() : num(v); };
    return optional(p["breaking_load"]) + "," + optional(p["utilisation"]) + "," +
           optional(p["safety_factor"]) + "," +
           (p["max_tension_at"].is_null() ? std::string() : barPlaceText(p["max_tension_at"]));
}

/// The load case every tension and reaction of the report is of: "weight alone", or the weight
/// and the wind its shape was relaxed in.
std::string loadCaseText(const json& r) {
    const json& wind = r.contains("wind") ? r["wind"] : json();
    return wind.is_object() ? "weight and a wind of " + g6(wind["pressure"]) + " N/m towards " +
                                  vecText(wind["direction"])
                            : std::string("weight alone");
}

} // namespace

std::string reportMarkdown(const json& r) {
    std::string md = "# netsculpt report\n\n";
    const json& relax = r["relax"];
    // The residual beside the tolerance it was relaxed to: what "relaxed" promises of the loads.
    const std::string residual =
        g6(r["residual"]) + " for the tolerance " + g6(r["force_balance"]["tolerance"]);
    if (r["relaxed"].get<bool>() && relax.is_null())
        md += "Shape: **relaxed** (residual " + residual +
              "; relaxed before the file was saved).\n\n";
    else if (r["relaxed"].get<bool>())
        md += "Shape: **relaxed** (residual " + residual + ", " +
              relax["backend"].get<std::string>() + ", " +
              std::to_string(relax["steps"].get<long long>()) + " steps, " + g6(relax["seconds"]) +
              " s).\n\n";
    else
        md += "Shape: **not relaxed** (residual " + g6(r["residual"]) +
              "); loads and tensions are those of the current, unbalanced shape.\n\n";
    md += "| quantity | value |\n|---|---|\n";
    // Every load below is of this case: a wind's load is in the tensions and reactions too.
    md += "| load case | " + loadCaseText(r) + " |\n";
    md += "| knots | " + num(r["knots"]) + " |\n| bars | " + num(r["bars"]) + " |\n";
    md += "| rope length | " + g6(r["rope_length"]) + " m |\n";
    md += "| total mass | " + g6(r["total_mass"]) + " kg |\n| total weight | " +
          g6(r["total_weight"]) + " N |\n";
    md += "| largest tension | " + g6(r["max_tension"]) + " N";
    if (!r["max_tension_at"].is_null())
        md += " (" + barText(r["max_tension_at"]) + ")";
    md += " |\n| largest strain | " + g6(100 * r["max_strain"].get<double>()) + " %";
    if (!r["max_strain_at"].is_null())
        md += " (" + barText(r["max_strain_at"]) + ")";
    md += " |\n| slack bars | " + num(r["slack_bars"]) + " |\n" + strengthSummaryMarkdown(r) + "\n";
    const bool settled =
        r["relaxed"].get<bool>() || r["residual"].get<double>() <= kSettledResidual;
    if (settled && r["overstretched_bars"].get<std::size_t>() > 0)
        md += "**Check the design:** " + num(r["overstretched_bars"]) +
              " bars are stretched by more than " +
              g6(100 * r["overstretch_limit"].get<double>()) +
              " % of their length. Net rope stretches a few per cent under load and yields or "
              "breaks before 20 %: the net is tied between rails farther apart than it reaches, "
              "and the tensions and rail loads below are those of a rope that does not exist.\n\n";

    const json& fb = r["force_balance"];
    const bool windy = r.contains("wind") && !r["wind"].is_null();
    md += "## Force balance\n\nSum of the rail reactions " + vecText(fb["reaction_sum"]) +
          " N against the weight" +
          (windy ? " and the wind (" + g6(r["wind"]["pressure"]) + " N/m towards " +
                       vecText(r["wind"]["direction"]) + ": " + vecText(r["wind"]["force"]) +
                       " N on the net)"
                 : std::string()) +
          " " + vecText(fb["expected"]) + " N: relative difference " +
          g6(fb["relative_difference"]) + ", " +
          (fb["within_tolerance"].get<bool>() ? "within" : "**not within**") + " the tolerance " +
          g6(fb["tolerance"]) + ". " + fb["note"].get<std::string>() + ".\n\n";

    return md + piecesMarkdown(r) + strengthMarkdown(r) + joinsMarkdown(r) + barLengthsMarkdown(r) +
           railsMarkdown(r) + attachmentsMarkdown(r);
}

std::string reportPiecesCsv(const json& r) {
    std::string csv =
        "id,name,rows,columns,closed,knots,bars,rope_length,mass,bar_axis,bar_min,bar_max,"
        "bar_first,bar_last,max_tension,top,last_row,knots_tied,breaking_load,utilisation,"
        "safety_factor,max_tension_at,seams,load_case\n";
    const std::string loadCase = csvField(loadCaseText(r));
    for (const json& p : r["pieces"]) {
        std::vector<double> lengths = knottedLengths(p).get<std::vector<double>>();
        if (rowGearBars(p))
            lengths.push_back(p["bar_lengths"][0].get<double>());
        const auto [lo, hi] = std::minmax_element(lengths.begin(), lengths.end());
        csv += num(p["id"]) + "," + csvField(p["name"].get<std::string>()) + "," + num(p["rows"]) +
               "," + num(p["columns"]) + "," + (p["closed"].get<bool>() ? "1" : "0") + "," +
               num(p["knots"]) + "," + num(p["bars"]) + "," + num(p["rope_length"]) + "," +
               num(p["mass"]) + "," + p["bar_axis"].get<std::string>() + "," + io::numberText(*lo) +
               "," + io::numberText(*hi) + "," + knottedEnds(p) + "," + num(p["max_tension"]) +
               "," + csvField(topText(p["top"])) + "," +
               csvField(p["bottom"].is_null() ? "free" : railEdgeText(p["bottom"])) + "," +
               num(p["knots_tied"]) + "," + strengthCsv(p) + "," +
               (p["seams"].empty() ? std::string() : csvField(seamsText(p["seams"]))) + "," +
               loadCase + "\n";
    }
    return csv;
}

std::string reportAttachmentsCsv(const json& r) {
    std::string csv = "rail,piece,row,column,t,x,y,z,fx,fy,fz,magnitude,along,load_case\n";
    const std::string loadCase = csvField(loadCaseText(r));
    for (const json& rail : r["rails"])
        for (const json& p : rail["points"])
            csv += num(rail["id"]) + "," + num(p["piece"]) + "," + num(p["row"]) + "," +
                   num(p["column"]) + "," + num(p["t"]) + "," + num(p["position"]["x"]) + "," +
                   num(p["position"]["y"]) + "," + num(p["position"]["z"]) + "," +
                   num(p["reaction"]["x"]) + "," + num(p["reaction"]["y"]) + "," +
                   num(p["reaction"]["z"]) + "," + num(p["magnitude"]) + "," + num(p["along"]) +
                   "," + loadCase + "\n";
    return csv;
}

} // namespace netsculpt
