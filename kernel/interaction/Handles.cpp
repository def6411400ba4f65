#include "interaction/Handles.h"

#include "model/Edits.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace netsculpt {

namespace {

Vec3 knotPosition(const CompiledSculpture& compiled, PieceId id, int row, int column) {
    return compiled.system.worldPosition(compiled.pieces.at(id).at(row, column));
}

bool hasChildren(const Sculpture& s, PieceId id) { return !s.childrenOf(id).empty(); }

Handle pieceHandle(HandleKind kind, const Piece& p, int row, int column, const CompiledSculpture& compiled,
                   const HandleSettings& settings) {
    Handle h;
    h.kind = kind;
    h.piece = p.id;
    h.row = row;
    h.column = column;
    h.position = knotPosition(compiled, p.id, row, column);
    h.pixelRadius = settings.pixelRadius;
    return h;
}

/// Rail positions of `count` spheres: [0, 1) on a closed rail, [0, end] on an open one.
std::vector<double> railStops(bool closed, int count, double end = 1) {
    std::vector<double> stops;
    if (!closed && end <= 0) return {0.0}; // exactly one place fits
    count = std::max(count, 2);
    for (int i = 0; i < count; ++i) stops.push_back(closed ? double(i) / count : end * i / (count - 1));
    return stops;
}

/// Signed area of the xy projection of a closed polygon (> 0 = counter-clockwise seen from above).
double signedArea(const std::vector<Vec3>& ring) {
    double area = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const Vec3& a = ring[i];
        const Vec3& b = ring[(i + 1) % ring.size()];
        area += a.x * b.y - b.x * a.y;
    }
    return 0.5 * area;
}

void addRailPoints(std::vector<Handle>& out, const Sculpture& s, const HandleSettings& settings) {
    for (const auto& [id, rail] : s.rails)
        for (double t : railStops(rail.curve().closed(), settings.railPointsPerRail)) {
            Handle h;
            h.kind = HandleKind::RailPoint;
            h.rail = id;
            h.t = t;
            h.position = rail.curve().pointAt(t);
            h.pixelRadius = settings.pixelRadius;
            out.push_back(h);
        }
}

} // namespace

std::string_view modeName(Mode mode) {
    switch (mode) {
    case Mode::View: return "view";
    case Mode::NewNet: return "new net";
    case Mode::Divide: return "divide";
    case Mode::Rows: return "rows";
    case Mode::Columns: return "columns";
    case Mode::BarLength: return "bar length";
    case Mode::Connect: return "connect";
    }
    return "view";
}

std::vector<Handle> handlesForMode(Mode mode, const Sculpture& s, const CompiledSculpture& compiled,
                                   const HandleSettings& settings) {
    std::vector<Handle> out;
    if (mode == Mode::NewNet) addRailPoints(out, s, settings);
    for (const auto& [id, p] : s.pieces) {
        if (!compiled.pieces.count(id)) continue; // not compiled yet (never in a consistent document)
        const int last = p.rows - 1, middleColumn = p.columns / 2;
        switch (mode) {
        case Mode::View: break;
        case Mode::NewNet:
            if (!p.bottom && !hasChildren(s, id))
                out.push_back(pieceHandle(HandleKind::LastRow, p, last, middleColumn, compiled, settings));
            break;
        case Mode::Divide: {
            if (!splitRefusal(s, id).empty())
                break; // the studio offers no split the model refuses
            const int lastSplit = p.closed ? p.columns - 1 : p.columns - 2;
            for (int c = 1; c <= lastSplit; ++c) out.push_back(pieceHandle(HandleKind::TopKnot, p, 0, c, compiled, settings));
            break;
        }
        case Mode::Rows: out.push_back(pieceHandle(HandleKind::RowsEnd, p, last, middleColumn, compiled, settings)); break;
        case Mode::Columns:
            // A split part below a piece has its columns fixed by the join it shares.
            if (p.onRail() || p.parentTop().whole)
                out.push_back(pieceHandle(HandleKind::ColumnsEdge, p, 0, middleColumn, compiled, settings));
            break;
        case Mode::BarLength: {
            if (p.bar.gradedByRow()) {
                // Graded by row (never seamed): its top and its last row, each set on its own.
                // The top's sphere sits on row 1, where the top bars end (row 0 may be another
                // piece's last row, with a sphere of its own).
                for (int row : {0, last}) {
                    const int at = row == 0 && last >= 2 ? 1 : row;
                    Handle h = pieceHandle(HandleKind::BarEnd, p, at, 0, compiled, settings);
                    h.barRow = row;
                    out.push_back(h);
                }
                break;
            }
            const PieceId left = s.leftPartner(id), right = s.rightPartner(id);
            if (!left) {
                Handle h = pieceHandle(HandleKind::BarEnd, p, p.rows / 2, 0, compiled, settings);
                if (right) h.barColumn = 0;
                out.push_back(h);
            }
            if (right) { // the seam with the right partner: both pieces' bars there change together
                const int rows = std::min(p.rows, s.piece(right).rows);
                Handle h = pieceHandle(HandleKind::BarEnd, p, rows / 2, p.columns - 1, compiled, settings);
                h.barColumn = p.columns - 1;
                out.push_back(h);
            } else if (left) { // the free end of a chain of split parts
                Handle h = pieceHandle(HandleKind::BarEnd, p, p.rows / 2, p.columns - 1, compiled, settings);
                h.barColumn = p.columns - 1;
                out.push_back(h);
            }
            break;
        }
        case Mode::Connect:
            if (!p.bottom && !hasChildren(s, id))
                out.push_back(pieceHandle(HandleKind::ConnectSource, p, last, 0, compiled, settings));
            break;
        }
    }
    return out;
}

