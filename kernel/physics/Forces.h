#pragma once
// The force of Eq. 3 of the paper on every knot of a mass-spring system, and what is derived
// from it: bar tensions, residuals, rail reactions, total weight.
//
//   F_j = m_j g + sum_i s k_ij (l_ij - l_eq,ij) (p_i - p_j) / |p_i - p_j|  (+ wind)      (Eq. 3)
//
// with k_ij = kTension when the bar is stretched (l > l_eq) and kCompression otherwise, and s a
// stiffness scale (1 = the material; continuation uses s < 1). A bar of zero current length
// has no direction and exerts no force.
//
// What is computed, bit for bit, whichever way: each bar's spring force (the same IEEE operations
// in a SIMD lane as in scalar code: Forces.cpp is compiled without floating-point contraction
// and spells out the two FMAs of |d|^2), and F_j = m_j g plus the forces of the bars of knot j
// added in increasing bar order (end a: +f, end b: -f, so the two ends get exactly opposite
// forces). Two ways compute it:
//  - the two-phase way (computeBars, then knotForce per knot): per-bar forces in an array, then a
//    gather per knot through the knot -> bar table. With wind, evaluate() takes this way;
//  - evaluate() without wind: one streaming pass over the bars in index order that adds each
//    bar's force straight into its ends' totals, a knot's total starting at m_j g just before
//    its first bar; no per-bar array. A thread takes a range of knots and walks the bars from
//    its knots' first to their last (bars at the edge of its range are computed by both
//    neighbours; each keeps only its own ends).
// Either way the result does not depend on the number of threads. The streaming pass suits the
// compiler's numbering (knots row by row, bars by their knot in the lower row: a knot's bars
// are a row apart at most); with threads it falls back to the two-phase way when their walks
// would overlap much (pieces joined across far-apart knot numbers).

