// Pieces: doc:attach_to_rail, attach_to_piece, split, set_rows, set_columns, set_gear,
// set_bar_length, connect_to_rail, disconnect, set_material, set_colour, remove_piece.

#include "model/Error.h"
#include "scripting/Handles.h"
#include "scripting/Wrap.h"

#include <cmath>
#include <limits>

namespace netsculpt::lua {

namespace {

constexpr std::int64_t kMaxRows = 100000;
constexpr std::int64_t kMaxColumns = 1000000;

const char* const kGearExpected = "a gear: 3, 2, 1, 0.5, 1/3 or a string \"1/2\", \"x2\", ...";

/// A gear from a number (3, 2, 1, 0.5, 1/3) or a string ("1/2", "x2").
Gear gearArg(const TableArgs& args, const char* key, std::optional<Gear> fallback) {
    const Call& call = args.call();
    const int at = args.push(key);
    Gear gear;
    switch (lua_type(call.L, at)) {
    case LUA_TNIL:
        if (!fallback)
            args.missing(key, kGearExpected);
        gear = *fallback;
        break;
    case LUA_TNUMBER: {
        const double value = lua_tonumber(call.L, at);
        bool found = false;
        for (Gear g : allowedGears())
            if (std::abs(value - g.value()) < 1e-9)
                gear = g, found = true;
        if (!found)
            call.bad(key, at, kGearExpected);
        break;
    }
    case LUA_TSTRING:
        try {
            gear = parseGear(lua_tostring(call.L, at));
        } catch (const UserError&) {
            call.bad(key, at, kGearExpected);
        }
        break;
    default:
        call.bad(key, at, kGearExpected);
    }
    args.pop();
    return gear;
}

/// The piece of a call that takes only a piece: doc:f{piece = p} or doc:f(p).
PieceId onlyPiece(const Call& call) {
    if (lua_type(call.L, 2) == LUA_TUSERDATA)
        return checkPiece(call, 2, "piece");
    const TableArgs args(call, 2, {"piece"});
    return pieceArg(args, "piece");
}

/// A finite number >= 0 (masses), or the fallback.
double nonNegative(const TableArgs& args, const char* key, double fallback) {
    const int at = args.push(key);
    const double value =
        lua_isnil(args.call().L, at) ? fallback : checkFinite(args.call(), at, key);
    if (value < 0)
        args.call().bad(key, at, "a finite number >= 0");
    args.pop();
    return value;
}

/// The breaking_load of set_material: a finite number of newtons > 0, false for none, or the
/// fallback when not given.
std::optional<double> breakingLoadArg(const TableArgs& args, std::optional<double> fallback) {
    const Call& call = args.call();
    const int at = args.push("breaking_load");
    std::optional<double> value = fallback;
    if (lua_type(call.L, at) == LUA_TBOOLEAN && !lua_toboolean(call.L, at)) {
        value = std::nullopt;
    } else if (!lua_isnil(call.L, at)) {
        const double newtons = lua_tonumber(call.L, at);
        if (lua_type(call.L, at) != LUA_TNUMBER || !(newtons > 0) || !std::isfinite(newtons))
            call.bad("breaking_load", at,
                     "a finite number of newtons > 0 (a knotted bar's breaking load), or false "
                     "for none");
        value = newtons;
    }
    args.pop();
    return value;
}

/// The rope's fields of set_material (and of attach_to_piece's material table) read from
/// `args`; a field not given keeps its value in `m`.
Material materialArgs(const TableArgs& args, Material m) {
    m.stiffness = args.positive("stiffness", m.stiffness);
    m.compressionRatio = nonNegative(args, "compression_ratio", m.compressionRatio);
    if (m.compressionRatio > 1)
        args.call().fail("argument 'compression_ratio' must be from 0 to 1, got " +
                         formatNumber(m.compressionRatio));
    m.knotMass = nonNegative(args, "knot_mass", m.knotMass);
    m.linearDensity = nonNegative(args, "linear_density", m.linearDensity);
    m.breakingLoad = breakingLoadArg(args, m.breakingLoad);
    return m;
}

int w_attach_to_rail(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"rail", "columns", "spacing", "rows", "bar", "at", "reverse"});
    AttachToRailArgs a;
    a.rail = railArg(args, "rail");
    if (args.has("columns") && args.has("spacing"))
        call.fail("give columns or spacing, not both");
    if (!args.has("columns") && !args.has("spacing"))
        call.fail("argument 'columns' (or 'spacing') is missing; expected a whole number >= 2");
    if (args.has("columns"))
        a.columns = int(args.whole("columns", std::nullopt, 2, kMaxColumns));
    else
        a.spacing = args.positive("spacing", std::nullopt);
    a.rows = int(args.whole("rows", std::nullopt, 1, kMaxRows));
    a.bar = args.positive("bar", a.bar);
    a.at = args.finite("at", 0.0);
    a.reverse = args.boolean("reverse", false);
    const CommandResult created = doc.execute(AttachToRailCommand{a});
    pushPiece(call.L, 1, created.pieces.at(0));
    return 1;
}

