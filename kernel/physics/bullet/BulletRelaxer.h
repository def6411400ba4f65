#pragma once
// The cross-check backend (DESIGN.md "Physics", issue 6): the compiled mass-spring system relaxed
// by Bullet's deformable-body solver (btDeformableMultiBodyDynamicsWorld, implicit backward Euler,
// btDeformableMassSpringForce). Built only with NETSCULPT_WITH_BULLET (NETSCULPT_HAVE_BULLET is
// then defined); this header names no Bullet type, so it can be included anywhere.
//
// Why the deformable world and not btSoftBody in a btSoftRigidDynamicsWorld: a classic soft
// body link is a position-based constraint whose "linear stiffness" kLST in [0, 1] is a
// per-iteration correction weight, so its equilibrium depends on iteration counts and time step
// and no kLST reproduces EA. The deformable world's mass-spring force is a physical spring,
// f = k (|d| - l_rest) d/|d| with k in N/m, integrated implicitly: k = EA / l_eq maps one to one.
//
// How the two models differ, and what it means for agreement:
// - Tension and compression. Eq. 3 uses k_s when a bar is stretched and k_c =
//   compression_ratio k_s when it is not; a Bullet link has one stiffness both ways. Bullet gets
//   k_s (kTension). The equilibria coincide exactly when compression_ratio = 1, and also whenever
//   no bar ends up shorter than its rest length (a net hanging in tension everywhere). Where bars
//   are compressed (slack rope in reality) Bullet holds them up with the full k_s, so its shape is
//   stiffer there, and the project's residual of Bullet's shape stays at about
//   (k_s - k_c) |compression| / (m g) at those knots: Bullet cannot converge in the project's
//   sense, and relax() then stops with stopReason "stalled" (see BulletRelaxer::relax).
// - Per-link stiffness. btDeformableMassSpringForce holds one elastic stiffness for all the
//   links of the bodies it acts on. When every bar has the same kTension (one material, one bar
//   length) Bullet's class is used as is; otherwise a subclass that only replaces that one
//   number by kTension of each link (same force and force differential formulas) is used.
// - Mass. Bullet's nodes carry the knot masses of the system (kg), so gravity m_j g is the same;
//   fixed knots are Bullet nodes of zero mass (inverse mass 0 = pinned, a Dirichlet constraint of
//   the solver). Unlike the RK4 backend's fictitious masses these masses also set the dynamics,
//   which only changes the path, not the rest state.
// - Integration and damping. Bullet integrates M (v' - v) = dt F(x + dt v') (backward Euler) with
//   one Newton step per time step, a conjugate-gradient solve preconditioned by the mass matrix,
//   fixed knots projected out. With a time step far beyond the net's periods (the default) a
//   step is in effect a regularised Newton step on F(x) = 0, so the shape converges to the same
//   static state without physical damping; backward Euler's own dissipation removes the motion.
//   The result does not depend on the step or the damping, only the path does.
// - Precision: Bullet is linked in double precision (BT_USE_DOUBLE_PRECISION, the -float64
//   libraries), so positions are copied to and from Bullet without rounding.
//
// Determinism: Bullet's deformable solver runs on one thread; the same system and settings give
// the same shape bit for bit on the same machine and build.

#include "physics/Relaxer.h"

#include <cstdint>
#include <string_view>

namespace netsculpt {

/// Solver knobs of the Bullet backend. The defaults suit a static rest state; tests and the
/// benchmark may change them.
struct BulletSettings {
    /// First backward Euler step, s; 0 = automatic (a free fall of a tenth of the shortest bar).
    double initialTimeStep = 0;
    /// Longest step, s; 0 = automatic (100 times the longest pendulum period of the net, where a
    /// step is in effect a Newton step on F = 0).
    double maxTimeStep = 0;
    /// Switched evolution relaxation: the step grows as the residual falls and shrinks when it
    /// rises. false = every step is initialTimeStep.
    bool adaptiveTimeStep = true;
    /// Kinetic damping: all nodes are stopped after every step, so each step solves
    /// (M / dt^2 + K) dx = F (pseudo-transient continuation) instead of carrying momentum.
    bool kineticDamping = true;
    /// Newton iterations per Bullet step (Bullet's default is 1), >= 1.
    int newtonIterations = 1;
    /// Conjugate-gradient iterations per Newton iteration, >= 1 (Bullet's default is 300).
    int conjugateGradientIterations = 300;
    /// Damping of each link along its direction, N s/m (Bullet's mass-spring damping), >= 0.
    double linkDamping = 0;
};

/// Relaxes a MassSpringSystem with Bullet's deformable solver (see the file comment for how its
/// model differs from Eq. 3). name() and RelaxResult::backend are "bullet".
///
/// relax() honours RelaxOptions::tolerance (measured every checkInterval steps with the
/// project's own force function, at the material's stiffness), maxSeconds, maxSteps (Bullet
/// steps), cancel and progress. It ignores threads (Bullet's solver is serial), continuation
/// (a Newton step needs none) and wind (Bullet's mass-spring world has no matching load; a
/// wind option is refused with UserError rather than silently dropped).
///
/// stopReason is one of "converged", "time limit", "step limit", "cancelled", "diverged"
/// (a non-finite state; the last finite one is returned) or "stalled": Bullet's own model is at
/// rest (its residual, Eq. 3 with k_c = k_s, is below the tolerance) but the project's is not,
/// because bars are compressed and compression_ratio < 1; going on cannot help.
/// RelaxResult::residual is residual(system) at the returned positions; converged means it is
/// below the tolerance. forceEvaluations counts passes of Eq. 3 made by the checks.
class BulletRelaxer final : public Relaxer {
  public:
    explicit BulletRelaxer(const BulletSettings& settings = {});
    std::string_view name() const override { return "bullet"; }
    [[nodiscard]] RelaxResult relax(MassSpringSystem& system, const RelaxOptions& options) override;

    const BulletSettings& settings() const { return settings_; }

  private:
    BulletSettings settings_;
};

/// BulletRelaxer(settings).relax(system, options).
[[nodiscard]] RelaxResult relaxBullet(MassSpringSystem& system, const RelaxOptions& options = {},
                                      const BulletSettings& settings = {});

} // namespace netsculpt
