// exportFile's dispatch by extension, the knots CSV, the JSON document and the rails files.

#include "io/Export.h"

#include "io/DxfExport.h"
#include "io/Exporters.h"
#include "io/IoText.h"
#include "io/Scene.h"
#include "io/Views.h"
#include "model/Error.h"
#include "physics/Forces.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

namespace netsculpt {

namespace {

void validate(const ExportOptions& o) {
    if (o.colourBy != "piece" && o.colourBy != "tension")
        throw UserError("colour_by must be \"piece\" or \"tension\", got \"" + o.colourBy + "\"");
    if (!(std::isfinite(o.tubeRadius) && o.tubeRadius >= 0))
        throw UserError("tube_radius must be a finite number >= 0 (m), got " +
                        formatNumber(o.tubeRadius));
    for (auto [value, name] : {std::pair{o.width, "width"}, std::pair{o.height, "height"}})
        if (value < 16 || value > 16384)
            throw UserError(std::string(name) + " must be from 16 to 16384 pixels, got " +
                            std::to_string(value));
    const auto& views = io::viewNames();
    if (o.view != "all" && std::find(views.begin(), views.end(), o.view) == views.end())
        throw UserError("view must be one of " + io::listed(views) + " or all; got \"" + o.view +
                        "\"");
}

/// A CSV field: quoted when it holds a comma, a quote or blanks at its ends.
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos && io::trim(text) == text)
        return text;
    std::string out = "\"";
    for (char c : text)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

nlohmann::json vec(const Vec3& v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}

} // namespace

namespace io {

std::string knotsCsv(const ExportInput& in) {
    const MassSpringSystem& sys = in.compiled.system;
    std::string out = "piece,row,column,x,y,z,fixed\n";
    for (const auto& [id, knots] : in.compiled.pieces)
        for (int r = 0; r < knots.rows; ++r)
            for (int c = 0; c < knots.columns; ++c) {
                const std::uint32_t k = knots.at(r, c);
                out += std::to_string(id.value) + "," + std::to_string(r) + "," +
                       std::to_string(c) + ",";
                appendVec(out, sys.worldPosition(k), ',');
                out += sys.fixed[k] ? ",1\n" : ",0\n";
            }
    return out;
}

std::string jsonDocument(const ExportInput& in) {
    const Sculpture& s = in.sculpture;
    const MassSpringSystem& sys = in.compiled.system;
    nlohmann::json doc;
    doc["format"] = "netsculpt-export";
    doc["version"] = 1;
    doc["units"] = "m";
    doc["frame"] = "z up";
    doc["gravity"] = vec(s.gravity);
    doc["relaxed"] = in.status.relaxed;
    nlohmann::json rails = nlohmann::json::array();
    for (const auto& [id, rail] : s.rails) {
        nlohmann::json points = nlohmann::json::array();
        for (const Vec3& p : railPolyline(rail.curve(), false))
            points.push_back(vec(p));
        rails.push_back({{"id", id.value},
                         {"name", rail.name},
                         {"closed", rail.curve().closed()},
                         {"kind", rail.curve().spec().spline ? "spline" : "polyline"},
                         {"length", rail.curve().length()},
                         {"points", std::move(points)}});
    }
    doc["rails"] = std::move(rails);
    nlohmann::json pieces = nlohmann::json::array();
    for (const auto& [id, knots] : in.compiled.pieces) {
        const Piece& p = s.piece(id);
        pieces.push_back({{"id", id.value},
                          {"name", p.name},
                          {"rows", knots.rows},
                          {"columns", knots.columns},
                          {"closed", p.closed},
                          {"colour", {p.colour.r, p.colour.g, p.colour.b}},
                          {"knots", knots.index}});
    }
    doc["pieces"] = std::move(pieces);
    nlohmann::json knots = nlohmann::json::array();
    for (std::size_t k = 0; k < sys.knotCount(); ++k) {
        nlohmann::json refs = nlohmann::json::array();
        for (std::uint32_t i = sys.refStart[k]; i < sys.refStart[k + 1]; ++i)
            refs.push_back({sys.refs[i].piece.value, sys.refs[i].row, sys.refs[i].column});
        nlohmann::json knot{{"position", vec(sys.worldPosition(k))},
                            {"mass", sys.mass[k]},
                            {"fixed", sys.fixed[k] != 0},
                            {"refs", std::move(refs)}};
        if (sys.fixed[k])
            knot["hold"] = {{"rail", sys.hold[k].rail.value}, {"t", sys.hold[k].t}};
        if (sys.origin != Vec3{}) // site coordinates: the bits the equilibrium is computed in
            knot["local"] = vec(sys.position[k]);
        knots.push_back(std::move(knot));
    }
    doc["knots"] = std::move(knots);
    if (sys.origin != Vec3{})
        doc["origin"] = vec(sys.origin);
    const std::vector<double> tension = sys.barCount() ? barTensions(sys) : std::vector<double>{};
    nlohmann::json bars = nlohmann::json::array();
    for (std::size_t b = 0; b < sys.barCount(); ++b)
        bars.push_back({{"a", sys.barA[b]},
                        {"b", sys.barB[b]},
                        {"piece", sys.barPiece[b].value},
                        {"rest_length", sys.restLength[b]},
                        {"length", distance(sys.position[sys.barA[b]], sys.position[sys.barB[b]])},
                        {"tension", tension[b]}});
    doc["bars"] = std::move(bars);
    doc["report"] = buildReport(s, in.compiled, in.status);
    return doc.dump(1) + "\n";
}

} // namespace io