/// attach_to_piece's rope: the parent's, with the fields its `material` table gives (if any).
Material childMaterial(const TableArgs& args, const Material& parent) {
    const int at = args.push("material");
    if (lua_isnil(args.call().L, at)) {
        args.pop();
        return parent;
    }
    if (lua_type(args.call().L, at) != LUA_TTABLE)
        args.call().bad("material", at,
                        "a table of the rope's fields (stiffness, compression_ratio, knot_mass, "
                        "linear_density, breaking_load); those not given are the parent's");
    // Its errors read "attach_to_piece: material: argument 'stiffness' must be ...".
    const Call inMaterial{args.call().L, "attach_to_piece: material"};
    const Material m = materialArgs(TableArgs(inMaterial, at,
                                              {"stiffness", "compression_ratio", "knot_mass",
                                               "linear_density", "breaking_load"}),
                                    parent);
    args.pop();
    return m;
}

int w_attach_to_piece(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"piece", "gear", "rows", "bar", "material"});
    AttachToPieceArgs a;
    a.parent = pieceArg(args, "piece");
    a.gear = gearArg(args, "gear", Gear{1, 1});
    a.rows = int(args.whole("rows", std::nullopt, 1, kMaxRows));
    a.bar = args.positive("bar", a.bar);
    if (doc.sculpture().hasPiece(a.parent))
        a.material = childMaterial(args, doc.sculpture().piece(a.parent).material);
    const CommandResult created = doc.execute(AttachToPieceCommand{a});
    pushPiece(call.L, 1, created.pieces.at(0));
    return 1;
}

/// doc:split{piece, column} -> the two parts (the first keeps the piece's id).
int w_split(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"piece", "column"});
    const PieceId piece = pieceArg(args, "piece");
    // Any whole column that is an int reaches the model, whose message gives this piece's range.
    const int column = int(args.whole("column", std::nullopt, std::numeric_limits<int>::min(),
                                      std::numeric_limits<int>::max()));
    const CommandResult created = doc.execute(SplitCommand{piece, column});
    pushPiece(call.L, 1, created.pieces.at(0));
    pushPiece(call.L, 1, created.pieces.at(1));
    return 2;
}

int w_set_rows(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"piece", "rows"});
    const PieceId piece = pieceArg(args, "piece");
    doc.execute(SetRowsCommand{piece, int(args.whole("rows", std::nullopt, 1, kMaxRows))});
    return 0;
}

int w_set_columns(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"piece", "columns"});
    const PieceId piece = pieceArg(args, "piece");
    doc.execute(SetColumnsCommand{piece, int(args.whole("columns", std::nullopt, 1, kMaxColumns))});
    return 0;
}

