#pragma once
// The spheres of the studio's modes (the paper's interaction): where each mode puts its handles,
// what a handle stands for, and picking a handle under the cursor in screen pixels.

#include "interaction/Camera.h"
#include "model/Compiler.h"
#include "model/Sculpture.h"

#include <optional>
#include <string_view>
#include <vector>

namespace netsculpt {

enum class Mode {
    View,      ///< camera only: no handles
    NewNet,    ///< spheres on rails and on free last rows; a click creates a piece there
    Divide,    ///< spheres on top knots of pieces split allows; a click splits there
    Rows,      ///< a sphere on each last row; drag down = more rows, up = fewer
    Columns,   ///< a sphere on each top edge; drag up = more columns (or a larger gear)
    BarLength, ///< spheres on first columns and seams; drag up = shorter bars, down = longer
    Connect,   ///< a sphere on each free last row; drag it onto a rail sphere to connect
};

/// "view", "new net", "divide", "rows", "columns", "bar length", "connect".
std::string_view modeName(Mode mode);
inline constexpr Mode kAllModes[] = {Mode::View,    Mode::NewNet,    Mode::Divide, Mode::Rows,
                                     Mode::Columns, Mode::BarLength, Mode::Connect};

enum class HandleKind {
    RailPoint,      ///< NewNet: a point of a rail (rail, t)
    LastRow,        ///< NewNet: a last row a new piece can hang from (piece)
    TopKnot,        ///< Divide: top knot (piece, column) where the piece may be split
    RowsEnd,        ///< Rows: a piece's last row (piece)
    ColumnsEdge,    ///< Columns: a piece's top edge (piece)
    BarEnd,         ///< BarLength: a piece's first or last column, or a seam (piece, barColumn);
                    ///< the top or last row of a piece graded by row (piece, barRow)
    ConnectSource,  ///< Connect: a last row that may be dragged to a rail (piece)
    ConnectTarget,  ///< Connect, while dragging: a rail position to drop on (rail, t, reverse)
};

/// A sphere drawn at `position` with a radius of `pixelRadius` pixels whatever the zoom.
struct Handle {
    Vec3 position;          ///< m
    double pixelRadius = 7; ///< px
    HandleKind kind = HandleKind::RailPoint;
    PieceId piece;
    RailId rail;
    int row = 0;
    int column = 0;
    double t = 0;                 ///< rail position (RailPoint, ConnectTarget)
    bool reverse = false;         ///< ConnectTarget: the least-twist direction for the dragged piece
    std::optional<int> barColumn; ///< BarEnd: the column set_bar_length gets (nullopt = whole piece)
    std::optional<int> barRow;    ///< BarEnd: the row set_bar_length gets (a piece graded by row)
};

/// Tunables of the modes (defaults are what the studio uses).
struct HandleSettings {
    double pixelRadius = 7;    ///< sphere size, px
    int railPointsPerRail = 12; ///< NewNet / Connect spheres per rail (equal steps of t)
};

/// The handles of `mode` for the current model and knot positions, in a fixed order (rails by id
/// then t; pieces by id then column).
std::vector<Handle> handlesForMode(Mode mode, const Sculpture& s, const CompiledSculpture& compiled,
                                   const HandleSettings& settings = {});

/// Rail positions piece `dragged` may connect its last row to (the Connect drop targets): every
/// rail a tube may join (closed rails for a closed piece), on open rails only where it fits. A
/// sphere is where the row's knot 0 goes; on an open rail a row that runs against the rail is
/// tied reversed, knot 0 at the far end of the stretch it covers.
std::vector<Handle> connectTargets(const Sculpture& s, const CompiledSculpture& compiled, PieceId dragged,
                                   const HandleSettings& settings = {});

/// The handle whose projection is nearest to pixel (x, y) within `radiusPixels` (and its own
/// pixel radius); among equally near ones the one nearest the eye. -1 when none.
int pickHandle(const std::vector<Handle>& handles, const Camera& camera, double x, double y,
               double radiusPixels);

/// Bounding box of the rails and knots (for frame-all). An empty sculpture gives a 4 x 4 x 3 m box.
std::pair<Vec3, Vec3> sceneBounds(const Sculpture& s, const CompiledSculpture& compiled);

} // namespace netsculpt
