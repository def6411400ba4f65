#pragma once
// Per-piece rope material and display colour (DESIGN.md "Physics").

#include <array>

namespace netsculpt {

struct Material {
    double stiffness = 2.0e5;       ///< EA, N; k_s = EA / l_eq. Must be > 0.
    double compressionRatio = 0.01; ///< k_c = compressionRatio * k_s. In [0, 1].
    double knotMass = 0.002;        ///< kg per knot. >= 0.
    double linearDensity = 0.006;   ///< kg per metre of rope. >= 0.
    bool operator==(const Material&) const = default;
};

/// Display colour, linear RGB components in [0, 1].
struct Colour {
    double r = 0.85, g = 0.35, b = 0.2;
    bool operator==(const Colour&) const = default;
};

} // namespace netsculpt
