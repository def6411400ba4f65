#include "io/Scene.h"

#include "model/Error.h"
#include "physics/Forces.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace netsculpt::io {

namespace {

double linearToSrgb(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

double srgbToLinear(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::string thousands(std::size_t n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0)
            out += ',';
        out += digits[i];
    }
    return out;
}

} // namespace

Rgb toSrgb(const Colour& c) {
    return {linearToSrgb(c.r), linearToSrgb(c.g), linearToSrgb(c.b)};
}

Colour toLinear(const Rgb& c) {
    return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)};
}

Rgb tensionColour(double fraction) {
    static constexpr std::array<Rgb, 4> stops{
        {{0.17, 0.38, 0.78}, {0.10, 0.62, 0.55}, {0.96, 0.62, 0.10}, {0.80, 0.08, 0.10}}};
    const double f =
        std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0) * double(stops.size() - 1);
    const std::size_t i = std::min(std::size_t(f), stops.size() - 2);
    const double w = f - double(i);
    const Rgb& a = stops[i];
    const Rgb& b = stops[i + 1];
    return {a.r + (b.r - a.r) * w, a.g + (b.g - a.g) * w, a.b + (b.b - a.b) * w};
}

bool isSlack(double length, double restLength) {
    return length < restLength * (1 - 1e-9);
}

std::vector<Vec3> railPolyline(const Curve& curve, bool repeatFirst) {
    const CurveSpec& spec = curve.spec();
    std::vector<Vec3> points;
    if (!spec.spline) {
        for (const Vec3& p : spec.points)
            if (points.empty() || !(p == points.back()))
                points.push_back(p);
        if (spec.closed && points.size() > 1 && points.back() == points.front())
            points.pop_back();
    } else {
        CurveSpec byParameter = spec;
        byParameter.sampling = Sampling::Parameter;
        const Curve sampler = Curve::build(byParameter);
        const int spans = std::max(1, int(spec.points.size()) - (spec.closed ? 0 : spec.degree));
        const int n = std::max(256, 64 * spans);
        points = sampler.samplePoints(0, 1.0 / (spec.closed ? n : n - 1), n);
    }
    if (repeatFirst && spec.closed && !points.empty())
        points.push_back(points.front());
    return points;
}

Scene buildScene(const Sculpture& s, const CompiledSculpture& c, const std::string& colourBy,
                 bool relaxed) {
    if (colourBy != "piece" && colourBy != "tension")
        throw UserError("colour_by must be \"piece\" or \"tension\", got \"" + colourBy + "\"");
    const MassSpringSystem& sys = c.system;
    Scene scene;
    scene.colourBy = colourBy;
    scene.tension = sys.barCount() > 0 ? barTensions(sys) : std::vector<double>{};
    for (double t : scene.tension)
        if (std::isfinite(t))
            scene.maxTension = std::max(scene.maxTension, t);
    for (std::uint32_t b = 0; b < sys.barCount(); ++b) {
        SceneSegment seg{sys.worldPosition(sys.barA[b]), sys.worldPosition(sys.barB[b]), {}, false,
                         b};
        const double length = distance(sys.position[sys.barA[b]], sys.position[sys.barB[b]]);
        if (colourBy == "piece") {
            seg.colour = toSrgb(s.piece(sys.barPiece[b]).colour);
        } else if (isSlack(length, sys.restLength[b])) {
            seg.colour = kSlackColour;
        } else {
            seg.colour =
                tensionColour(scene.maxTension > 0 ? scene.tension[b] / scene.maxTension : 0.0);
        }
        scene.segments.push_back(seg);
    }
    for (const auto& [id, rail] : s.rails) {
        const auto points = railPolyline(rail.curve(), true);
        for (std::size_t i = 0; i + 1 < points.size(); ++i)
            scene.segments.push_back({points[i], points[i + 1], kRailColour, true, 0});
    }
    for (std::size_t k = 0; k < sys.knotCount(); ++k)
        if (sys.fixed[k])
            scene.heldKnots.push_back(sys.worldPosition(k));

    if (colourBy == "piece") {
        for (const auto& [id, piece] : s.pieces)
            scene.legend.push_back(
                {piece.name.empty() ? toString(id) : piece.name, toSrgb(piece.colour)});
    } else {
        scene.legend.push_back({"0 N", tensionColour(0)});
        scene.legend.push_back(
            {formatNumber(std::round(scene.maxTension * 1000) / 1000) + " N", tensionColour(1)});
        scene.legend.push_back({"slack", kSlackColour});
    }
    scene.title = "netsculpt - " + thousands(s.pieces.size()) +
                  (s.pieces.size() == 1 ? " piece, " : " pieces, ") + thousands(sys.knotCount()) +
                  " knots, " + thousands(sys.barCount()) + " bars, " +
                  (relaxed ? "relaxed" : "not relaxed");

    bool first = true;
    const auto grow = [&](const Vec3& p) {
        if (first) {
            scene.lo = scene.hi = p;
            first = false;
        }
        scene.lo = {std::min(scene.lo.x, p.x), std::min(scene.lo.y, p.y),
                    std::min(scene.lo.z, p.z)};
        scene.hi = {std::max(scene.hi.x, p.x), std::max(scene.hi.y, p.y),
                    std::max(scene.hi.z, p.z)};
    };
    for (const auto& seg : scene.segments) {
        grow(seg.a);
        grow(seg.b);
    }
    for (const Vec3& p : scene.heldKnots)
        grow(p);
    return scene;
}

} // namespace netsculpt::io
