// The report as text: a Markdown summary for people (numbers rounded to 6 significant digits)
// and CSV tables for programs (numbers with round-trip precision).

#include "io/Report.h"

#include "io/IoText.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>

namespace netsculpt {

namespace {

using nlohmann::json;

std::string g6(double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

std::string g6(const json& v) {
    return v.is_number() ? g6(v.get<double>()) : "-";
}

std::string vecText(const json& v) {
    return io::concat({"(", g6(v["x"]), ", ", g6(v["y"]), ", ", g6(v["z"]), ")"});
}

std::string cell(const std::string& text) {
    std::string out;
    for (char c : text)
        out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
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
    return "piece " + num(at["piece"]) + ", row " + num(at["a"]["row"]) + " column " +
           num(at["a"]["column"]) + " to row " + num(at["b"]["row"]) + " column " +
           num(at["b"]["column"]);
}

std::string topText(const json& top) {
    if (top["kind"] == "rail")
        return "rail " + std::to_string(top["rail"].get<int>()) + " (" +
               top["rail_name"].get<std::string>() + ")";
    std::string parents;
    for (const auto& p : top["parents"])
        parents += io::concat({parents.empty() ? "" : "+", std::to_string(p.get<int>())});
    return "piece " + parents + ", gear " + top["gear"].get<std::string>();
}

} // namespace

std::string reportMarkdown(const json& r) {
    std::string md = "# netsculpt report\n\n";
    const json& relax = r["relax"];
    if (r["relaxed"].get<bool>() && relax.is_null())
        md += "Shape: **relaxed** (residual " + g6(r["residual"]) +
              "; relaxed before the file was saved).\n\n";
    else if (r["relaxed"].get<bool>())
        md += "Shape: **relaxed** (residual " + g6(r["residual"]) + ", " +
              relax["backend"].get<std::string>() + ", " +
              std::to_string(relax["steps"].get<long long>()) + " steps, " + g6(relax["seconds"]) +
              " s).\n\n";
    else
        md += "Shape: **not relaxed** (residual " + g6(r["residual"]) +
              "); loads and tensions are those of the current, unbalanced shape.\n\n";
    md += "| quantity | value |\n|---|---|\n";
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
    md += " |\n| slack bars | " + num(r["slack_bars"]) + " |\n\n";
    if (r["relaxed"].get<bool>() && r["overstretched_bars"].get<std::size_t>() > 0)
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

    md += "## Pieces\n\n| id | name | rows x columns | closed | knots | bars | rope (m) | mass "
          "(kg) | bar length (m) | top |\n"
          "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const json& p : r["pieces"]) {
        double lo = 0, hi = 0;
        bool first = true;
        for (const json& l : p["bar_lengths"]) {
            const double v = l.get<double>();
            lo = first ? v : std::min(lo, v);
            hi = first ? v : std::max(hi, v);
            first = false;
        }
        const std::string bar =
            lo == hi ? g6(lo)
                     : g6(lo) + " to " + g6(hi) + " by " + p["bar_axis"].get<std::string>();
        md += "| " + num(p["id"]) + " | " + cell(p["name"].get<std::string>()) + " | " +
              num(p["rows"]) + " x " + num(p["columns"]) + " | " +
              (p["closed"].get<bool>() ? "yes" : "no") + " | " + num(p["knots"]) + " | " +
              num(p["bars"]) + " | " + g6(p["rope_length"]) + " | " + g6(p["mass"]) + " | " + bar +
              " | " + cell(topText(p["top"])) + " |\n";
    }
    md += "\n## Rails\n\n| id | name | length (m) | closed | attachments | reaction sum (N) | "
          "largest reaction (N) |\n"
          "|---|---|---|---|---|---|---|\n";
    for (const json& rail : r["rails"])
        md += "| " + num(rail["id"]) + " | " + cell(rail["name"].get<std::string>()) + " | " +
              g6(rail["length"]) + " | " + (rail["closed"].get<bool>() ? "yes" : "no") + " | " +
              num(rail["attachments"]) + " | " + vecText(rail["reaction"]) + " | " +
              g6(rail["max_reaction"]) + " |\n";
    return md;
}

std::string reportPiecesCsv(const json& r) {
    std::string csv =
        "id,name,rows,columns,closed,knots,bars,rope_length,mass,bar_axis,bar_min,bar_max\n";
    for (const json& p : r["pieces"]) {
        double lo = 0, hi = 0;
        bool first = true;
        for (const json& l : p["bar_lengths"]) {
            const double v = l.get<double>();
            lo = first ? v : std::min(lo, v);
            hi = first ? v : std::max(hi, v);
            first = false;
        }
        csv += num(p["id"]) + "," + csvField(p["name"].get<std::string>()) + "," + num(p["rows"]) +
               "," + num(p["columns"]) + "," + (p["closed"].get<bool>() ? "1" : "0") + "," +
               num(p["knots"]) + "," + num(p["bars"]) + "," + num(p["rope_length"]) + "," +
               num(p["mass"]) + "," + p["bar_axis"].get<std::string>() + "," + io::numberText(lo) +
               "," + io::numberText(hi) + "\n";
    }
    return csv;
}

std::string reportAttachmentsCsv(const json& r) {
    std::string csv = "rail,piece,row,column,t,x,y,z,fx,fy,fz,magnitude\n";
    for (const json& rail : r["rails"])
        for (const json& p : rail["points"])
            csv += num(rail["id"]) + "," + num(p["piece"]) + "," + num(p["row"]) + "," +
                   num(p["column"]) + "," + num(p["t"]) + "," + num(p["position"]["x"]) + "," +
                   num(p["position"]["y"]) + "," + num(p["position"]["z"]) + "," +
                   num(p["reaction"]["x"]) + "," +
                   num(p["reaction"]["y"]) + "," + num(p["reaction"]["z"]) + "," +
                   num(p["magnitude"]) + "\n";
    return csv;
}

} // namespace netsculpt
