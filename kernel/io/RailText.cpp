// Rails from OBJ and CSV files (Import.h): CSV x,y,z rows (optionally a rail column), OBJ `l`
// elements chained per object.

#include "io/Chains.h"
#include "io/ImportDetail.h"
#include "io/IoText.h"
#include "model/Error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace netsculpt::io {

namespace {

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
        field = std::string(trim(field));
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
    const auto value = parseDouble(field);
    if (!value)
        throw UserError(file + ":" + std::to_string(line) + ": " + what + " " + io::quoted(field) +
                        " " + numberRefusal(field));
    if (!std::isfinite(*value))
        throw UserError(file + ":" + std::to_string(line) + ": " + what + " is " +
                        io::quoted(field) + "; coordinates must be finite numbers");
    return *value;
}

// ---- CSV ----

/// A CSV coordinate: a finite number within kMaxCoordinate (`metres` per file unit), else a
/// UserError naming its line, the value and what is allowed.
double csvCoordinate(const std::string& file, std::size_t line, std::string_view field,
                     const char* what, double metres) {
    const double value = coordinate(file, line, field, what);
    if (const std::string far = farCoordinate(value, metres); !far.empty())
        throw UserError(file + ":" + std::to_string(line) + ": " + what + " is " + far);
    return value;
}

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

} // namespace

std::vector<SourcedCurve> readCsv(const std::filesystem::path& path, double metres) {
    const std::string file = displayName(path);
    const std::string text = withoutByteOrderMark(readWholeFile(path));
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
        const std::string_view line = trim(all[i]);
        if (line.empty() || line.front() == '#')
            continue;
        auto fields = splitFields(line, ',');
        if (!sawHeader && points.empty() && !parseDouble(fields[0])) {
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
        const Vec3 p{csvCoordinate(file, lineNo, fields[std::size_t(at.x)], "x", metres),
                     csvCoordinate(file, lineNo, fields[std::size_t(at.y)], "y", metres),
                     csvCoordinate(file, lineNo, fields[std::size_t(at.z)], "z", metres)};
        if (!points.count(rail)) {
            order.push_back(rail);
            firstLine[rail] = lineNo;
        }
        points[rail].push_back(p);
    }
    if (order.empty())
        throw UserError(file + ": holds no points (expected x,y,z rows)");
    std::vector<SourcedCurve> out;
    for (const auto& name : order)
        out.push_back(
            {{name, polylineSpec(points[name])},
             "rail " + io::quoted(name) + " (from line " + std::to_string(firstLine[name]) + ")"});
    return out;
}

// ---- OBJ ----

namespace {

/// Resolves an OBJ vertex reference ("3", "-1", "3/7"): 1-based, negative from the end.
std::size_t vertexIndex(const std::string& file, std::size_t lineNo, const std::string& word,
                        std::size_t defined) {
    const std::string_view ref = std::string_view(word).substr(0, word.find('/'));
    const auto index = parseInteger(ref);
    const long long n = (long long)defined;
    const long long resolved = !index ? 0 : *index > 0 ? *index : n + *index + 1;
    if (!index || *index == 0 || resolved < 1 || resolved > n)
        throw UserError(file + ":" + std::to_string(lineNo) + ": vertex reference " +
                        io::quoted(word) + " does not name one of the " + std::to_string(n) +
                        " vertices defined so far");
    return std::size_t(resolved - 1);
}

/// Refuses OBJ vertex `index` (0-based, defined on line `vertexLine`) when a coordinate is too
/// far out, naming the vertex's own line and the `l` on line `lineNo` that uses it.
void checkObjVertex(const std::string& file, std::size_t lineNo, std::size_t index,
                    std::size_t vertexLine, const Vec3& vertex, double metres) {
    const std::array<std::pair<const char*, double>, 3> coordinates{
        {{"x", vertex.x}, {"y", vertex.y}, {"z", vertex.z}}};
    for (const auto& [what, value] : coordinates)
        if (const std::string far = farCoordinate(value, metres); !far.empty())
            throw UserError(concat({file, ":", std::to_string(vertexLine), ": vertex ",
                                    std::to_string(index + 1), ", used by the 'l' on line ",
                                    std::to_string(lineNo), ": ", what, " is ", far}));
}

} // namespace

/// The `l` elements of each object (in order of first appearance), chained into rails like a
/// DXF layer's LINEs: an object drawn as one `l` per edge (as Blender writes) is one rail.
std::vector<SourcedCurve> readObj(const std::filesystem::path& path, double metres) {
    const std::string file = displayName(path);
    const std::string text = readWholeFile(path);
    checkText(file, text);
    std::vector<Vec3> vertices;
    std::vector<std::size_t> vertexLines; // where each vertex is defined
    std::vector<std::string> objects; // in order of their first `l`
    std::map<std::string, std::vector<ChainPart>> parts;
    std::string object = path.stem().string();
    const auto all = lines(text);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const std::size_t lineNo = i + 1;
        const std::string_view line = trim(all[i]);
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
            vertexLines.push_back(lineNo);
        } else if (keyword == "o" || keyword == "g") {
            if (words.size() > 1)
                object = std::string(trim(line.substr(1)));
        } else if (keyword == "l") {
            if (words.size() < 3)
                throw UserError(file + ":" + std::to_string(lineNo) +
                                ": a line element needs at least 2 vertices");
            ChainPart part{{}, object, "line " + std::to_string(lineNo), lineNo};
            for (std::size_t w = 1; w < words.size(); ++w) {
                const std::size_t v = vertexIndex(file, lineNo, words[w], vertices.size());
                checkObjVertex(file, lineNo, v, vertexLines[v], vertices[v], metres);
                part.points.push_back(vertices[v]);
            }
            if (!parts.count(object))
                objects.push_back(object);
            parts[object].push_back(std::move(part));
        }
    }
    if (objects.empty())
        throw UserError(file +
                        ": holds no polylines ('l' elements); rails are read from 'l' lines");
    std::vector<SourcedCurve> out;
    for (const auto& name : objects) {
        auto chains = joinChains(file, std::move(parts[name]),
                                 "put the branches in different objects ('o' lines)");
        std::stable_sort(chains.begin(), chains.end(),
                         [](const auto& a, const auto& b) { return a.order < b.order; });
        for (std::size_t k = 0; k < chains.size(); ++k) {
            if (chains.size() > 1)
                chains[k].rail.name += concat({"#", std::to_string(k + 1)});
            out.push_back(std::move(chains[k]));
        }
    }
    return out;
}

} // namespace netsculpt::io
