#pragma once
// The independent parts of a mass-spring system: its free knots in connected components, two free
// knots being connected when a bar joins them (a fixed knot joins nothing: it does not move).
// Pieces hung from rails of their own are such parts, and so are nets that share only rails:
// each has an equilibrium of its own, found without the others. FastRelaxer relaxes them one by
// one, so that each takes its own Newton steps (a part that creeps no longer holds back the
// steps and the factorizations of the others) and a part an edit did not touch, still in
// equilibrium, costs nothing.
#include "physics/MassSpringSystem.h"

#include <cstdint>
#include <vector>

namespace netsculpt {

/// The free knots of each connected component, in increasing knot order; the components in the
/// order of their first knot. Empty when the system's arrays do not agree in size or a bar's end
/// is not a knot (the caller's validation names the problem).
std::vector<std::vector<std::uint32_t>> freeComponents(const MassSpringSystem& system);

/// Some free knots as a system of their own: them and every other knot their bars reach (held
/// in the part: for a component, fixed knots only), and the bars with an end among them, both
/// in the whole system's order (so each knot's bars are summed in the same order, and its force
/// has the same bits, in either system). A component is such a set (FastRelaxer relaxes parts
/// each as a system of its own), and so is a region of knots still out of balance (FocusRegion.h).
struct Part {
    MassSpringSystem system;
    std::vector<std::uint32_t> knotOf; ///< the whole system's knot for each of the part's knots
    std::vector<std::uint32_t> barOf;  ///< the whole system's bar for each of the part's bars
};

/// The part of `system` whose free knots are `freeKnots` (one entry of freeComponents(), or
/// any set of free knots: the others their bars reach are held).
/// `scratch` is a knot-indexed work array (any content; resized as needed).
Part extractPart(const MassSpringSystem& system, const std::vector<std::uint32_t>& freeKnots,
                 std::vector<std::int64_t>& scratch);

} // namespace netsculpt
