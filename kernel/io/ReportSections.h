#pragma once
// The report's Markdown sections for the net maker (ReportFabrication.cpp), from the report's
// JSON (Report.h): how each piece hanging from another is knotted into it, and every bar length
// of a piece whose bar length varies.

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace netsculpt {

/// "## Joins": for each piece hanging from others, which of its row-0 knots are which knots of
/// their last rows, and the rows it adds. Empty when no piece hangs from another.
std::string joinsMarkdown(const nlohmann::json& report);
/// "## Bar lengths": every length a graded piece's bars are knotted to, column by column or row
/// by row. Empty when every piece has one bar length.
std::string barLengthsMarkdown(const nlohmann::json& report);
/// A number as the Markdown prints it: 6 significant digits, no "-0".
std::string g6(double value);

} // namespace netsculpt
