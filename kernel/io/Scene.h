#pragma once
// What the pictures and 3D exports draw: bars and rails as coloured segments, with a legend and
// a title, built once from a sculpture and its compiled system.

#include "geometry/Curve.h"
#include "model/Compiler.h"
#include "model/Sculpture.h"

#include <string>
#include <vector>

namespace netsculpt::io {

/// A display colour, sRGB components in [0, 1].
struct Rgb {
    double r = 0, g = 0, b = 0;
};

/// Linear RGB (model colours) to sRGB.
Rgb toSrgb(const Colour& linear);
/// sRGB to linear RGB (for glTF).
Colour toLinear(const Rgb& srgb);
/// The tension colour ramp at `fraction` in [0, 1] of the largest tension (blue - teal -
/// orange - red), sRGB.
Rgb tensionColour(double fraction);
inline constexpr Rgb kSlackColour{0.62, 0.62, 0.62};
inline constexpr Rgb kRailColour{0.13, 0.14, 0.17};
inline constexpr Rgb kBackground{0.975, 0.972, 0.96};

/// The points a rail is drawn and exported with: a polyline's own vertices; a spline sampled at
/// equal parameter steps, 64 per knot span and at least 256. A closed rail repeats its first
/// point at the end when `repeatFirst`.
std::vector<Vec3> railPolyline(const Curve& curve, bool repeatFirst);

struct SceneSegment {
    Vec3 a, b;
    Rgb colour;
    bool rail = false;
    std::uint32_t bar = 0; ///< bar index (bars only)
};

struct LegendEntry {
    std::string label;
    Rgb colour;
};

struct Scene {
    std::vector<SceneSegment> segments; ///< the bars, then the rails
    std::vector<Vec3> heldKnots;        ///< knots fixed to rails (drawn as dots)
    std::vector<double> tension;        ///< per bar, N (> 0 tension)
    double maxTension = 0;              ///< N, >= 0
    std::vector<LegendEntry> legend;    ///< pieces (colourBy piece) or the ramp's ends (tension)
    std::string colourBy;               ///< "piece" or "tension"
    std::string title;
    Vec3 lo, hi; ///< bounds of everything drawn, m
};

/// `colourBy` is "piece" or "tension" (UserError otherwise, listing both).
Scene buildScene(const Sculpture& s, const CompiledSculpture& c, const std::string& colourBy,
                 bool relaxed);

/// Whether bar b (rest length l_eq, current length l) is slack: shorter than its rest length by
/// more than 1e-9 relative (rounding of an unrelaxed start never counts).
bool isSlack(double length, double restLength);

} // namespace netsculpt::io
