#pragma once
// The part of a Newton run (NewtonRelaxer.cpp) that depends only on the topology of the system:
// kept by FastRelaxer between calls.

#include "geometry/Vec3.h"
#include "physics/Forces.h"
#include "physics/MassSpringSystem.h"
#include "physics/fast/HugePageArray.h"
#include "physics/fast/SupernodalCholesky.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace netsculpt {

/// The topology-dependent part of a run: the free numbering, the block pattern and its
/// factorization analysis, and the storage of a run (its force field, per-knot and per-bar
/// vectors, the Newton matrix): kept between calls for a system with the same topology, so that
/// a warm run (a drag step) allocates nothing and touches no fresh page.
struct NewtonAnalysis {
    std::vector<std::uint8_t> fixed;
    std::vector<std::uint32_t> barA, barB;

    std::vector<std::uint32_t> freeKnots;     ///< free index -> knot
    std::vector<std::int64_t> freeIndex;      ///< knot -> free index, -1 when fixed
    std::vector<std::int64_t> barPair;        ///< bar -> block pair, -1 when an end is fixed
    std::vector<std::array<std::uint32_t, 2>> pairs; ///< free indices of the blocks' nodes
    SupernodalCholesky cholesky;
    /// The mean k_s of the bars (N/m) of the system whose matrix cholesky last factorized
    /// successfully (0: none since the analysis): a later run takes chord steps with that factor
    /// only for a system about as stiff (RelaxOptions::reuseFactor).
    double factorStiffness = 0;
    /// The conjugate-gradient iterations the last step solved with that factor took (0: none
    /// yet): the factor ages along a drag, and past kRefreshAfter it is made anew.
    int reusedIterations = 0;

    // A run's storage (NewtonRun's members of the same names). Every run sets what it reads: its
    // law into the field (ForceField::setLaw), its start into the vectors.
    ForceField field;
    std::vector<Vec3> x, trial, force, step, bend, bendThird, bestX;
    std::vector<double> tension, kCompression, rhs, linearResidual, barTerm, weightOf,
        dampingUnit;
    std::vector<double> krylovX, krylovZ, krylovD, krylovQ; ///< NewtonRun::solveByPreviousFactor
    HugePageArray barBlock; ///< written whole by every assembly
    HugePageArray values;   ///< likewise

    bool matches(const MassSpringSystem& system) const {
        return system.fixed == fixed && system.barA == barA && system.barB == barB;
    }

    /// `checked`: the system's force field (built, so validated, by the caller).
    NewtonAnalysis(const MassSpringSystem& system, ForceField&& checked)
        : field(std::move(checked)) {
        analyse(system);
    }

    /// Analyses `system`'s topology (its force field is already in `field`), keeping the
    /// storage of the previous one where it is large enough (the factor's among it).
    void analyse(const MassSpringSystem& system);
};

} // namespace netsculpt
