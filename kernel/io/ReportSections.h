#pragma once
// The report's Markdown sections for the net maker (ReportFabrication.cpp), from the report's
// JSON (Report.h): how each piece hanging from another is knotted into it, and every bar length
// of a piece whose bar length varies. The strength check for the engineer (ReportStrength.cpp):
// its JSON fields and its Markdown.

#include "model/Material.h"

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace netsculpt {

/// "## Joins": for each piece hanging from others, which of its row-0 knots are which knots of
/// their last rows, and the rows it adds. Empty when no piece hangs from another.
std::string joinsMarkdown(const nlohmann::json& report);
/// "## Bar lengths": every length a graded piece's bars are knotted to, column by column or row
/// by row. Empty when every piece has one bar length.
std::string barLengthsMarkdown(const nlohmann::json& report);
/// Where a child whose column 0 is not its parents' first knot starts (its top's offset: a
/// split part), in the parents' knots: "knot (4, 3) of piece 1", or for a new knot of a gear-up
/// "the new knot after knot (4, 2) of piece 1" ("the first" / "the second" with gear 3).
std::string childStartText(const nlohmann::json& top);
/// Whether `piece` (a report's piece) hangs from its parents through gear 2 or 3: its row 0 has
/// new knots, each hung by two bars of its column's length, or row 0's when graded by row.
bool gearsUp(const nlohmann::json& piece);
/// A number as the Markdown prints it: 6 significant digits, no "-0".
std::string g6(double value);
/// Text for a Markdown table's cell: its "|" escaped.
std::string markdownCell(const std::string& text);
/// "row 0 column 3 to row 1 column 3": where a bar ({a, b} of a max_tension_at) is in its piece.
std::string barPlaceText(const nlohmann::json& at);
/// A JSON integer (an id, a row) as text.
std::string integerText(const nlohmann::json& v);
/// The entry of report["pieces"] whose id is `id`.
const nlohmann::json& reportPiece(const nlohmann::json& report, const nlohmann::json& id);

/// A piece's strength from its material and its largest tension (N): breaking_load (N; null
/// when the material has none), utilisation (largest tension / breaking load, a fraction; null
/// without a breaking load) and safety_factor (breaking load / largest tension; null without a
/// breaking load, or when no bar of the piece is in tension).
nlohmann::json pieceStrength(const Material& material, double maxTension);
/// The sculpture's, from its pieces' report: min_safety_factor (the least over the pieces that
/// have one; null when none has), min_safety_factor_at (that piece's max_tension_at) and
/// pieces_without_breaking_load (their ids).
nlohmann::json strengthSummary(const nlohmann::json& pieces);
/// The summary table's rows "least safety factor" and "pieces without a breaking load".
std::string strengthSummaryMarkdown(const nlohmann::json& report);
/// "## Strength": every piece's breaking load, largest tension, utilisation, safety factor and
/// the bar of its largest tension.
std::string strengthMarkdown(const nlohmann::json& report);

} // namespace netsculpt
