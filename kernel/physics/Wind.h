#pragma once
// A steady, uniform wind acting on the rope of the net (an optional load of the relaxation).
// Each bar takes q * L_bar * (the part of the wind direction normal to the bar), where L_bar is
// its current length; half of it goes to each end knot. Wind parallel to a bar loads it not.

#include "geometry/Vec3.h"

namespace netsculpt {

struct Wind {
    Vec3 direction{1, 0, 0}; ///< where the wind blows to; any non-zero finite length (normalized)
    double pressure = 0;     ///< q in N per metre of rope, >= 0; 0 = no load
};

/// Throws UserError unless the direction is finite and non-zero and the pressure finite and
/// >= 0. Returns the direction normalized to unit length.
Vec3 validatedWindDirection(const Wind& wind);

} // namespace netsculpt
