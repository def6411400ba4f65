// Rails: doc:add_rail, doc:import_rails, doc:remove_rail; ns.circle, the points of a ring rail.

#include "geometry/Circle.h"
#include "io/Import.h"
#include "io/IoText.h"
#include "model/Error.h"
#include "scripting/Context.h"
#include "scripting/Handles.h"
#include "scripting/Sandbox.h"
#include "scripting/Wrap.h"

#include <iostream>

namespace netsculpt::lua {

namespace {

const std::vector<std::string> kSamplings = {"arclength", "parameter"};

CurveSpec curveArgs(const TableArgs& args) {
    const Call& call = args.call();
    const bool polyline = args.has("points"), spline = args.has("control");
    if (polyline == spline)
        call.fail(polyline ? "give points (a polyline) or control (a B-spline), not both"
                           : "argument 'points' (a polyline) or 'control' (a B-spline) is missing");
    CurveSpec spec;
    spec.spline = spline;
    spec.closed = args.boolean("closed", false);
    spec.sampling = args.choice("sampling", kSamplings, "arclength") == "parameter"
                        ? Sampling::Parameter
                        : Sampling::ArcLength;
    if (polyline) {
        for (const char* key : {"degree", "knots", "weights"})
            if (args.has(key))
                call.fail(std::string("argument '") + key +
                          "' belongs to a B-spline (control = {...}); " +
                          "points = {...} make a polyline");
        spec.points = args.points("points");
        return spec;
    }
    spec.points = args.points("control");
    spec.degree = int(args.whole("degree", 3, 1, 7));
    if (args.has("knots"))
        spec.knots = args.numbers("knots");
    if (args.has("weights"))
        spec.weights = args.numbers("weights");
    return spec;
}

/// doc:add_rail{name, points = {{x,y,z}, ...}, closed} or
/// doc:add_rail{name, degree, control = {...}, knots, weights, closed, sampling}.
int w_add_rail(Call& call) {
    Document& doc = checkDocument(call);
    const TableArgs args(
        call, 2, {"name", "points", "control", "degree", "knots", "weights", "closed", "sampling"});
    AddRailCommand command{args.string("name", std::string()), curveArgs(args)};
    const CommandResult created = doc.execute(command);
    pushRail(call.L, 1, created.rails.at(0));
    return 1;
}

/// A rail longer than this read from a file that states no unit (OBJ, CSV) without `units` is
/// most likely drawn in millimetres or centimetres: import_rails warns.
constexpr double kUnlikelyRailLength = 1000; // m

/// Warns on stderr for each such rail, naming it, its length and the option that fixes it.
void warnUnlikelyLengths(const Document& doc, const std::vector<RailId>& rails,
                         const std::string& file) {
    for (RailId id : rails) {
        const Rail& rail = doc.sculpture().rail(id);
        const double length = rail.curve().length();
        if (length > kUnlikelyRailLength)
            std::cerr << "netsculpt: warning: import_rails: rail '" << rail.name << "' of " << file
                      << " is " << formatNumber(length)
                      << " m long, read as metres (the file states no unit); if it is drawn in "
                         "millimetres, import it with {units = \"mm\"}\n";
    }
}

/// doc:import_rails(path [, {units = "mm", layers = {"RAIL", ...}}]) -> {rail, ...}: DXF, OBJ
/// polylines or CSV.
int w_import_rails(Call& call) {
    Document& doc = checkDocument(call);
    const std::string given = checkString(call, 2, "path");
    ImportOptions options;
    if (!lua_isnoneornil(call.L, 3)) {
        const TableArgs args(call, 3, {"units", "layers"});
        options.units = args.choice("units", unitNames(), std::string());
        if (args.has("layers"))
            options.layers = args.strings("layers");
    }
    const auto path = resolveReadPath(context(call.L), given, call.name);
    ImportRailsCommand command{given, importRailsFile(path, options)};
    const CommandResult created = doc.execute(command);
    if (options.units.empty() && io::lowerExtension(path) != "dxf")
        warnUnlikelyLengths(doc, created.rails, given);
    lua_createtable(call.L, int(created.rails.size()), 0);
    for (std::size_t i = 0; i < created.rails.size(); ++i) {
        pushRail(call.L, 1, created.rails[i]);
        lua_rawseti(call.L, -2, lua_Integer(i + 1));
    }
    return 1;
}

/// doc:remove_rail{rail = r} (or doc:remove_rail(r)).
int w_remove_rail(Call& call) {
    Document& doc = checkDocument(call);
    RailId rail;
    if (lua_type(call.L, 2) == LUA_TUSERDATA) {
        rail = checkRail(call, 2, "rail");
    } else {
        const TableArgs args(call, 2, {"rail"});
        rail = railArg(args, "rail");
    }
    doc.execute(RemoveRailCommand{rail});
    return 0;
}

/// ns.circle{radius = r, points = n [, centre = {x, y, z}]} -> {{x,y,z}, ...}: the corners of
/// a regular polygon in the horizontal circle, for doc:add_rail{points = ..., closed = true}.
int w_circle(Call& call) {
    const TableArgs args(call, 1, {"radius", "points", "centre"});
    const double radius = args.positive("radius", std::nullopt);
    const auto vertices = int(args.whole("points", std::nullopt, 3, kMaxCircleVertices));
    const Vec3 centre = args.has("centre") ? args.vec3("centre") : Vec3{};
    const std::vector<Vec3> corners = circlePoints(centre, radius, vertices);
    lua_createtable(call.L, vertices, 0);
    for (int i = 0; i < vertices; ++i) {
        pushVec3(call.L, corners[std::size_t(i)]);
        lua_rawseti(call.L, -2, lua_Integer(i) + 1);
    }
    return 1;
}

} // namespace

void addModuleRailFunctions(lua_State* L) {
    setFunctions(L, {{"circle", entry<w_circle>, kKeywordTable}});
}

void addRailMethods(lua_State* L) {
    setMethods(L, {{"add_rail", entry<w_add_rail>, kKeywordTable},
                     {"import_rails", entry<w_import_rails>, 2},
                     {"remove_rail", entry<w_remove_rail>, 1}});
}

} // namespace netsculpt::lua