int w_set_gear(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"piece", "gear"});
    const PieceId piece = pieceArg(args, "piece");
    doc.execute(SetGearCommand{piece, gearArg(args, "gear", std::nullopt)});
    return 0;
}

/// doc:set_bar_length{piece, column = 0 | last, length} or {piece, row = 0 | last, length};
/// neither column nor row: the whole piece.
int w_set_bar_length(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"piece", "column", "row", "length"});
    SetBarLengthCommand command;
    command.piece = pieceArg(args, "piece");
    if (args.has("column") && args.has("row"))
        call.fail("give column or row, not both");
    if (args.has("column"))
        command.column = int(args.whole("column", std::nullopt, 0, kMaxColumns));
    if (args.has("row"))
        command.row = int(args.whole("row", std::nullopt, 0, kMaxRows));
    command.length = args.positive("length", std::nullopt);
    doc.execute(command);
    return 0;
}

int w_connect_to_rail(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"piece", "rail", "at", "reverse"});
    ConnectToRailCommand command;
    command.piece = pieceArg(args, "piece");
    command.rail = railArg(args, "rail");
    command.at = args.finite("at", 0.0);
    command.reverse = args.boolean("reverse", false);
    doc.execute(command);
    return 0;
}

int w_disconnect(Call& call) {
    Document& doc = checkDocument(call);
    doc.execute(DisconnectCommand{onlyPiece(call)});
    return 0;
}

/// doc:set_material{piece, stiffness, compression_ratio, knot_mass, linear_density,
/// breaking_load}: the fields not given keep their current values.
int w_set_material(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2,
                         {"piece", "stiffness", "compression_ratio", "knot_mass", "linear_density",
                          "breaking_load"});
    const PieceId piece = pieceArg(args, "piece");
    const Material m = materialArgs(args, doc.sculpture().piece(piece).material);
    doc.execute(SetMaterialCommand{piece, m});
    return 0;
}

/// doc:set_colour{piece, colour = {r, g, b}} (components from 0 to 1).
int w_set_colour(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(call, 2, {"piece", "colour"});
    const PieceId piece = pieceArg(args, "piece");
    static const char* const kRgb[3] = {"r", "g", "b"};
    const int at = args.push("colour");
    if (lua_isnil(call.L, at))
        args.missing("colour", "a colour {r, g, b}");
    const Vec3 c =
        checkTriple(call, at, "colour", kRgb, "a colour {r, g, b} of numbers from 0 to 1");
    args.pop();
    for (double v : {c.x, c.y, c.z})
        if (!(v >= 0 && v <= 1))
            call.fail("argument 'colour' must be {r, g, b} with components from 0 to 1, got " +
                      formatNumber(v));
    doc.execute(SetColourCommand{piece, Colour{c.x, c.y, c.z}});
    return 0;
}

int w_remove_piece(Call& call) {
    Document& doc = checkDocument(call);
    doc.execute(RemovePieceCommand{onlyPiece(call)});
    return 0;
}

} // namespace

void addPieceMethods(lua_State* L) {
    setMethods(L, {{"attach_to_rail", entry<w_attach_to_rail>, kKeywordTable},
                     {"attach_to_piece", entry<w_attach_to_piece>, kKeywordTable},
                     {"split", entry<w_split>, kKeywordTable},
                     {"set_rows", entry<w_set_rows>, kKeywordTable},
                     {"set_columns", entry<w_set_columns>, kKeywordTable},
                     {"set_gear", entry<w_set_gear>, kKeywordTable},
                     {"set_bar_length", entry<w_set_bar_length>, kKeywordTable},
                     {"connect_to_rail", entry<w_connect_to_rail>, kKeywordTable},
                     {"disconnect", entry<w_disconnect>, 1},
                     {"set_material", entry<w_set_material>, kKeywordTable},
                     {"set_colour", entry<w_set_colour>, kKeywordTable},
                     {"remove_piece", entry<w_remove_piece>, 1}});
}

} // namespace netsculpt::lua
