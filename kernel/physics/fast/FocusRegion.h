#pragma once
// Where a relaxation is still going on: the knots of a net that are out of balance when most of
// it is already in equilibrium. Near the end of a run at the rope's stiffness, a net's parts
// converge at different rates: in the installation the core, the canopy and most of the banner
// are in balance within about 300 iterations, while the banner's free edge creeps for a thousand
// more (docs/performance.md), and every one of those iterations factorizes the whole part. Once
// few knots are left out of balance, FastRelaxer relaxes them and a few rings of their neighbours
// as a system of their own (the rest held where it is), then the whole again from there, which
// takes the few iterations its boundary needs. Internal to kernel/physics/fast.
#include "physics/Forces.h"
#include "physics/fast/Components.h"
#include "physics/MassSpringSystem.h"

#include <cstdint>
#include <span>
#include <vector>

namespace netsculpt::newton {

/// A system with fewer free knots than this is relaxed whole to the end: a region's own analysis
/// and its boundary's iterations would cost about what they save.
constexpr std::size_t kFocusMinKnots = 1000;
/// In any stage, once it has taken this many iterations since its start or its last region: one
/// that converges quadratically takes fewer, and a region would cost it its boundary's iterations
/// for nothing. At once, though, in the material's last stage when its mixed iterations stall
/// (NewtonRun.h, kMixedPatience): their full steps then leave the residual where it was, a few
/// hundred knots of a slack piece's collapsed edges out of balance (the installation's banner at
/// 6.3e-4 of a knot's weight for five iterations after its last stage's first three), and the
/// energy steps after them creep with the whole net factorized each time
/// (NewtonStatistics::stallFocusRegions).
constexpr int kFocusAfter = 20;
/// The region: the knots out of balance and this many rings of their neighbours ...
constexpr int kFocusRings = 6;
/// ... taken on its own when it holds at most this share of the free knots ...
constexpr double kFocusShare = 0.5;
/// ... or in a stage softer than the material's (a slack net's soft and intermediate stages,
/// relaxed at the stage's stiffness) this share. There the imbalance is spread over the net until
/// late in the stage (half the slack 100x200 sheet's knots: regions of half the net took it from
/// 149 to 318 iterations), and then hovers in a few places while the whole still factorizes at
/// every iteration (in the installation's core and bell, 7 to 80 knots of 20,200 for the last 40
/// iterations of its soft stage). The region held at its boundary may lead the stage to another
/// of a slack net's equilibria (docs/performance.md).
constexpr double kSoftFocusShare = 0.1;
/// The region is relaxed to this share of the tolerance, so that the whole, from there, has only
/// its boundary to settle; a region's own regions to the same (halved again at each level, a
/// banner's region three levels down crept for 19,000 steps towards 1.25e-7 of a knot's weight).
constexpr double kFocusTolerance = 0.5;
/// A region takes at most this many steps before the whole goes on (a region creeps at about a
/// millisecond per step where the whole would take ten or more).
constexpr std::int64_t kFocusMaxSteps = 2000;

/// The free knots of a region to relax on its own, in increasing order: those whose residual in
/// `force` (ForceField::evaluate at the current positions) is at least `tolerance`, and
/// kFocusRings rings of their free neighbours (knots a bar joins to the region). Empty when the
/// system has fewer than kFocusMinKnots free knots (`freeKnots`) or the region would hold more
/// than `share` of them.
std::vector<std::uint32_t> focusRegion(const ForceField& field, std::span<const Vec3> force,
                                       std::span<const std::uint32_t> freeKnots, double tolerance,
                                       double share = kFocusShare);

/// The region `region` (focusRegion()) as a system of its own (extractPart: the knots its bars
/// reach held) under its stage's law: each bar's compression stiffness max(k_c, blend k_s), and
/// both stiffnesses times the stage's `scale`, so that scale 1 of the part is the stage. `scratch`:
/// as for extractPart.
Part regionSystem(const MassSpringSystem& system, const std::vector<std::uint32_t>& region,
                  double blend, double scale, std::vector<std::int64_t>& scratch);

} // namespace netsculpt::newton
