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
// An evaluation has two passes over flat arrays: each bar's spring force (and wind load) is
// computed once into a per-bar array (phase 1), then each knot sums its bars (phase 2) in a
// fixed order, from a knot -> bar table built once. Each pass can be shared out among threads;
// nothing depends on how, so the result is bit-identical whatever the number of threads. The
// two ends of a bar get exactly opposite spring forces (negation is exact).

#include "geometry/Vec3.h"
#include "physics/MassSpringSystem.h"
#include "physics/Wind.h"

#include <cstdint>
#include <optional>
#include <span>
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

    std::size_t knotCount() const { return fixed_.size(); }
    std::size_t barCount() const { return bars_.size(); }

    /// Sets the load evaluations use from now on: wind (empty = none; validated, UserError) and
    /// the stiffness scale s (> 0; 1 = the material).
    void setLoad(const std::optional<Wind>& wind, double stiffnessScale = 1.0);
    double stiffnessScale() const { return scale_; }

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

    /// Both phases for all knots: force[j] = F_j in N (fixed knots too). With a pool the two
    /// phases are split over its threads; the result is the same bit for bit.
    void evaluate(std::span<const Vec3> positions, std::span<Vec3> force,
                  ThreadPool* pool = nullptr);

    bool isFixed(std::size_t j) const { return fixed_[j] != 0; }
    /// The knots at the ends of bar b.
    std::uint32_t barEndA(std::size_t b) const { return bars_[b].a; }
    std::uint32_t barEndB(std::size_t b) const { return bars_[b].b; }
    /// kTension of bar b in N/m at scale 1.
    double barTensionStiffness(std::size_t b) const { return bars_[b].kTension; }
    /// The bars of knot j (indices into the bars), in the fixed order of the sum.
    std::span<const std::uint32_t> barsOfKnot(std::size_t j) const;

  private:
    /// Hot per-bar data, 32 bytes.
    struct Bar {
        std::uint32_t a, b;  ///< end knots
        double restLength;   ///< m
        double kTension;     ///< N/m at scale 1
        double kCompression; ///< N/m at scale 1
    };
    static_assert(sizeof(Bar) == 32);

    std::vector<Bar> bars_;
    std::vector<Vec3> weight_;          ///< m_j g, N
    std::vector<double> inverseWeight_; ///< 1 / (m_j |g|), 1/N
    std::vector<std::uint8_t> fixed_;
    std::vector<std::uint32_t> adjacencyStart_; ///< knotCount()+1 offsets into adjacency_
    std::vector<std::uint32_t> adjacency_;      ///< 2 b + (0 at end a, 1 at end b), by knot
    std::vector<std::uint32_t> adjacentBars_;   ///< b, same order (for barsOfKnot)
    std::vector<Vec3> barForce_; ///< spring force of bar b on its end a (end b: the opposite), N
    std::vector<Vec3> barWind_;  ///< wind load of bar b on each of its ends, N (if wind)
    double scale_ = 1.0;
    bool hasWind_ = false;
    Vec3 windDirection_;      ///< unit
    double windPressure_ = 0; ///< N/m
};

/// Sum of m_j |g| over all knots, fixed ones included: N.
double totalWeight(const MassSpringSystem& system);

/// F_j of Eq. 3 for every knot at the system's positions, at stiffness scale 1: N.
std::vector<Vec3> knotForces(const MassSpringSystem& system, const std::optional<Wind>& wind = {});

/// |F_j| / (m_j |g|) per knot at stiffness scale 1; 0 for fixed knots (see reactions()).
std::vector<double> knotResiduals(const MassSpringSystem& system,
                                  const std::optional<Wind>& wind = {});

/// The convergence measure: max over free knots of |F_j| / (m_j |g|) at stiffness scale 1
/// (0 when no knot is free; NaN never, +inf if a force is not finite).
double residual(const MassSpringSystem& system, const std::optional<Wind>& wind = {});

/// Per bar: k (l - l_eq) in N at stiffness scale 1; > 0 tension, < 0 compression.
std::vector<double> barTensions(const MassSpringSystem& system);

/// Per knot: the force the rail exerts on a fixed knot, -F_j, in N; zero for free knots. At
/// equilibrium without wind they sum to (0, 0, totalWeight) for gravity (0, 0, -g).
std::vector<Vec3> reactions(const MassSpringSystem& system, const std::optional<Wind>& wind = {});

} // namespace netsculpt