#include "geometry/Vec3.h"
#include "physics/MassSpringSystem.h"
#include "physics/Wind.h"

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace netsculpt {

class ThreadPool;

/// The force function of one system, with its precomputed tables and scratch so that an
/// evaluation allocates nothing. It copies what it needs from the system at construction; the
/// system's positions are passed to each evaluation (a solver evaluates at trial positions).
class ForceField {
  public:
    /// Validates the system (array sizes, bar ends, rest lengths > 0, stiffness >= 0 with
    /// kTension > 0, masses > 0, gravity finite and non-zero, every free knot having a bar) and
    /// throws UserError naming the first offending knot or bar.
    explicit ForceField(const MassSpringSystem& system);

    /// Takes `system`'s masses, gravity, rest lengths and stiffnesses into this field, validated
    /// as the constructor validates them (UserError naming the first offending knot or bar), and
    /// keeps every table that depends only on the topology. `system` must have the knots, fixed
    /// flags and bars (ends) of the system the field was built from: a solver that relaxes edits
    /// of one topology (a drag) updates its field instead of building a new one. The field is
    /// then the one the constructor would build from `system`.
    void setLaw(const MassSpringSystem& system);
    /// Replaces every bar's compression stiffness (barCount() values, N/m at scale 1, finite and
    /// >= 0): a solver's staged law (see NewtonRelaxer.h).
    void setCompressionStiffness(std::span<const double> kCompression);

    std::size_t knotCount() const { return fixed_.size(); }
    std::size_t barCount() const { return restLength_.size(); }

    /// Sets the load evaluations use from now on: wind (empty = none; validated, UserError) and
    /// the stiffness scale s (> 0; 1 = the material).
    void setLoad(const std::optional<Wind>& wind, double stiffnessScale = 1.0);
    double stiffnessScale() const { return scale_; }
    /// With wind: takes the wind's load at `positions` (knotCount() entries) and keeps it, as a
    /// fixed load, in the evaluations that follow until thawWind(): a load with a potential
    /// (-its dot product with the positions), so a solver can measure an energy along a step.
    void freezeWind(std::span<const Vec3> positions);
    /// Evaluations take the wind at the positions they are given again (the default).
    void thawWind() { windFrozen_ = false; }
    /// out[j] = the change of the wind's load on knot j (N) when the knots at `positions` move
    /// by `move` (m), to first order: the wind's part of the force's Jacobian, which has no
    /// symmetric form (a load that turns with the bars). Fixed knots' `move` must be 0.
    void windChange(std::span<const Vec3> positions, std::span<const Vec3> move,
                    std::span<Vec3> out) const;
    /// The wind's load on knot j, N: the frozen one (or the last evaluation's).
    Vec3 knotWind(std::size_t j) const {
        Vec3 load{};
        if (hasWind_)
            for (std::uint32_t k = adjacencyStart_[j], e = adjacencyStart_[j + 1]; k < e; ++k)
                load += barWind_[adjacency_[k] >> 1];
        return load;
    }

    /// Phase 1 of an evaluation, bars [begin, end): each bar's force on its ends (spring of
    /// Eq. 3 and wind). tension, if not null, receives s k (l - l_eq) per bar in N (< 0:
    /// compression). positions has knotCount() entries.
    void computeBars(const Vec3* positions, std::size_t begin, std::size_t end,
                     double* tension = nullptr);

    /// Phase 2, after phase 1 for all bars: the total force F_j on knot j in N (Eq. 3).
    Vec3 knotForce(std::size_t j) const {
        Vec3 force = weight_[j];
        for (std::uint32_t k = adjacencyStart_[j], e = adjacencyStart_[j + 1]; k < e; ++k) {
            const std::uint32_t entry = adjacency_[k];
            const double sign = 1.0 - 2.0 * static_cast<double>(entry & 1u); // end a: +1, b: -1
            force += barForce_[entry >> 1] * sign;
        }
        if (hasWind_)
            for (std::uint32_t k = adjacencyStart_[j], e = adjacencyStart_[j + 1]; k < e; ++k)
                force += barWind_[adjacency_[k] >> 1];
        return force;
    }

    /// |F| / (m_j |g|) for the force F on knot j: the knot's residual (dimensionless).
    double residualOf(std::size_t j, const Vec3& force) const {
        return force.norm() * inverseWeight_[j];
    }

    /// The convergence measure of `force` (an evaluate() result): max over free knots of
    /// residualOf, +inf if one is not finite; the same bits as residual() of the system.
    double maxResidual(std::span<const Vec3> force) const;

    /// F_j for all knots: force[j] in N (fixed knots too). With a pool the work is split over its
    /// threads; the result is the same bit for bit (and the same as the two phases above).
    void evaluate(std::span<const Vec3> positions, std::span<Vec3> force,
                  ThreadPool* pool = nullptr);

    bool isFixed(std::size_t j) const { return fixed_[j] != 0; }
    /// The knots at the ends of bar b.
    std::uint32_t barEndA(std::size_t b) const { return endOffsets_[2 * b] / sizeof(Vec3); }
    std::uint32_t barEndB(std::size_t b) const { return endOffsets_[2 * b + 1] / sizeof(Vec3); }
    /// kTension of bar b in N/m at scale 1.
    double barTensionStiffness(std::size_t b) const { return kTension_[b]; }
    /// The bars of knot j (indices into the bars), in the fixed order of the sum.
    std::span<const std::uint32_t> barsOfKnot(std::size_t j) const;

  private:
    /// Each bar's wind load on each of its ends, bars [begin, end), into barWind_.
    void computeWind(const Vec3* positions, std::size_t begin, std::size_t end);
    /// The streaming pass of evaluate() for knots [begin, end) (see the top of this file).
    void streamKnots(const Vec3* positions, Vec3* force, std::size_t begin, std::size_t end) const;
    /// Bars [begin, end) of the streaming pass: adds their forces to those of their ends in
    /// [firstKnot, endKnot) (Checked) or to both ends (!Checked: the caller knows both are in),
    /// setting force[j] = m_j g first for knots j < endKnot from *nextKnot on as bars reach them.
    template <bool Checked>
    void streamBars(const Vec3* positions, Vec3* force, std::size_t begin, std::size_t end,
                    std::size_t firstKnot, std::size_t endKnot, std::size_t* nextKnot) const;
    /// The bars the streaming pass walks for knots [begin, end): [first, last).
    std::pair<std::size_t, std::size_t> streamBarRange(std::size_t begin, std::size_t end) const;

    // Hot per-bar data, struct of arrays for SIMD: 32 bytes per bar.
    /// Byte offsets of the knots at the ends of bar b in a Vec3 array (sizeof(Vec3) times the
    /// knot): end a at 2 b, end b at 2 b + 1.
    std::vector<std::uint32_t> endOffsets_;
    std::vector<double> restLength_;    ///< m
    std::vector<double> kTension_;      ///< N/m at scale 1
    std::vector<double> kCompression_;  ///< N/m at scale 1
    std::vector<Vec3> weight_;          ///< m_j g, N
    std::vector<double> inverseWeight_; ///< 1 / (m_j |g|), 1/N
    std::vector<std::uint8_t> fixed_;
    std::vector<std::uint32_t> adjacencyStart_; ///< knotCount()+1 offsets into adjacency_
    std::vector<std::uint32_t> adjacency_;      ///< 2 b + (0 at end a, 1 at end b), by knot
    std::vector<std::uint32_t> adjacentBars_;   ///< b, same order (for barsOfKnot)
    std::vector<Vec3> barForce_; ///< spring force of bar b on its end a (end b: the opposite), N
    std::vector<Vec3> barWind_;  ///< wind load of bar b on each of its ends, N (if wind)
    // The streaming pass's bounds (knot j's bars lie between its first and its last bar).
    std::vector<std::uint32_t> firstBarFrom_; ///< knotCount()+1: min first bar of knots >= j
    std::vector<std::uint32_t> lastBarTo_;    ///< knotCount(): 1 + max last bar of knots <= j
    std::vector<std::uint32_t> knotsBelow_;   ///< per bar: 1 + the largest end of bars <= b
    std::size_t unmaskedEnd_ = 0;             ///< bars before it do not touch the last knot
    double scale_ = 1.0;
    bool hasWind_ = false;
    bool windFrozen_ = false; ///< barWind_ kept from freezeWind()
    Vec3 windDirection_;      ///< unit
    double windPressure_ = 0; ///< N/m
};

/// Sum of m_j |g| over all knots, fixed ones included: N.
double totalWeight(const MassSpringSystem& system);

/// The wind's load on the whole net at the system's positions (the sum of its load on every
/// bar, half of which each end knot takes): N. What the rails carry beside the weight.
Vec3 totalWindForce(const MassSpringSystem& system, const Wind& wind);

/// F_j of Eq. 3 for every knot at the system's positions, at stiffness scale 1: N.
std::vector<Vec3> knotForces(const MassSpringSystem& system, const std::optional<Wind>& wind = {});

/// |F_j| / (m_j |g|) per knot at stiffness scale 1; 0 for fixed knots (see reactions()).
std::vector<double> knotResiduals(const MassSpringSystem& system,
                                  const std::optional<Wind>& wind = {});

/// The convergence measure: max over free knots of |F_j| / (m_j |g|) at stiffness scale 1
/// (0 when no knot is free; NaN never, +inf if a force is not finite).
double residual(const MassSpringSystem& system, const std::optional<Wind>& wind = {});

/// The free knot with the largest |F_j| / (m_j |g|) at stiffness scale 1 (the first one on a
/// tie; a non-finite residual counts as the largest), or -1 when no knot is free.
std::int64_t knotWithLargestResidual(const MassSpringSystem& system,
                                     const std::optional<Wind>& wind = {});

/// Per bar: k (l - l_eq) in N at stiffness scale 1; > 0 tension, < 0 compression.
std::vector<double> barTensions(const MassSpringSystem& system);

/// Per knot: the force the rail exerts on a fixed knot, -F_j, in N; zero for free knots. At
/// equilibrium they sum to (0, 0, totalWeight) for gravity (0, 0, -g), less totalWindForce.
std::vector<Vec3> reactions(const MassSpringSystem& system, const std::optional<Wind>& wind = {});

} // namespace netsculpt
