// Rails from OBJ and CSV files, the dispatch by extension, units, and the final check of every
// rail through Curve::build (Import.h).

#include "io/Import.h"

#include "geometry/Curve.h"
#include "io/ImportDetail.h"
#include "io/IoText.h"
#include "model/Error.h"

#include <algorithm>
#include <array>
#include <map>

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

std::string joined(const std::vector<std::string>& items) {
    std::string text;
    for (const auto& item : items)
        text += (text.empty() ? "" : ", ") + item;
    return text;
}

/// Splits a line at `separator`, honouring double-quoted fields ("a,b" and "" for a quote).
std::vector<std::string> splitFields(std::string_view line, char separator) {
    std::vector<std::string> fields(1);
    bool inQuotes = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (inQuotes) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                fields.back() += '"';
                ++i;
            } else if (c == '"') {
                inQuotes = false;
            } else {
                fields.back() += c;
            }
        } else if (c == '"') {
            inQuotes = true;
        } else if (c == separator) {
            fields.emplace_back();
        } else {
            fields.back() += c;
        }
    }
    for (auto& field : fields)
        field = std::string(io::trim(field));
    return fields;
}

std::vector<std::string> splitWords(std::string_view line) {
    std::vector<std::string> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
            ++i;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t')
            ++i;
        if (i > start)
            words.emplace_back(line.substr(start, i - start));
    }
    return words;
}

std::vector<std::string_view> lines(const std::string& text) {
    std::vector<std::string_view> out;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos)
            end = text.size();
        std::string_view line(text.data() + start, end - start);
        if (!line.empty() && line.back() == '\r')
            line.remove_suffix(1);
        out.push_back(line);
        start = end + 1;
    }
    if (!out.empty() && out.back().empty())
        out.pop_back();
    return out;
}

void checkText(const std::string& file, const std::string& text) {
    if (text.find('\0') != std::string::npos)
        throw UserError(file + ": holds binary data (a NUL byte); expected a text file");
}

double coordinate(const std::string& file, std::size_t line, std::string_view field,
                  const char* what) {
    const auto value = io::parseDouble(field);
    if (!value)
        throw UserError(file + ":" + std::to_string(line) + ": " + what + " " + io::quoted(field) +
                        " is not a number");
    if (!std::isfinite(*value))
        throw UserError(file + ":" + std::to_string(line) + ": " + what + " is " +
                        io::quoted(field) + "; coordinates must be finite numbers");
    return *value;
}

// ---- CSV ----

/// `text` without the UTF-8 byte-order mark that spreadsheets write before a CSV's first field.
std::string withoutByteOrderMark(std::string text) {
    if (text.starts_with("\xEF\xBB\xBF"))
        text.erase(0, 3);
    return text;
}

/// Where a rail CSV's fields are: x, y, z and the rail's name (-1: none, one rail per file).
struct CsvColumns {
    int rail = -1, x = 0, y = 1, z = 2;
};

/// The columns a header line names: x, y and z once each, rail at most once, nothing else.
CsvColumns readCsvHeader(const std::string& file, std::size_t lineNo, std::string_view line,
                         const std::vector<std::string>& fields) {
    CsvColumns at{-1, -1, -1, -1};
    for (std::size_t c = 0; c < fields.size(); ++c) {
        std::string name = fields[c];
        std::transform(name.begin(), name.end(), name.begin(), ::tolower);
        int* column = name == "x"      ? &at.x
                      : name == "y"    ? &at.y
                      : name == "z"    ? &at.z
                      : name == "rail" ? &at.rail
                                       : nullptr;
        if (column == nullptr || *column >= 0)
            throw UserError(file + ":" + std::to_string(lineNo) + ": the header " +
                            io::quoted(line, 80) + " has " +
                            (column == nullptr ? "a column " : "twice the column ") +
                            io::quoted(name, 40) +
                            "; a rail file's columns are x, y, z and optionally rail (a knots "
                            "export is no rail file)");
        *column = int(c);
    }
    if (at.x < 0 || at.y < 0 || at.z < 0)
        throw UserError(file + ":" + std::to_string(lineNo) + ": the header " +
                        io::quoted(line, 80) +
                        " must name columns x, y and z (and optionally rail)");
    return at;
}