std::vector<Handle> connectTargets(const Sculpture& s, const CompiledSculpture& compiled, PieceId dragged,
                                   const HandleSettings& settings) {
    std::vector<Handle> out;
    if (!s.hasPiece(dragged) || !compiled.pieces.count(dragged)) return out;
    const Piece& p = s.piece(dragged);
    const int last = p.rows - 1;
    std::vector<Vec3> lastRow;
    for (int c = 0; c < p.columns; ++c) lastRow.push_back(knotPosition(compiled, dragged, last, c));
    const Vec3 rowDirection = lastRow.back() - lastRow.front();
    for (const auto& [id, rail] : s.rails) {
        const Curve& curve = rail.curve();
        if (p.closed && !curve.closed()) continue; // a tube connects to a closed rail only
        double span = 0; // of an open rail, as a fraction of its length: the row's
        if (!curve.closed()) { // the whole last row must fit on an open rail
            span = (p.columns - 1) * topSpacing(s, dragged) / curve.length();
            if (span > 1) continue;
        }
        bool reverse = false;
        if (p.closed) {
            // Least twist for a tube: run the rail the way the last row winds around its axis.
            std::vector<Vec3> ring;
            for (double t : railStops(true, 64)) ring.push_back(curve.pointAt(t));
            reverse = (signedArea(ring) > 0) != (signedArea(lastRow) > 0);
        }
        for (double start : railStops(curve.closed(), settings.railPointsPerRail, 1 - span)) {
            double t = start; // where knot 0 goes: the sphere
            if (!curve.closed()) {
                // The row covers [start, start + span] either way round: reversed, knot 0 is
                // tied at the far end and the row runs back towards the rail's first point.
                const double end = std::min(start + span, 1.0);
                reverse = rowDirection.dot(curve.pointAt(end) - curve.pointAt(start)) < 0;
                if (reverse) t = end;
            } else if (!p.closed) { // a sheet on a ring: its row runs along the rail's direction
                reverse = rowDirection.dot(curve.tangentAt(t)) < 0;
            }
            Handle h;
            h.kind = HandleKind::ConnectTarget;
            h.rail = id;
            h.piece = dragged;
            h.t = t;
            h.position = curve.pointAt(t);
            h.pixelRadius = settings.pixelRadius;
            h.reverse = reverse;
            out.push_back(h);
        }
    }
    return out;
}

int pickHandle(const std::vector<Handle>& handles, const Camera& camera, double x, double y, double radiusPixels) {
    int best = -1;
    double bestPixels = std::numeric_limits<double>::infinity(), bestDepth = bestPixels;
    for (std::size_t i = 0; i < handles.size(); ++i) {
        const ScreenPoint sp = camera.project(handles[i].position);
        if (!sp.visible) continue;
        const double pixels = std::hypot(sp.x - x, sp.y - y);
        if (pixels > std::max(radiusPixels, handles[i].pixelRadius)) continue;
        const bool nearer = pixels < bestPixels - 0.5 || (pixels < bestPixels + 0.5 && sp.depth < bestDepth);
        if (nearer) {
            best = int(i);
            bestPixels = pixels;
            bestDepth = sp.depth;
        }
    }
    return best;
}

std::pair<Vec3, Vec3> sceneBounds(const Sculpture& s, const CompiledSculpture& compiled) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
    auto add = [&](const Vec3& p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    };
    for (const auto& [id, rail] : s.rails)
        for (double t : railStops(rail.curve().closed(), 64)) add(rail.curve().pointAt(t));
    const MassSpringSystem& sys = compiled.system;
    for (std::size_t j = 0; j < sys.knotCount(); ++j) add(sys.worldPosition(j));
    if (!(lo.x <= hi.x)) return {Vec3{-2, -2, 0}, Vec3{2, 2, 3}}; // room for a first rail
    return {lo, hi};
}

} // namespace netsculpt
