#pragma once
// The fabrication and load report: the numbers a net maker and an engineer need (DESIGN.md
// "Lua API": report()). Computed from the document's current shape.
//
// Keys (lengths m, masses kg, forces N, vectors {x, y, z}; `units` says so in the file):
//   relaxed (a relaxation converged since the last change), residual (max |F_j| / (m_j |g|) over
//   free knots now), relax {converged, residual, steps, seconds, backend, stop_reason} of the last
//   relaxation run on the document since it was opened (null when none was: a shape read from a
//   snapshot keeps only whether it was relaxed), knots, bars (distinct, whole sculpture),
//   total_mass, total_weight, rope_length, max_tension, max_tension_at {bar, piece, a {row,
//   column}, b {row, column}} (null without bars), slack_bars (bars shorter than their rest length
//   by more than 1e-9 relative: in compression), max_strain (the largest (l - l_eq) / l_eq, a
//   fraction (0.01 = 1 %; the Markdown prints per cent), 0
//   when no bar is stretched), max_strain_at (as max_tension_at; null when no bar is stretched),
//   overstretched_bars (bars stretched by more than overstretch_limit = kOverstretchStrain; in a
//   relaxed shape, a design the rope cannot hang as computed, which the Markdown says; an Eq. 2
//   start stretches open edges' bars by up to tens of per cent), force_balance {reaction_sum, expected (= -total
//   mass x gravity), difference, relative_difference (|difference| / total_weight), tolerance,
//   within_tolerance, relaxed, note}. Without a converged relaxation the balance is not expected to
//   hold. min_safety_factor (the least safety_factor over the pieces that have a breaking load;
//   null when none has one, or none of theirs has a bar in tension), min_safety_factor_at (that
//   piece's max_tension_at: the bar, with its piece), pieces_without_breaking_load [ids] (pieces
//   whose strength is not checked: no strength is assumed for them).
//   pieces[]: id, name, rows, columns, closed, knots (rows x columns: its own grid, shared
//   knots counted in every piece holding them), knots_tied (the knots it owns: a shared knot is
//   tied once, in the first piece that holds it; they sum to `knots`), bars (the bars the piece
//   owns), rope_length (sum of their rest lengths), mass (its bars' rope + the knot mass of the knots it owns: a
//   shared knot's knot mass counts once, in the first piece that holds it; the pieces' masses
//   sum to total_mass), bar_axis ("column" or "row"), bar_lengths[] (per column or per row),
//   bar_lengths_between_rows[] (a piece whose length varies by row: the length of every bar
//   between rows r and r + 1, as it is knotted; empty otherwise; below a gear-up the new knots
//   of row 0 hang by bars of bar_lengths[c] of their column, or bar_lengths[0] by row),
//   max_tension (the largest tension of its bars, 0 when none is stretched), max_tension_at
//   (that bar, as max_tension_at above; null when none is stretched), breaking_load (N, the
//   material's: a bar's as knotted; null when it has none), utilisation (max_tension /
//   breaking_load, a fraction; null without a breaking load), safety_factor (breaking_load /
//   max_tension; null without a breaking load or without a bar in tension),
//   material {stiffness, compression_ratio, knot_mass, linear_density, breaking_load (null when
//   none)}, colour [r, g, b],
//   top {kind "rail": rail, rail_name, at, step, offset, reverse, start, start_along | kind
//   "piece": parents[], gear, gear_value, offset, ring, joined_knots, joined_row[]} (offset: the
//   column of the rail's or the geared row where the piece's column 0 is; start: the rail
//   position of column 0, in [0, 1) on a closed rail; start_along: the distance along the rail
//   from its start to there, m; ring: the parents' last rows close round; joined_knots: how many
//   knots the parents' last rows hold, numbered as one row from the first part's column 0;
//   joined_row: each part's run of them, {piece, row, first_column, last_column, first_knot},
//   a seam knot in the run before it when both parts end on the same row, else two knots),
//   bottom (null or {rail, rail_name, at, step, offset, reverse, start, start_along}),
//   seams[] {side "left"/"right", piece, column (this piece's column on the seam), other_column
//   (the other piece's, the same knots), rows (they share rows 0 to rows - 1: the shorter
//   piece's), shared_bars (the bars along the seam column, made once), shared_bars_counted_in
//   (the piece whose bars they are)}.
//   rails[]: id, name, closed, length, sampling ("arc length" or "parameter": what t means),
//   start (its first point: t = 0, along = 0), direction (the unit vector it runs along from
//   there: the way t and along grow),
//   attachments (fixed knots held by it), reaction (sum of the reaction forces of its points),
//   max_reaction (the largest magnitude of one knot's reaction), max_point_load (the largest
//   magnitude of the summed reactions of the knots tied at one point of the rail: pieces tied at
//   the same places load each with their knots' sum), max_point_load_knots (how many knots are
//   tied there), shared_points (the points where knots of more than one piece are tied),
//   points[] {piece, row, column, t, along (the distance along the rail from its start, m: what
//   a tape measures; t x length only under arc-length sampling), position, reaction,
//   magnitude}.