std::vector<std::string> exportFormats() {
    return {"csv", "obj", "ply", "glb", "json", "svg", "png", "dxf"};
}

void checkExport(const std::filesystem::path& path, const ExportOptions& options) {
    const std::string ext = io::lowerExtension(path);
    const auto formats = exportFormats();
    if (std::find(formats.begin(), formats.end(), ext) == formats.end())
        throw UserError(io::displayName(path) + ": cannot export to " +
                        (ext.empty() ? "a file without extension" : "." + ext) +
                        "; the formats are " + io::listed(formats));
    validate(options);
}

void exportFile(const Sculpture& sculpture, const CompiledSculpture& compiled,
                const RelaxStatus& status, const std::filesystem::path& path,
                const ExportOptions& options) {
    checkExport(path, options);
    const std::string ext = io::lowerExtension(path);
    const io::ExportInput in{sculpture, compiled, status, options};
    std::string bytes;
    if (ext == "csv")
        bytes = io::knotsCsv(in);
    else if (ext == "obj")
        bytes = io::objText(in);
    else if (ext == "ply")
        bytes = io::plyText(in);
    else if (ext == "glb")
        bytes = io::glbBytes(in);
    else if (ext == "json")
        bytes = io::jsonDocument(in);
    else if (ext == "svg")
        bytes = io::svgText(in);
    else if (ext == "dxf")
        bytes = io::dxfText(sculpture, &compiled.system);
    else
        bytes = io::pngBytes(in);
    io::writeFileAtomically(path, bytes);
}

std::vector<std::string> railExportFormats() {
    return {"csv", "obj", "dxf"};
}

void checkRailsExport(const std::filesystem::path& path) {
    const std::string ext = io::lowerExtension(path);
    const auto formats = railExportFormats();
    if (std::find(formats.begin(), formats.end(), ext) == formats.end())
        throw UserError(io::displayName(path) + ": rails are exported to .csv, .obj or .dxf, not " +
                        (ext.empty() ? "a file without extension" : "." + ext));
}

void exportRailsFile(const Sculpture& sculpture, const std::filesystem::path& path) {
    checkRailsExport(path);
    const std::string ext = io::lowerExtension(path);
    if (ext == "dxf") {
        io::writeFileAtomically(path, io::dxfText(sculpture, nullptr));
        return;
    }
    // Names must tell rails apart when read back (CSV groups rows by name).
    std::set<std::string> used;
    std::string out = ext == "csv" ? "rail,x,y,z\n" : "# netsculpt rails; metres, z up\n";
    std::size_t vertices = 0;
    for (const auto& [id, rail] : sculpture.rails) {
        std::string name = rail.name.empty() ? toString(id) : rail.name;
        if (!used.insert(name).second)
            name += " (" + toString(id) + ")";
        used.insert(name);
        const auto points = io::railPolyline(rail.curve(), false);
        if (ext == "csv") {
            const std::string field = csvField(name) + ",";
            for (std::size_t i = 0; i <= points.size(); ++i) {
                if (i == points.size() && !rail.curve().closed())
                    break;
                out += field;
                io::appendVec(out, points[i % points.size()], ',');
                out += '\n';
            }
            continue;
        }
        out += "o " + name + "\n";
        for (const Vec3& p : points) {
            out += "v ";
            io::appendVec(out, p, ' ');
            out += '\n';
        }
        out += "l";
        for (std::size_t i = 0; i < points.size(); ++i) {
            out += ' ';
            out += std::to_string(vertices + i + 1);
        }
        if (rail.curve().closed()) {
            out += ' ';
            out += std::to_string(vertices + 1);
        }
        out += '\n';
        vertices += points.size();
    }
    io::writeFileAtomically(path, out);
}

} // namespace netsculpt
