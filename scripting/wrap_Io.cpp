// Files out: doc:export(path, options), doc:report(), doc:write_report(path);
// ns.export_formats(), ns.rail_export_formats(), ns.output_dir(), ns.script_dir().

#include "commands/Journal.h"
#include "io/Export.h"
#include "io/Report.h"
#include "scripting/Context.h"
#include "scripting/Handles.h"
#include "scripting/Sandbox.h"
#include "scripting/Wrap.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <optional>
#include <stdexcept>

namespace netsculpt::lua {

namespace {

/// A vector {"x", "y", "z"} of the report.
bool isVector(const nlohmann::json& value) {
    if (!value.is_object() || value.size() != 3) return false;
    for (const char* axis : {"x", "y", "z"})
        if (!value.contains(axis) || !value[axis].is_number()) return false;
    return true;
}

/// Pushes JSON as Lua values: objects become tables with string keys, arrays sequences
/// (1-based), integers integers, null nil. A vector is both: v.x, v.y, v.z and v[1], v[2], v[3]
/// (as r:point(t) and p:knots() give points).
void pushJson(lua_State* L, const nlohmann::json& value) {
    if (!lua_checkstack(L, 3))
        throw std::runtime_error("the report is nested too deeply");
    switch (value.type()) {
    case nlohmann::json::value_t::object:
        lua_createtable(L, isVector(value) ? 3 : 0, int(value.size()));
        for (const auto& [key, item] : value.items()) {
            pushJson(L, item);
            lua_setfield(L, -2, key.c_str());
        }
        if (isVector(value))
            for (lua_Integer i = 1; const char* axis : {"x", "y", "z"}) {
                lua_pushnumber(L, value[axis].get<double>());
                lua_rawseti(L, -2, i++);
            }
        break;
    case nlohmann::json::value_t::array: {
        lua_createtable(L, int(value.size()), 0);
        lua_Integer i = 0;
        for (const auto& item : value) {
            pushJson(L, item);
            lua_rawseti(L, -2, ++i);
        }
        break;
    }
    case nlohmann::json::value_t::string:
        lua_pushstring(L, value.get_ref<const std::string&>().c_str());
        break;
    case nlohmann::json::value_t::boolean:
        lua_pushboolean(L, value.get<bool>());
        break;
    case nlohmann::json::value_t::number_integer:
        lua_pushinteger(L, value.get<std::int64_t>());
        break;
    case nlohmann::json::value_t::number_unsigned:
        lua_pushinteger(L, lua_Integer(value.get<std::uint64_t>()));
        break;
    case nlohmann::json::value_t::number_float:
        lua_pushnumber(L, value.get<double>());
        break;
    default:
        lua_pushnil(L);
        break;
    }
}

const std::vector<std::string> kColourBy = {"piece", "tension"};
const std::vector<std::string> kViews = {"top", "side", "front", "perspective", "all"};

const char* const kExportKeys[] = {"colour_by", "tube_radius", "width", "height", "view"};

/// The export options each format uses; others given are refused, not ignored.
std::vector<std::string> optionsOf(const std::string& ext) {
    if (ext == "obj" || ext == "ply") return {"tube_radius"};
    if (ext == "glb") return {"tube_radius", "colour_by"};
    if (ext == "svg" || ext == "png") return {"colour_by", "width", "height", "view"};
    return {};
}

/// `what` is ".obj export" or "rails export".
void checkOptionsFor(const Call& call, const TableArgs& args, const std::vector<std::string>& used,
                     const std::string& what) {
    for (const char* key : kExportKeys) {
        if (!args.has(key) || std::find(used.begin(), used.end(), key) != used.end())
            continue;
        std::string takes;
        for (const std::string& option : used)
            takes += (takes.empty() ? "" : ", ") + option;
        call.fail("argument '" + std::string(key) + "' does not apply to a " + what + " (" +
                  (takes.empty() ? "it takes no options" : "it takes " + takes) + ")");
    }
}

ExportOptions exportArgs(const Call& call, const TableArgs& args, const std::string& ext) {
    ExportOptions o;
    checkOptionsFor(call, args, optionsOf(ext), "." + ext + " export");
    o.colourBy = args.choice("colour_by", kColourBy, o.colourBy);
    if (args.has("tube_radius")) {
        o.tubeRadius = args.finite("tube_radius", std::nullopt);
        if (o.tubeRadius < 0) {
            const int at = args.push("tube_radius");
            call.bad("tube_radius", at, "a number of metres >= 0 (0 = bars as lines)");
        }
    }
    o.width = int(args.whole("width", o.width, 16, 16384));
    o.height = int(args.whole("height", o.height, 16, 16384));
    o.view = args.choice("view", kViews, o.view);
    return o;
}

void checkFormat(const Call& call, const std::string& given, const std::string& ext, bool rails) {
    const std::vector<std::string> formats = rails ? railExportFormats() : exportFormats();
    if (std::find(formats.begin(), formats.end(), ext) != formats.end())
        return;
    std::string allowed;
    for (const std::string& f : formats)
        allowed += (allowed.empty() ? "." : ", .") + f;
    call.fail(std::string("argument 'path' ") + (rails ? "of a rails export " : "") +
              "must end in one of " + allowed + " (the format), got \"" + given + "\"");
}

/// doc:export(path, {colour_by, tube_radius, width, height, view}): format by extension
/// (ns.export_formats()); doc:export(path, {rails = true}): the rails alone, .csv, .obj or .dxf
/// (ns.rail_export_formats()). Returns the path written.
int w_export(Call& call) {
    const Document& doc = checkDocument(call);
    const auto [given, ext] = checkFileArgument(call, 2);
    std::optional<TableArgs> args; // the options table (argument 3), if given
    if (!lua_isnoneornil(call.L, 3))
        args.emplace(call, 3,
                     std::initializer_list<const char*>{"colour_by", "tube_radius", "width",
                                                        "height", "view", "rails"});
    const bool rails = args && args->boolean("rails", false);
    checkFormat(call, given, ext, rails);
    ExportOptions options;
    if (args && rails)
        checkOptionsFor(call, *args, {}, "rails export");
    else if (args)
        options = exportArgs(call, *args, ext);
    const auto path = resolveWritePath(context(call.L), given, call.name);
    if (rails)
        exportRailsFile(doc.sculpture(), path);
    else
        exportFile(doc, path, options);
    lua_pushstring(call.L, path.c_str());
    return 1;
}

/// doc:report() -> the fabrication and load report (DESIGN.md "Lua API") as a table.
int w_report(Call& call) {
    pushJson(call.L, buildReport(checkDocument(call)));
    return 1;
}

/// doc:write_report(path [, {table = "pieces" | "attachments"}]): the report as .json, .md
/// (Markdown) or .csv (the pieces table, or the rails' attachment points), by extension, into the
/// output folder. Returns the path written.
int w_write_report(Call& call) {
    const Document& doc = checkDocument(call);
    const auto [given, ext] = checkFileArgument(call, 2);
    if (ext != "json" && ext != "md" && ext != "csv")
        call.fail("argument 'path' must end in .json, .md or .csv, got \"" + given + "\"");
    std::string table = "pieces";
    if (!lua_isnoneornil(call.L, 3)) {
        const TableArgs args(call, 3, {"table"});
        table = args.choice("table", {"pieces", "attachments"}, "pieces");
        if (ext != "csv")
            call.fail("argument 'table' is for a .csv report, got \"" + given + "\"");
    }
    const auto path = resolveWritePath(context(call.L), given, call.name);
    const nlohmann::json report = buildReport(doc);
    const std::string text = ext == "json"          ? report.dump(2) + "\n"
                             : ext == "md"          ? reportMarkdown(report)
                             : table == "pieces"    ? reportPiecesCsv(report)
                                                    : reportAttachmentsCsv(report);
    writeFileDurably(path, text);
    lua_pushstring(call.L, path.c_str());
    return 1;
}

void pushStrings(lua_State* L, const std::vector<std::string>& strings) {
    lua_createtable(L, int(strings.size()), 0);
    for (std::size_t i = 0; i < strings.size(); ++i) {
        lua_pushstring(L, strings[i].c_str());
        lua_rawseti(L, -2, lua_Integer(i + 1));
    }
}

int w_export_formats(Call& call) {
    pushStrings(call.L, exportFormats());
    return 1;
}

/// ns.rail_export_formats() -> {"csv", "obj", "dxf"}: what doc:export(path, {rails = true}) writes.
int w_rail_export_formats(Call& call) {
    pushStrings(call.L, railExportFormats());
    return 1;
}

/// ns.output_dir() -> the absolute output folder (where relative save/export paths go).
int w_output_dir(Call& call) {
    lua_pushstring(call.L, context(call.L).outputDir.c_str());
    return 1;
}

/// ns.script_dir() -> the absolute folder of the running script (where relative reads resolve).
int w_script_dir(Call& call) {
    lua_pushstring(call.L, context(call.L).scriptDir.c_str());
    return 1;
}

} // namespace

void addIoMethods(lua_State* L) {
    setMethods(L, {{"export", entry<w_export>, 2},
                     {"report", entry<w_report>, 0},
                     {"write_report", entry<w_write_report>, 2}});
}

void addModuleIoFunctions(lua_State* L) {
    setFunctions(L, {{"export_formats", entry<w_export_formats>, 0},
                     {"rail_export_formats", entry<w_rail_export_formats>, 0},
                     {"output_dir", entry<w_output_dir>, 0},
                     {"script_dir", entry<w_script_dir>, 0}});
}

} // namespace netsculpt::lua
