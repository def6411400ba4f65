// The report's sections for the net maker (ReportSections.h): the joins between pieces as
// DESIGN.md "How pieces are joined" makes them, and every bar length of graded pieces.

#include "io/ReportSections.h"

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>

namespace netsculpt {

namespace {

using nlohmann::json;

/// "piece 1 (tube)", or "pieces 1 (a), 4 (b) and 3 (c), taken in that order as one row".
std::string parentsText(const json& report, const json& parents) {
    std::string text = parents.size() == 1 ? "piece " : "pieces ";
    for (std::size_t i = 0; i < parents.size(); ++i) {
        const json& parent = reportPiece(report, parents[i]);
        text += (i == 0                    ? ""
                 : i + 1 == parents.size() ? " and "
                                           : ", ") +
                integerText(parent["id"]) + " (" + parent["name"].get<std::string>() + ")";
    }
    return parents.size() == 1 ? text : text + ", taken in that order as one row";
}

/// "14 knots: 0 to 4 are knots (4, 0) to (4, 4) of piece 1, 5 to 13 ...": which knot of which
/// part each knot of the joined row is, and whether a seam knot is counted once.
std::string joinedRowText(const json& report, const json& top) {
    const int knots = top["joined_knots"].get<int>();
    int columns = 0;
    std::string text = std::to_string(knots) + " knots:";
    for (const json& run : top["joined_row"]) {
        columns += reportPiece(report, run["piece"])["columns"].get<int>();
        const int first = run["first_knot"].get<int>();
        const int last = first + run["last_column"].get<int>() - run["first_column"].get<int>();
        const std::string row = integerText(run["row"]);
        text += (first == 0 ? " " : ", ") + std::to_string(first) + " to " + std::to_string(last) +
                " are knots (" + row + ", " + integerText(run["first_column"]) + ") to (" + row +
                ", " + integerText(run["last_column"]) + ") of piece " + integerText(run["piece"]);
    }
    return knots < columns ? text + "; a seam knot counted once, in the part before it" : text;
}

/// "knot (19, X) of piece 1" for one parent, "knot X of that joined row (40 knots: ...)" for
/// several.
std::string parentKnot(const json& report, const json& top, const std::string& column) {
    const json& parents = top["parents"];
    const bool ring = top["ring"].get<bool>();
    const std::string wrap = ring ? ", round the ring: past the last, counting goes on from 0" : "";
    if (parents.size() != 1)
        return "knot " + column + " of that joined row (" + joinedRowText(report, top) + wrap + ")";
    const json& parent = reportPiece(report, parents[0]);
    // Only an offset ("c + 4") can count past the last column.
    const bool offset = column.find('+') != std::string::npos;
    return "knot (" + std::to_string(parent["rows"].get<int>() - 1) + ", " + column +
           ") of piece " + integerText(parent["id"]) +
           (ring && offset ? " (" + wrap.substr(2) + ")" : "");
}

/// "knot (4, 2) of piece 3": knot `index` of the parents' joined row, counted round a ring.
std::string joinedKnot(const json& top, int index) {
    const int knots = top["joined_knots"].get<int>();
    if (top["ring"].get<bool>())
        index = (index % knots + knots) % knots;
    for (const json& run : top["joined_row"]) {
        const int column = run["first_column"].get<int>() + index - run["first_knot"].get<int>();
        if (column >= run["first_column"].get<int>() && column <= run["last_column"].get<int>())
            return "knot (" + integerText(run["row"]) + ", " + std::to_string(column) +
                   ") of piece " + integerText(run["piece"]);
    }
    throw std::logic_error("report: no knot " + std::to_string(index) + " in the joined row");
}

/// "c + 4" for a child whose column 0 is column 4 of the joined row, else "c".
std::string columnText(int offset) {
    return offset > 0 ? "c + " + std::to_string(offset) : "c";
}

/// "2 x c", "(c + 4) / 2": a column expression with a factor before or a divisor after it.
std::string scaled(const std::string& column, const std::string& before, const std::string& after) {
    const std::string term = column == "c" ? column : "(" + column + ")";
    return before + term + after;
}

bool graded(const json& piece) {
    const json& lengths = piece["bar_lengths"];
    for (const json& l : lengths)
        if (l != lengths.front())
            return true;
    return false;
}

/// "of 0.13 m": the length of the bars a gear-up's new knot hangs by, its own column's or row
/// 0's (the compiler's barLength(0, c, 0, c)).
std::string gearBarText(const json& piece) {
    if (graded(piece) && piece["bar_axis"] == "column")
        return "of its column's length (Bar lengths below)";
    return "of " + g6(piece["bar_lengths"][0].get<double>()) + " m";
}

/// How row 0 of `piece` meets its parents' last row, by its gear (DESIGN.md).
std::string gearText(const json& report, const json& piece) {
    const json& top = piece["top"];
    const std::string id = integerText(piece["id"]), column = columnText(top["offset"].get<int>());
    const double gear = top["gear_value"].get<double>();
    if (gear == 1)
        return "its row 0 is the last row above it: knot (0, c) of piece " + id + " is " +
               parentKnot(report, top, column) + ".";
    if (gear > 1) {
        const int g = int(gear + 0.5);
        std::string text = "knot (0, c) of piece " + id + " with " + column + " a multiple of " +
                           std::to_string(g) + " is " +
                           parentKnot(report, top, scaled(column, "", " / " + std::to_string(g))) +
                           "; " +
                           (g == 2 ? "the knot between two of them is new, tied"
                                   : "the two knots between two of them are new, each tied") +
                           " by one bar " + gearBarText(piece) + " to each of the two.";
        if (g == 3)
            text += " Both new knots hang from the same two knots, so they take one place.";
        return text;
    }
    const int g = int(1 / gear + 0.5);
    return "knot (0, c) of piece " + id + " is " +
           parentKnot(report, top, scaled(column, std::to_string(g) + " x ", "")) +
           "; the other knots of that row keep only their bars up.";
}

std::string addedRowsText(const json& piece) {
    const int rows = piece["rows"].get<int>();
    const std::string tied = integerText(piece["knots_tied"]) + " knots tied";
    if (rows == 1)
        return " It adds no row below (" + tied + ").";
    return " It adds rows 1 to " + std::to_string(rows - 1) + " below (" + tied + ").";
}

/// One table of a column-graded piece: each column's bars and the bars to the next column.
std::string columnLengths(const json& piece) {
    const json& lengths = piece["bar_lengths"];
    const std::size_t n = lengths.size();
    const bool closed = piece["closed"].get<bool>();
    std::string md = "| column | bars within the column (m) | bars to the next column (m) |\n"
                     "|---|---|---|\n";
    for (std::size_t c = 0; c < n; ++c) {
        const bool hasNext = c + 1 < n || closed;
        const double next =
            hasNext ? 0.5 * (lengths[c].get<double>() + lengths[(c + 1) % n].get<double>()) : 0.0;
        md += "| " + std::to_string(c) + " | " + g6(lengths[c].get<double>()) + " | " +
              (hasNext ? g6(next) + (c + 1 == n ? " (to column 0)" : "") : "-") + " |\n";
    }
    if (gearsUp(piece))
        md += "\nRow 0's new knots (gear " + piece["top"]["gear"].get<std::string>() +
              ") hang from the knots above by bars of their own column's length (bars within "
              "the column).\n";
    return md;
}

std::string rowLengths(const json& piece) {
    const json& lengths = piece["bar_lengths_between_rows"];
    std::string md = "| rows | bars between them (m) |\n|---|---|\n";
    if (gearsUp(piece))
        md += "| 0 (the gear's new knots to the knots above) | " +
              g6(piece["bar_lengths"][0].get<double>()) + " |\n";
    for (std::size_t r = 0; r < lengths.size(); ++r)
        md += "| " + std::to_string(r) + " to " + std::to_string(r + 1) + " | " +
              g6(lengths[r].get<double>()) + " |\n";
    return md;
}

} // namespace

std::string joinsMarkdown(const json& report) {
    std::string md;
    for (const json& piece : report["pieces"]) {
        const json& top = piece["top"];
        if (top["kind"] != "piece")
            continue;
        md += "- Piece " + integerText(piece["id"]) + " (" + piece["name"].get<std::string>() +
              ") hangs from " + parentsText(report, top["parents"]) + ", gear " +
              top["gear"].get<std::string>() + ": " + gearText(report, piece) +
              addedRowsText(piece) + "\n";
    }
    if (md.empty())
        return md;
    return "\n## Joins\n\nKnots are (row, column) of their piece; c counts the child's columns "
           "from 0.\n\n" +
           md;
}

std::string barLengthsMarkdown(const json& report) {
    std::string md;
    for (const json& piece : report["pieces"]) {
        if (!graded(piece))
            continue;
        const bool byRow = piece["bar_axis"] == "row";
        md += "\n### Piece " + integerText(piece["id"]) + " (" + piece["name"].get<std::string>() +
              "), graded by " + (byRow ? "row" : "column") + "\n\n" +
              (byRow ? rowLengths(piece) : columnLengths(piece));
    }
    if (md.empty())
        return md;
    return "\n## Bar lengths\n\nEvery length the bars of a graded piece are knotted to, from "
           "knot centre to knot centre: a bar takes the mean of the lengths of the two columns "
           "(or rows) it joins.\n" +
           md;
}

std::string childStartText(const json& top) {
    const int column = top["offset"].get<int>();
    const double gear = top["gear_value"].get<double>();
    if (gear < 1)
        return joinedKnot(top, column * int(1 / gear + 0.5));
    const int g = int(gear + 0.5), after = column % g;
    const std::string knot = joinedKnot(top, column / g);
    if (after == 0)
        return knot;
    return std::string(g == 2       ? "the new knot"
                       : after == 1 ? "the first new knot"
                                    : "the second new knot") +
           " after " + knot;
}

bool gearsUp(const json& piece) {
    const json& top = piece["top"];
    return top["kind"] == "piece" && top["gear_value"].get<double>() > 1;
}

} // namespace netsculpt