std::vector<io::SourcedCurve> readCsv(const std::filesystem::path& path) {
    const std::string file = io::displayName(path);
    const std::string text = withoutByteOrderMark(io::readWholeFile(path));
    checkText(file, text);
    CsvColumns at;
    std::size_t expected = 3;
    bool sawHeader = false;
    std::vector<std::string> order;                  // rail names, first appearance
    std::map<std::string, std::vector<Vec3>> points; // by rail name
    std::map<std::string, std::size_t> firstLine;
    const std::string stem = path.stem().string();
    const auto all = lines(text);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const std::size_t lineNo = i + 1;
        const std::string_view line = io::trim(all[i]);
        if (line.empty() || line.front() == '#')
            continue;
        auto fields = splitFields(line, ',');
        if (!sawHeader && points.empty() && !io::parseDouble(fields[0])) {
            sawHeader = true;
            at = readCsvHeader(file, lineNo, line, fields);
            expected = fields.size();
            continue;
        }
        if (fields.size() != expected)
            throw UserError(file + ":" + std::to_string(lineNo) + ": " +
                            std::to_string(fields.size()) + " fields, expected " +
                            std::to_string(expected) +
                            (sawHeader ? " (as in the header)"
                                       : " (x,y,z; give a header line to add a rail column)"));
        const std::string rail = at.rail >= 0 ? fields[std::size_t(at.rail)] : stem;
        if (rail.empty())
            throw UserError(file + ":" + std::to_string(lineNo) + ": the rail column is empty");
        const Vec3 p{coordinate(file, lineNo, fields[std::size_t(at.x)], "x"),
                     coordinate(file, lineNo, fields[std::size_t(at.y)], "y"),
                     coordinate(file, lineNo, fields[std::size_t(at.z)], "z")};
        if (!points.count(rail)) {
            order.push_back(rail);
            firstLine[rail] = lineNo;
        }
        points[rail].push_back(p);
    }
    if (order.empty())
        throw UserError(file + ": holds no points (expected x,y,z rows)");
    std::vector<io::SourcedCurve> out;
    for (const auto& name : order)
        out.push_back(
            {{name, io::polylineSpec(points[name])},
             "rail " + io::quoted(name) + " (from line " + std::to_string(firstLine[name]) + ")"});
    return out;
}

// ---- OBJ ----

std::vector<io::SourcedCurve> readObj(const std::filesystem::path& path) {
    const std::string file = io::displayName(path);
    const std::string text = io::readWholeFile(path);
    checkText(file, text);
    std::vector<Vec3> vertices;
    struct Line {
        std::string object;
        std::size_t lineNo;
        std::vector<Vec3> points;
        bool closed;
    };
    std::vector<Line> found;
    std::string object = path.stem().string();
    const auto all = lines(text);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const std::size_t lineNo = i + 1;
        const std::string_view line = io::trim(all[i]);
        if (line.empty() || line.front() == '#')
            continue; // a '#' inside a name is not a comment
        const std::vector<std::string> words = splitWords(line);
        const std::string& keyword = words[0];
        if (keyword == "v") {
            if (words.size() < 4)
                throw UserError(file + ":" + std::to_string(lineNo) +
                                ": a vertex needs x y z, got " + io::quoted(line, 80));
            vertices.push_back({coordinate(file, lineNo, words[1], "x"),
                                coordinate(file, lineNo, words[2], "y"),
                                coordinate(file, lineNo, words[3], "z")});
        } else if (keyword == "o" || keyword == "g") {
            if (words.size() > 1)
                object = std::string(io::trim(line.substr(1)));
        } else if (keyword == "l") {
            if (words.size() < 3)
                throw UserError(file + ":" + std::to_string(lineNo) +
                                ": a line element needs at least 2 vertices");
            Line l{object, lineNo, {}, false};
            std::vector<long long> indices;
            for (std::size_t w = 1; w < words.size(); ++w) {
                const std::string_view ref =
                    std::string_view(words[w]).substr(0, words[w].find('/'));
                const auto index = io::parseInteger(ref);
                const long long n = (long long)vertices.size();
                const long long resolved = !index ? 0 : *index > 0 ? *index : n + *index + 1;
                if (!index || *index == 0 || resolved < 1 || resolved > n)
                    throw UserError(file + ":" + std::to_string(lineNo) + ": vertex reference " +
                                    io::quoted(words[w]) + " does not name one of the " +
                                    std::to_string(n) + " vertices defined so far");
                indices.push_back(resolved);
                l.points.push_back(vertices[std::size_t(resolved - 1)]);
            }
            if (indices.size() > 2 && indices.front() == indices.back()) {
                l.points.pop_back();
                l.closed = true;
            }
            found.push_back(std::move(l));
        }
    }
    if (found.empty())
        throw UserError(file +
                        ": holds no polylines ('l' elements); rails are read from 'l' lines");
    std::map<std::string, int> perObject, seen;
    for (const auto& l : found)
        ++perObject[l.object];
    std::vector<io::SourcedCurve> out;
    for (auto& l : found) {
        std::string name = l.object;
        if (perObject[l.object] > 1)
            name += io::concat({"#", std::to_string(++seen[l.object])});
        out.push_back({{name, io::polylineSpec(std::move(l.points), l.closed)},
                       "line " + std::to_string(l.lineNo)});
    }
    return out;
}

} // namespace

namespace io {

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
                    joined(unitNames()));
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
    const double metres = options.units.empty() ? 1.0 : metresPerUnit(options.units);
    if (ext == "obj")
        return io::finishRails(file, readObj(path), metres);
    if (ext == "csv")
        return io::finishRails(file, readCsv(path), metres);
    throw UserError(file + ": cannot read rails from a ." + ext +
                    " file; rail files are .dxf, .obj and .csv");
}

} // namespace netsculpt
