#pragma once
// The paper's operations on a sculpture (DESIGN.md "How pieces are joined"). Each checks its
// own arguments and throws UserError (naming the value and what is allowed) before it changes
// anything. They work on a copy held by the command layer, which then runs
// refreshAndValidate() and compiles; so a failure anywhere leaves the real sculpture untouched.

#include "model/Compiler.h"
#include "model/Sculpture.h"

#include <optional>
#include <string>
#include <utility>

namespace netsculpt {

struct AttachToRailArgs {
    RailId rail;
    int columns = 0;      ///< knots along the rail; 0 = derive from spacing
    double spacing = 0;   ///< m between top knots (closed rails: columns = round(length / spacing))
    int rows = 1;
    double bar = 0.25;    ///< m
    double at = 0; ///< rail position of column 0 (open rail: 0; reversed, column 0 is at 1)
    bool reverse = false; ///< run against the rail's direction
};

struct AttachToPieceArgs {
    PieceId parent;
    Gear gear;
    int rows = 1;
    double bar = 0.25; ///< m
    /// The new piece's rope. The Lua API and the studio give the parent's (a piece knotted into
    /// another is made of its rope unless said otherwise); empty, the default Material, as in
    /// journals written before a child took its parent's rope, which replay as they were.
    std::optional<Material> material = std::nullopt;
};

RailId addRail(Sculpture& s, const std::string& name, const CurveSpec& spec);
void removeRail(Sculpture& s, RailId id);
void renameRail(Sculpture& s, RailId id, const std::string& name);

PieceId attachToRail(Sculpture& s, const AttachToRailArgs& args);
PieceId attachToPiece(Sculpture& s, const AttachToPieceArgs& args);
/// Splits at `column`: the piece keeps its id and columns 0..column; the returned new piece
/// holds columns column..end; they share the knots of `column` (a seam).
std::pair<PieceId, PieceId> split(Sculpture& s, PieceId id, int column);
/// Why split refuses piece `id` at every column, in its own words (naming the piece and what
/// to do first); empty when some column may be split.
[[nodiscard]] std::string splitRefusal(const Sculpture& s, PieceId id);
void setRows(Sculpture& s, PieceId id, int rows);
/// On a rail: the new spacing over the same extent. Below a piece: the nearest allowed gear.
void setColumns(Sculpture& s, PieceId id, int columns);
void setGear(Sculpture& s, PieceId id, Gear gear);
/// Bar length at column 0 or the last column (seam partners follow); a piece with no seams
/// has one bar length everywhere. `column` = nullopt sets the whole piece.
void setBarLength(Sculpture& s, PieceId id, std::optional<int> column, double length);
/// Bar length by row: at the top row (0) or the last row, interpolated between.
void setBarLengthByRow(Sculpture& s, PieceId id, int row, double length);
void connectToRail(Sculpture& s, PieceId id, RailId rail, double at, bool reverse);
void disconnect(Sculpture& s, PieceId id);
void setMaterial(Sculpture& s, PieceId id, const Material& material);
void setColour(Sculpture& s, PieceId id, const Colour& colour);
void renamePiece(Sculpture& s, PieceId id, const std::string& name);
/// Removes the piece and everything hanging below it.
void removePiece(Sculpture& s, PieceId id);
void setGravity(Sculpture& s, const Vec3& gravity);

/// Gear from its text form ("2", "1/3", "x2", "/3"); throws UserError listing allowed gears.
Gear parseGear(const std::string& text);

} // namespace netsculpt

namespace netsculpt {

/// Applies `edit(copy)` to a copy of `s`, then refreshes, validates and compiles the copy; only
/// when all of that succeeds does the copy replace `s`. Returns the edit's result and the
/// compiled system. On UserError `s` is exactly as it was.
template <typename Edit> auto applyAtomically(Sculpture& s, Edit&& edit) {
    Sculpture next = s;
    auto result = edit(next);
    refreshAndValidate(next);
    CompiledSculpture compiled = compileSculpture(next);
    s = std::move(next);
    return std::make_pair(std::move(result), std::move(compiled));
}

} // namespace netsculpt
