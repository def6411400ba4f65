// What a script can ask about a sculpture: doc:piece_info(p) / p:info(), doc:knots(p) /
// p:knots(), doc:rail_info(r) / r:info(), r:point(t).

#include "scripting/Handles.h"
#include "scripting/Wrap.h"

namespace netsculpt::lua {

namespace {

/// {r, g, b} by name and by index (colour.r is colour[1]), as set_colour takes it.
void pushColour(lua_State* L, const Colour& c) {
    lua_createtable(L, 3, 3);
    const double channels[3] = {c.r, c.g, c.b};
    static const char* const kNames[3] = {"r", "g", "b"};
    for (int i = 0; i < 3; ++i) {
        lua_pushnumber(L, channels[i]);
        lua_rawseti(L, -2, i + 1);
        lua_pushnumber(L, channels[i]);
        lua_setfield(L, -2, kNames[i]);
    }
}

/// The material as set_material takes it; breaking_load nil when the piece has none.
void pushMaterial(lua_State* L, const Material& m) {
    lua_createtable(L, 0, 5);
    setNumber(L, "stiffness", m.stiffness);
    setNumber(L, "compression_ratio", m.compressionRatio);
    setNumber(L, "knot_mass", m.knotMass);
    setNumber(L, "linear_density", m.linearDensity);
    if (m.breakingLoad)
        setNumber(L, "breaking_load", *m.breakingLoad);
}

void pushRailEdge(lua_State* L, int docIndex, const RailEdge& e) {
    lua_createtable(L, 0, 4);
    pushRail(L, docIndex, e.rail);
    lua_setfield(L, -2, "rail");
    setNumber(L, "at", railPosition(e, 0));
    setNumber(L, "step", e.step);
    setBoolean(L, "reverse", e.reverse);
}

void pushTop(lua_State* L, int docIndex, const Piece& p) {
    if (p.onRail()) {
        pushRailEdge(L, docIndex, p.railTop());
        return;
    }
    const ParentEdge& e = p.parentTop();
    lua_createtable(L, 0, 4);
    lua_createtable(L, int(e.parents.size()), 0);
    for (std::size_t i = 0; i < e.parents.size(); ++i) {
        pushPiece(L, docIndex, e.parents[i]);
        lua_rawseti(L, -2, lua_Integer(i + 1));
    }
    lua_setfield(L, -2, "pieces");
    setString(L, "gear", toString(e.gear));
    setNumber(L, "gear_value", e.gear.value());
    setBoolean(L, "whole", e.whole);
}

void pushPieceList(lua_State* L, int docIndex, const std::vector<PieceId>& ids) {
    lua_createtable(L, int(ids.size()), 0);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        pushPiece(L, docIndex, ids[i]);
        lua_rawseti(L, -2, lua_Integer(i + 1));
    }
}

/// Bar length per column (or per row when the piece varies by row), 1-based.
void pushBarLengths(lua_State* L, const Piece& p) {
    const int n = p.bar.axis == BarAxis::Column ? p.columns : p.rows;
    lua_createtable(L, n, 0);
    for (int i = 0; i < n; ++i) {
        lua_pushnumber(L, p.bar.at(i));
        lua_rawseti(L, -2, i + 1);
    }
}

void pushPieceInfo(lua_State* L, int docIndex, const Sculpture& s, PieceId id) {
    const Piece& p = s.piece(id);
    lua_createtable(L, 0, 16);
    setInteger(L, "id", id.value);
    setString(L, "name", p.name);
    setInteger(L, "rows", p.rows);
    setInteger(L, "columns", p.columns);
    setBoolean(L, "closed", p.closed);
    setInteger(L, "knots", std::int64_t(p.rows) * p.columns);
    setString(L, "bar_axis", p.bar.axis == BarAxis::Column ? "column" : "row");
    pushBarLengths(L, p);
    lua_setfield(L, -2, "bar_lengths");
    pushMaterial(L, p.material);
    lua_setfield(L, -2, "material");
    pushColour(L, p.colour);
    lua_setfield(L, -2, "colour");
    pushTop(L, docIndex, p);
    lua_setfield(L, -2, "top");
    if (p.bottom) {
        pushRailEdge(L, docIndex, *p.bottom);
        lua_setfield(L, -2, "bottom");
    }
    if (const PieceId left = s.leftPartner(id))
        pushPiece(L, docIndex, left), lua_setfield(L, -2, "left");
    if (const PieceId right = s.rightPartner(id))
        pushPiece(L, docIndex, right), lua_setfield(L, -2, "right");
    pushPieceList(L, docIndex, s.childrenOf(id));
    lua_setfield(L, -2, "children");
}

void pushRailInfo(lua_State* L, int docIndex, const Sculpture& s, RailId id) {
    const Rail& rail = s.rail(id);
    const CurveSpec& spec = rail.curve().spec();
    lua_createtable(L, 0, 9);
    setInteger(L, "id", id.value);
    setString(L, "name", rail.name);
    setBoolean(L, "closed", rail.curve().closed());
    setNumber(L, "length", rail.curve().length());
    setString(L, "kind", spec.spline ? "bspline" : "polyline");
    setInteger(L, "degree", spec.degree);
    setInteger(L, "points", std::int64_t(spec.points.size()));
    setString(L, "sampling", spec.sampling == Sampling::ArcLength ? "arclength" : "parameter");
    pushPieceList(L, docIndex, s.piecesOnRail(id));
    lua_setfield(L, -2, "pieces");
}

/// Knot positions of a piece: knots[row + 1][column + 1] = {x, y, z} (current, relaxed if relaxed).
void pushKnots(lua_State* L, const Document& doc, PieceId id) {
    const CompiledSculpture& compiled = doc.compiled();
    const PieceKnots& knots = compiled.pieces.at(id);
    lua_createtable(L, knots.rows, 0);
    for (int r = 0; r < knots.rows; ++r) {
        lua_createtable(L, knots.columns, 0);
        for (int c = 0; c < knots.columns; ++c) {
            pushVec3(L, compiled.system.worldPosition(knots.at(r, c)));
            lua_rawseti(L, -2, c + 1);
        }
        lua_rawseti(L, -2, r + 1);
    }
}

/// The piece of doc:f(p) or doc:f{piece = p}.
PieceId pieceArgument(const Call& call) {
    if (lua_type(call.L, 2) == LUA_TUSERDATA)
        return checkPiece(call, 2, "piece");
    const TableArgs args(call, 2, {"piece"});
    return pieceArg(args, "piece");
}

int w_piece_info(Call& call) {
    const Document& doc = checkDocument(call);
    pushPieceInfo(call.L, 1, doc.sculpture(), pieceArgument(call));
    return 1;
}

int w_knots(Call& call) {
    const Document& doc = checkDocument(call);
    pushKnots(call.L, doc, pieceArgument(call));
    return 1;
}

int w_rail_info(Call& call) {
    const Document& doc = checkDocument(call);
    RailId id;
    if (lua_type(call.L, 2) == LUA_TUSERDATA) {
        id = checkRail(call, 2, "rail");
    } else {
        const TableArgs args(call, 2, {"rail"});
        id = railArg(args, "rail");
    }
    pushRailInfo(call.L, 1, doc.sculpture(), id);
    return 1;
}

int h_piece_info(Call& call) {
    PieceId id;
    const int docIndex = handleDocument(call, id);
    pushPieceInfo(call.L, docIndex, checkDocument(call, docIndex).sculpture(), id);
    return 1;
}

int h_piece_knots(Call& call) {
    PieceId id;
    const int docIndex = handleDocument(call, id);
    pushKnots(call.L, checkDocument(call, docIndex), id);
    return 1;
}

int h_rail_info(Call& call) {
    RailId id;
    const int docIndex = handleDocument(call, id);
    pushRailInfo(call.L, docIndex, checkDocument(call, docIndex).sculpture(), id);
    return 1;
}

/// r:point(t) -> {x, y, z}: the rail's point at rail position t.
int h_rail_point(Call& call) {
    RailId id;
    const int docIndex = handleDocument(call, id);
    const double t = checkFinite(call, 2, "t");
    if (!(t >= 0 && t <= 1))
        call.bad("t", 2, "a rail position from 0 to 1 (the fraction of the rail's length)");
    pushVec3(call.L, checkDocument(call, docIndex).sculpture().rail(id).curve().pointAt(t));
    return 1;
}

} // namespace

void addQueryMethods(lua_State* L) {
    setMethods(L, {{"piece_info", entry<w_piece_info>, 1},
                     {"knots", entry<w_knots>, 1},
                     {"rail_info", entry<w_rail_info>, 1}});
}

void addPieceHandleMethods(lua_State* L) {
    setMethods(L, {{"info", entry<h_piece_info>, 0}, {"knots", entry<h_piece_knots>, 0}});
}

void addRailHandleMethods(lua_State* L) {
    setMethods(L, {{"info", entry<h_rail_info>, 0}, {"point", entry<h_rail_point>, 1}});
}

} // namespace netsculpt::lua