#include "commands/Document.h"

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace netsculpt {

/// A bar stretched by more than this share of its rest length is flagged by the report. The
/// model's rope is linear elastic at any stretch; real net rope stretches a few per cent under a
/// working load and yields or breaks well before 20 %, so a net pulled that far is one tied
/// between rails farther apart than it reaches, and its tensions and rail loads are those of a
/// rope that does not exist.
inline constexpr double kOverstretchStrain = 0.02;

/// The bars of `system` stretched by more than kOverstretchStrain at its positions.
std::size_t countOverstretchedBars(const MassSpringSystem& system);
/// The warning the CLI prints for `count` such bars in a relaxed shape (one line, no newline).
std::string overstretchWarning(std::size_t count);
/// A shape this near its equilibrium (residual in knot weights) has its final strains, whether
/// or not a relaxation converged to its tolerance (a "precision limit" stop, a looser run): the
/// report checks the design on it.
inline constexpr double kSettledResidual = 1e-3;

/// How the shape being reported came about (what a Document knows).
struct RelaxStatus {
    bool relaxed = false;    ///< a relaxation converged since the last change
    RelaxResult last;        ///< the last relaxation (converged = false before any)
    double tolerance = 1e-6; ///< the relaxation tolerance the force balance is checked against
    /// The wind the shape was relaxed under (Document::shapeWind): its load is in the residual,
    /// the reactions and the force balance. Empty = gravity alone.
    std::optional<Wind> wind;
};

/// The full report as JSON (keys above).
nlohmann::json buildReport(const Document& doc);
/// The same for a sculpture and its compiled system at its current positions.
nlohmann::json buildReport(const Sculpture& sculpture, const CompiledSculpture& compiled,
                           const RelaxStatus& status = {});
/// What `doc` knows about its shape; tolerance = the one its shape was relaxed to
/// (Document::shapeTolerance, kept in snapshots; RelaxOptions' default when unknown).
RelaxStatus relaxStatus(const Document& doc);

/// The Markdown summary that `netsculpt report` prints.
std::string reportMarkdown(const nlohmann::json& report);
/// Per-piece table as CSV (id, name, rows, columns, closed, knots, bars, rope_length, mass,
/// bar_axis, bar_min, bar_max (of every bar's length, a gear's bars in row 0 too), bar_first,
/// bar_last: the knotted lengths at the first and the last column, or between the first and the
/// last two rows; max_tension; top and last_row: where the
/// piece hangs from and where its last row is tied, "free" when nowhere, as the Markdown says;
/// knots_tied; breaking_load, utilisation, safety_factor, max_tension_at ("row 0 column 3 to
/// row 1 column 3"): empty where the JSON has null; seams: which column of the piece is which
/// of another, in the Markdown's words, empty without a seam; load_case: the load case of every
/// tension, "weight alone" or "weight and a wind of P N/m towards (x, y, z)", as the Markdown's
/// summary).
std::string reportPiecesCsv(const nlohmann::json& report);
/// Per-attachment-point table as CSV (rail, piece, row, column, t, x, y, z: where the point is in
/// the sculpture's coordinates, m; fx, fy, fz: the reaction, N, the force the rail exerts on the
/// net; magnitude, N; along, m; load_case, as in reportPiecesCsv).
std::string reportAttachmentsCsv(const nlohmann::json& report);

} // namespace netsculpt
