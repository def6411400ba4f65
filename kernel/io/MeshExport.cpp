// OBJ and PLY: knots as vertices and bars as lines, or bars as tube meshes; rails as polylines.

#include "io/Exporters.h"
#include "io/IoText.h"
#include "io/Scene.h"

#include "model/Error.h"

#include <algorithm>
#include <cmath>

namespace netsculpt::io {

void appendTube(TubeMesh& mesh, const Vec3& a, const Vec3& b, double radius) {
    const Vec3 axis = b - a;
    const double length = axis.norm();
    if (!(length > 0))
        return;
    const Vec3 d = axis / length;
    const Vec3 helper = std::abs(d.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
    Vec3 u = d.cross(helper);
    u = u / u.norm();
    const Vec3 v = d.cross(u);
    const auto base = std::uint32_t(mesh.vertices.size());
    for (const Vec3& end : {a, b})
        for (int i = 0; i < kTubeSides; ++i) {
            const double angle = 2 * 3.14159265358979323846 * i / kTubeSides;
            const Vec3 n = u * std::cos(angle) + v * std::sin(angle);
            mesh.vertices.push_back(end + n * radius);
            mesh.normals.push_back(n);
        }
    for (std::uint32_t i = 0; i < kTubeSides; ++i) {
        const std::uint32_t j = (i + 1) % kTubeSides;
        mesh.triangles.push_back({base + i, base + j, base + kTubeSides + j});
        mesh.triangles.push_back({base + i, base + kTubeSides + j, base + kTubeSides + i});
    }
}

namespace {

std::string safeName(const std::string& name) {
    std::string out;
    for (char c : name)
        out += (c == ' ' || c == '\t' || c == '\n' || c == '\r') ? '_' : c;
    return out;
}

std::string pieceLabel(const Sculpture& s, PieceId id) {
    const Piece& p = s.piece(id);
    return concat(
        {"piece_", std::to_string(id.value), p.name.empty() ? "" : "_", safeName(p.name)});
}

void checkRadius(double radius) {
    if (!(std::isfinite(radius) && radius >= 0))
        throw UserError("tube_radius must be a finite number >= 0 (m), got " + numberText(radius));
}

struct Rgb8 {
    int r, g, b;
};
Rgb8 bytes(const Rgb& c) {
    const auto byte = [](double v) { return int(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
    return {byte(c.r), byte(c.g), byte(c.b)};
}

} // namespace

std::string objText(const ExportInput& in) {
    checkRadius(in.options.tubeRadius);
    const MassSpringSystem& sys = in.compiled.system;
    const bool tubes = in.options.tubeRadius > 0;
    std::string out = "# netsculpt: " + std::to_string(sys.knotCount()) + " knots, " +
                      std::to_string(sys.barCount()) + " bars, " +
                      std::to_string(in.sculpture.rails.size()) + " rails; metres, z up\n";
    std::size_t vertexCount = 0;
    if (!tubes) {
        out += "o knots\n";
        for (std::size_t k = 0; k < sys.knotCount(); ++k) {
            out += "v ";
            appendVec(out, sys.worldPosition(k), ' ');
            out += '\n';
        }
        vertexCount = sys.knotCount();
    }
    for (const auto& [id, piece] : in.sculpture.pieces) {
        out += concat({"o ", pieceLabel(in.sculpture, id), "\n"});
        if (!tubes) {
            for (std::size_t b = 0; b < sys.barCount(); ++b)
                if (sys.barPiece[b] == id) {
                    out += "l ";
                    appendIntegers(out, {sys.barA[b] + 1ll, sys.barB[b] + 1ll});
                    out += '\n';
                }
            continue;
        }
        TubeMesh mesh;
        for (std::size_t b = 0; b < sys.barCount(); ++b)
            if (sys.barPiece[b] == id)
                appendTube(mesh, sys.worldPosition(sys.barA[b]), sys.worldPosition(sys.barB[b]),
                           in.options.tubeRadius);
        for (const Vec3& p : mesh.vertices) {
            out += "v ";
            appendVec(out, p, ' ');
            out += '\n';
        }
        for (const auto& t : mesh.triangles) {
            const auto base = (long long)vertexCount + 1;
            out += "f ";
            appendIntegers(out, {base + t[0], base + t[1], base + t[2]});
            out += '\n';
        }
        vertexCount += mesh.vertices.size();
    }
    for (const auto& [id, rail] : in.sculpture.rails) {
        out += "o rail_";
        appendIntegers(out, {id.value});
        if (!rail.name.empty())
            out += '_' + safeName(rail.name);
        out += '\n';
        const auto points = railPolyline(rail.curve(), false);
        for (const Vec3& p : points) {
            out += "v ";
            appendVec(out, p, ' ');
            out += '\n';
        }
        out += "l";
        for (std::size_t i = 0; i <= points.size(); ++i) {
            if (i == points.size() && !rail.curve().closed())
                break;
            out += ' ';
            out += std::to_string(vertexCount + i % points.size() +
                                  1); // a closed rail ends where it starts
        }
        out += '\n';
        vertexCount += points.size();
    }
    return out;
}

std::string plyText(const ExportInput& in) {
    checkRadius(in.options.tubeRadius);
    const MassSpringSystem& sys = in.compiled.system;
    const bool tubes = in.options.tubeRadius > 0;
    std::vector<Vec3> vertices;
    std::vector<Rgb8> colours;
    std::vector<std::array<std::uint32_t, 2>> edges;
    std::vector<Rgb8> edgeColours;
    std::vector<std::array<std::uint32_t, 3>> faces;
    const auto pieceColour = [&](PieceId id) {
        return bytes(toSrgb(in.sculpture.piece(id).colour));
    };
    if (!tubes) {
        for (std::size_t k = 0; k < sys.knotCount(); ++k) vertices.push_back(sys.worldPosition(k));
        for (std::size_t k = 0; k < sys.knotCount(); ++k)
            colours.push_back(sys.fixed[k] ? bytes(kRailColour)
                                           : pieceColour(sys.refs[sys.refStart[k]].piece));
        for (std::size_t b = 0; b < sys.barCount(); ++b) {
            edges.push_back({sys.barA[b], sys.barB[b]});
            edgeColours.push_back(pieceColour(sys.barPiece[b]));
        }
    } else {
        for (std::size_t b = 0; b < sys.barCount(); ++b) {
            TubeMesh mesh;
            appendTube(mesh, sys.worldPosition(sys.barA[b]), sys.worldPosition(sys.barB[b]),
                       in.options.tubeRadius);
            const auto base = std::uint32_t(vertices.size());
            vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
            colours.insert(colours.end(), mesh.vertices.size(), pieceColour(sys.barPiece[b]));
            for (const auto& t : mesh.triangles)
                faces.push_back({base + t[0], base + t[1], base + t[2]});
        }
    }
    for (const auto& [id, rail] : in.sculpture.rails) {
        const auto points = railPolyline(rail.curve(), false);
        const auto base = std::uint32_t(vertices.size());
        vertices.insert(vertices.end(), points.begin(), points.end());
        colours.insert(colours.end(), points.size(), bytes(kRailColour));
        const std::size_t n = points.size();
        const std::size_t segments = rail.curve().closed() ? n : n - 1;
        for (std::size_t i = 0; i < segments; ++i) {
            edges.push_back({base + std::uint32_t(i), base + std::uint32_t((i + 1) % n)});
            edgeColours.push_back(bytes(kRailColour));
        }
    }
    std::string out = "ply\nformat ascii 1.0\ncomment netsculpt: metres, z up\n";
    out += "element vertex ";
    appendIntegers(out, {(long long)vertices.size()});
    out += "\nproperty double x\nproperty double y\nproperty double z\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    if (!faces.empty() || tubes) {
        out += "element face ";
        appendIntegers(out, {(long long)faces.size()});
        out += "\nproperty list uchar int vertex_indices\n";
    }
    out += "element edge ";
    appendIntegers(out, {(long long)edges.size()});
    out += "\nproperty int vertex1\nproperty int vertex2\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        appendVec(out, vertices[i], ' ');
        out += ' ';
        appendIntegers(out, {colours[i].r, colours[i].g, colours[i].b});
        out += '\n';
    }
    for (const auto& f : faces) {
        out += "3 ";
        appendIntegers(out, {f[0], f[1], f[2]});
        out += '\n';
    }
    for (std::size_t i = 0; i < edges.size(); ++i) {
        appendIntegers(
            out, {edges[i][0], edges[i][1], edgeColours[i].r, edgeColours[i].g, edgeColours[i].b});
        out += '\n';
    }
    return out;
}

} // namespace netsculpt::io
