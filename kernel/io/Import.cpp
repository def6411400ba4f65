// The dispatch of rail files by extension, units, and the final check of every rail (Import.h).

#include "io/Import.h"

#include "geometry/Curve.h"
#include "io/ImportDetail.h"
#include "io/IoText.h"
#include "model/Error.h"

#include <array>
#include <cmath>

namespace netsculpt {

namespace {

struct Unit {
    const char* name;
    double metres;
};
constexpr std::array<Unit, 9> kUnits{{{"m", 1.0},
                                      {"mm", 1e-3},
                                      {"cm", 1e-2},
                                      {"dm", 1e-1},
                                      {"km", 1e3},
                                      {"in", 0.0254},
                                      {"ft", 0.3048},
                                      {"yd", 0.9144},
                                      {"mi", 1609.344}}};

} // namespace

namespace io {

std::string farCoordinate(double c, double metres) {
    if (std::isnan(c) || std::abs(c * metres) <= kMaxCoordinate)
        return {};
    const bool inMetres = metres == 1.0;
    return concat(
        {numberText(c), inMetres ? " m" : concat({" (", numberText(c * metres), " m)"}),
         ", too large: rails must lie within ", numberText(kMaxCoordinate),
         " m of the origin in x, y and z",
         inMetres ? ""
                  : concat({" (", numberText(kMaxCoordinate / metres), " in the file's units)"})});
}

void checkCoordinates(const std::string& file, const std::string& where,
                      const std::vector<Vec3>& points, double metres) {
    for (const Vec3& p : points)
        for (const double c : {p.x, p.y, p.z}) {
            if (std::isnan(c))
                throw UserError(concat({file, ": ", where,
                                        ": has a coordinate that is not a number (nan); "
                                        "coordinates must be finite numbers"}));
            if (const std::string far = farCoordinate(c, metres); !far.empty())
                throw UserError(concat({file, ": ", where, ": has a coordinate of ", far}));
        }
}

CurveSpec polylineSpec(std::vector<Vec3> points, bool closed) {
    CurveSpec spec;
    if (points.size() > 2 && points.front() == points.back()) {
        points.pop_back();
        closed = true;
    }
    spec.points = std::move(points);
    spec.closed = closed;
    return spec;
}

std::vector<NamedCurve> finishRails(const std::string& file, std::vector<SourcedCurve> curves,
                                    double metres) {
    std::vector<NamedCurve> rails;
    rails.reserve(curves.size());
    for (auto& sourced : curves) {
        CurveSpec& spec = sourced.rail.curve;
        checkCoordinates(file, sourced.where, spec.points, metres);
        if (metres != 1.0)
            for (Vec3& p : spec.points)
                p *= metres;
        try {
            (void)Curve::build(spec);
        } catch (const UserError& e) {
            throw UserError(file + ": " + sourced.where + ": " + e.what());
        }
        rails.push_back(std::move(sourced.rail));
    }
    return rails;
}

} // namespace io

std::vector<std::string> unitNames() {
    std::vector<std::string> names;
    for (const Unit& u : kUnits)
        names.emplace_back(u.name);
    return names;
}

double metresPerUnit(const std::string& unit) {
    for (const Unit& u : kUnits)
        if (unit == u.name)
            return u.metres;
    throw UserError("unknown unit " + io::quoted(unit) + "; allowed units are " +
                    io::listed(unitNames()));
}

std::vector<NamedCurve> importRailsFile(const std::filesystem::path& path) {
    return importRailsFile(path, ImportOptions{});
}

std::vector<NamedCurve> importRailsFile(const std::filesystem::path& path,
                                        const ImportOptions& options) {
    const std::string file = io::displayName(path);
    const std::string ext = io::lowerExtension(path);
    if (!options.units.empty())
        (void)metresPerUnit(options.units); // validate first
    if (ext == "dxf")
        return io::importDxf(path, options);
    if (!options.layers.empty() && (ext == "obj" || ext == "csv"))
        throw UserError(file + ": layers selects the layers of a DXF drawing; an ." + ext +
                        " file has none (leave layers out)");
    const double metres = options.units.empty() ? 1.0 : metresPerUnit(options.units);
    if (ext == "obj")
        return io::finishRails(file, io::readObj(path, metres), metres);
    if (ext == "csv")
        return io::finishRails(file, io::readCsv(path, metres), metres);
    throw UserError(file + ": cannot read rails from a ." + ext +
                    " file; rail files are .dxf, .obj and .csv");
}

} // namespace netsculpt
