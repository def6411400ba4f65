// The DXF writer (DxfExport.h), by hand: dxflib's writer prints reals with "%.16f", which loses
// digits of small numbers, and asks for an AutoCAD 2000 skeleton (handles, dictionaries) that
// Release 12 does without.

#include "io/DxfExport.h"

#include "io/DxfCodes.h"
#include "io/IoText.h"
#include "io/Scene.h"

#include <algorithm>
#include <cmath>

namespace netsculpt::io {

namespace {

constexpr std::size_t kMaxLayerName = 255;
constexpr int kRailAci = 7;
constexpr int kGreyAci = 8;

/// Group code and value pairs, one per two lines.
class DxfWriter {
  public:
    void text(int code, std::string_view value) {
        appendIntegers(out_, {code});
        out_ += '\n';
        out_ += value;
        out_ += '\n';
    }
    void integer(int code, long long value) {
        appendIntegers(out_, {code});
        out_ += '\n';
        appendIntegers(out_, {value});
        out_ += '\n';
    }
    void real(int code, double value) {
        appendIntegers(out_, {code});
        out_ += '\n';
        appendNumber(out_, value);
        out_ += '\n';
    }
    /// Groups `code`, `code` + 10 and `code` + 20: x, y, z.
    void point(int code, const Vec3& p) {
        real(code, p.x);
        real(code + 10, p.y);
        real(code + 20, p.z);
    }
    void mark(std::initializer_list<std::string_view> strings) {
        text(1001, kDxfApplication);
        for (auto s : strings)
            text(1000, s);
    }
    std::string take() { return std::move(out_); }

  private:
    std::string out_;
};

struct Layer {
    std::string name;
    int colour;
};

void writeHeader(DxfWriter& w) {
    w.text(0, "SECTION");
    w.text(2, "HEADER");
    w.text(9, "$ACADVER");
    w.text(1, "AC1009");
    w.text(9, "$INSUNITS");
    w.integer(70, 6); // metres
    w.text(0, "ENDSEC");
}

void writeTable(DxfWriter& w, const char* name, int entries) {
    w.text(0, "TABLE");
    w.text(2, name);
    w.integer(70, entries);
}

void writeTables(DxfWriter& w, const std::vector<Layer>& layers) {
    w.text(0, "SECTION");
    w.text(2, "TABLES");
    writeTable(w, "LTYPE", 1);
    w.text(0, "LTYPE");
    w.text(2, "CONTINUOUS");
    w.integer(70, 0);
    w.text(3, "Solid line");
    w.integer(72, 65);
    w.integer(73, 0);
    w.real(40, 0);
    w.text(0, "ENDTAB");
    writeTable(w, "LAYER", int(layers.size()) + 1);
    const auto writeLayer = [&](const Layer& layer) {
        w.text(0, "LAYER");
        w.text(2, layer.name);
        w.integer(70, 0);
        w.integer(62, layer.colour);
        w.text(6, "CONTINUOUS");
    };
    writeLayer({"0", 7});
    for (const Layer& layer : layers)
        writeLayer(layer);
    w.text(0, "ENDTAB");
    writeTable(w, "APPID", 1);
    w.text(0, "APPID");
    w.text(2, kDxfApplication);
    w.integer(70, 0);
    w.text(0, "ENDTAB");
    w.text(0, "ENDSEC");
}

void writeRail(DxfWriter& w, const std::string& layer, const Rail& rail) {
    const bool closed = rail.curve().closed();
    w.text(0, "POLYLINE");
    w.text(8, layer);
    w.integer(66, 1);
    w.point(10, {});
    w.integer(70, closed ? 8 + 1 : 8); // 8: a 3D polyline; 1: closed
    w.mark({"rail", rail.name});
    for (const Vec3& p : railPolyline(rail.curve(), false)) {
        w.text(0, "VERTEX");
        w.text(8, layer);
        w.point(10, p);
        w.integer(70, 32); // a vertex of a 3D polyline
    }
    w.text(0, "SEQEND");
    w.text(8, layer);
}

void writeBars(DxfWriter& w, const std::string& layer, PieceId piece, const MassSpringSystem& sys) {
    for (std::size_t b = 0; b < sys.barCount(); ++b) {
        if (sys.barPiece[b] != piece)
            continue;
        w.text(0, "LINE");
        w.text(8, layer);
        w.point(10, sys.worldPosition(sys.barA[b]));
        w.point(11, sys.worldPosition(sys.barB[b]));
        w.mark({"bar"});
    }
}

} // namespace

std::string dxfLayerName(const std::string& kind, int id, const std::string& name) {
    std::string layer = concat({kind, "_", std::to_string(id)});
    if (name.empty() || name == concat({kind, " ", std::to_string(id)})) // a default name
        return layer;
    layer += '_';
    for (char c : name) {
        const bool allowed = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                             (c >= '0' && c <= '9') || c == '-' || c == '_';
        layer += allowed ? c : '_';
    }
    layer.resize(std::min(layer.size(), kMaxLayerName));
    return layer;
}

int nearestAci(double r, double g, double b) {
    const double high = std::max({r, g, b});
    const double low = std::min({r, g, b});
    const double chroma = high - low;
    const double saturation = high > 0 ? chroma / high : 0;
    if (saturation < 0.25)
        return high > 0.8 ? kRailAci : kGreyAci;
    double hue; // degrees
    if (high == r)
        hue = 60 * std::fmod((g - b) / chroma + 6, 6.0);
    else if (high == g)
        hue = 60 * ((b - r) / chroma + 2);
    else
        hue = 60 * ((r - g) / chroma + 4);
    // ACI 10, 20, ..., 240: hues 0, 15, ..., 345 degrees. Within each, +0 +2 +4 +6 +8 darken
    // (value 1, 0.8, 0.6, 0.5, 0.3) and an odd number is the half-saturated shade.
    const int hueStep = int(std::lround(hue / 15)) % 24;
    const double values[] = {1.0, 0.8, 0.6, 0.5, 0.3};
    int shade = 0;
    for (int i = 1; i < 5; ++i)
        if (std::abs(high - values[i]) < std::abs(high - values[shade]))
            shade = i;
    return 10 * (hueStep + 1) + 2 * shade + (saturation < 0.75 ? 1 : 0);
}

std::string dxfText(const Sculpture& sculpture, const MassSpringSystem* system) {
    std::vector<Layer> layers;
    std::vector<std::pair<PieceId, std::string>> pieceLayers;
    if (system)
        for (const auto& [id, piece] : sculpture.pieces) {
            const Rgb c = toSrgb(piece.colour);
            pieceLayers.push_back({id, dxfLayerName("piece", int(id.value), piece.name)});
            layers.push_back({pieceLayers.back().second, nearestAci(c.r, c.g, c.b)});
        }
    std::vector<std::pair<const Rail*, std::string>> railLayers;
    for (const auto& [id, rail] : sculpture.rails) {
        railLayers.push_back({&rail, dxfLayerName("rail", int(id.value), rail.name)});
        layers.push_back({railLayers.back().second, kRailAci});
    }
    DxfWriter w;
    w.text(999, "netsculpt: metres, z up");
    writeHeader(w);
    writeTables(w, layers);
    w.text(0, "SECTION");
    w.text(2, "ENTITIES");
    for (const auto& [id, layer] : pieceLayers)
        writeBars(w, layer, id, *system);
    for (const auto& [rail, layer] : railLayers)
        writeRail(w, layer, *rail);
    w.text(0, "ENDSEC");
    w.text(0, "EOF");
    return w.take();
}

} // namespace netsculpt::io
