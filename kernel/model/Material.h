#pragma once
// Per-piece rope material and display colour (DESIGN.md "Physics").

#include <array>
#include <optional>

namespace netsculpt {

struct Material {
    double stiffness = 2.0e5;       ///< EA, N; k_s = EA / l_eq. Must be > 0.
    double compressionRatio = 0.01; ///< k_c = compressionRatio * k_s. In [0, 1].
    double knotMass = 0.002;        ///< kg per knot. >= 0.
    double linearDensity = 0.006;   ///< kg per metre of rope. >= 0.
    /// N: the tension at which a bar of this rope breaks as it is knotted into the net, so with
    /// the knots' loss of strength already in it (a knot weakens rope: the straight rope's
    /// breaking load is not this). > 0 and finite; empty = not given, and then the report
    /// checks no strength for the piece (there is no default). Initialized here so that
    /// Material{ea, ratio, knot, rope} stays a complete initialization.
    std::optional<double> breakingLoad = std::nullopt;
    bool operator==(const Material&) const = default;
};

/// Display colour, linear RGB components in [0, 1].
struct Colour {
    double r = 0.85, g = 0.35, b = 0.2;
    bool operator==(const Colour&) const = default;
};

} // namespace netsculpt
