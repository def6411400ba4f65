#pragma once
// The cross-check backend (DESIGN.md "Physics", issue 6): the compiled mass-spring system relaxed
// by Bullet's deformable-body solver: btDeformableMultiBodyDynamicsWorld, implicit backward
// Euler, a mass-spring force derived from btDeformableMassSpringForce. Built only with
// NETSCULPT_WITH_BULLET (NETSCULPT_HAVE_BULLET is then defined); this header names no Bullet
// type, so it can be included anywhere.
//
// Why the deformable world and not btSoftBody in a btSoftRigidDynamicsWorld: a classic soft-body
// link is a position-based constraint whose "linear stiffness" kLST in [0, 1] is a correction
// weight per solver iteration, so its rest shape depends on iteration counts and the time step
// and no kLST reproduces EA. The deformable world's mass-spring force is a physical spring,
// f = k (|d| - l_rest) d/|d| with k in N/m, integrated implicitly: k = EA / l_eq maps one to one.
//
// How Bullet's model differs from Eq. 3, and what it means for agreement:
// - Tension and compression. Eq. 3 uses k_s when a bar is stretched and k_c =
//   compression_ratio k_s when it is not; a Bullet link has one stiffness both ways, and gets
//   k_s (kTension). The rest shapes coincide when compression_ratio = 1, and also when no bar
//   ends up shorter than its rest length. Where bars are compressed (slack rope) Bullet holds
//   them up with the full k_s: its shape is an equilibrium of Eq. 3 only up to the force
//   (k_s - k_c)(l_eq - l) of each compressed bar, so the project's residual of Bullet's shape
//   stays near that force over the knot's weight (about 1 for real rope) and relax() stops with
//   "stalled". With slack bars a net can also have several rest shapes, and the two backends may
//   settle in different ones from the same start (tests/physics_bullet/BulletRelaxerTests.cpp).
// - Stiffness per link. btDeformableMassSpringForce holds one stiffness for all the links it acts
//   on; a net's bars differ (k = EA / l_eq per piece and column), so a subclass keeps one per
//   link. Its force is Bullet's formula. Its force differential (the matrix of the implicit step)
//   is Bullet's too, except that a compressed link's negative transverse term is left out until
//   the net is near rest: Bullet's conjugate-gradient solve gives up at the first direction of
//   negative curvature, which compressed links bring in. That changes the path, not the rest
//   shape.
// - Mass. Bullet's nodes carry the knot masses (kg), so the weight m_j g is the same; fixed knots
//   are nodes of zero mass (inverse mass 0 = pinned, projected out of the solve). The masses also
//   set Bullet's dynamics, which only changes the path.
// - Integration and damping. Each Bullet step solves M (v' - v) = dt F(x + dt v') (backward
//   Euler, Newton iterations, conjugate gradients preconditioned by the mass matrix). Between
//   steps every node is stopped (kinetic damping), so a step is (M / dt^2 + K) dx = F: with a
//   short step a damped motion, with a long one a Newton step on F = 0. The step grows as the
//   residual falls (switched evolution relaxation) and a stiff net goes through stiffness
//   continuation first, as the RK4 backend does. No physical damping is needed; the rest shape
//   does not depend on any of this.
// - Solver settings: not Bullet's defaults (BulletSettings; issue 6, measured with
//   netsculpt-bench-compare on the realistic rope, EA 2e5 N; figures in CPU seconds, README
//   "Performance"). Near the rest shape a step is a Newton step whose matrix couples stretching
//   (EA / l) with the shape modes (tension / l, spread over the rows), a condition number of
//   10^8 and more; conjugate gradients preconditioned by the masses need about 10^4 iterations to
//   solve it (measured per solve at full stiffness: 10,000-15,000 on a 2,000-knot tube, up to
//   35,000 on a 20,000-knot one). Bullet's limit of 300 leaves every such step inexact and
//   the residual hovers at 3e-5 .. 5e-3, never 1e-6. Bullet's stopping test at its tolerance
//   (machine epsilon) is met only in the soft stages, so a fixed limit is paid in full by every
//   stiff solve (3,000: the 2k tube converges in 16 s; 10,000: 4 s). Hence a limit of 100,000
//   and the test at 1e-7: each solve stops when it is accurate enough, after tens to hundreds of
//   iterations in the soft stages and what the step needs in the stiff ones (2k tube: 3.7 s;
//   the 20k tube, which never converged before: 142 s). Looser is slower on tubes (1e-6: 6 s),
//   tighter on slack sheets (1e-8: 76 s instead of 57, 1e-10: 104). Two Newton iterations
//   per step: Bullet starts a step's Newton iterations from an explicit prediction
//   (v = v_n + dt M^-1 F(x)), which a long step on a slack net throws far off, and a second
//   iteration corrects it: the 2k slack sheet with compression ratio 1 converges (57 s; with
//   one it still hovered at 2.5e-4 after 220 s), tubes take 10-20 % longer. A step is given at
//   most the iterations that fit in the time left (RelaxOptions::maxSeconds), so a long solve
//   does not overrun the time limit.
// - Precision: Bullet is linked in double precision (BT_USE_DOUBLE_PRECISION, the -float64
//   libraries), so positions go to and from Bullet without rounding.
//
// Determinism: Bullet's deformable solver runs on one thread; the same system and settings give
// the same shape bit for bit on the same build (tested).

#include "physics/Relaxer.h"

#include <string_view>

namespace netsculpt {

/// Solver knobs of the Bullet backend. The defaults suit a static rest state.
struct BulletSettings {
    /// First backward Euler step of each continuation stage, s; 0 = automatic (a free fall of a
    /// tenth of the shortest bar: at the initial geometry nothing else resists sideways motion).
    double initialTimeStep = 0;
    /// Longest step, s; 0 = automatic (100 times the net's longest pendulum period, where a step
    /// is in effect a Newton step on F = 0).
    double maxTimeStep = 0;
    /// Switched evolution relaxation: the step grows as the residual falls and shrinks when it
    /// rises. false = every step is initialTimeStep (or the automatic first step).
    bool adaptiveTimeStep = true;
    /// Kinetic damping: all nodes are stopped after every step. false = Bullet's dynamics carry
    /// momentum from step to step (slower to settle; for experiments).
    bool kineticDamping = true;
    /// Newton iterations per Bullet step, >= 1 (Bullet's default: 1; 2 lets slack nets converge,
    /// see the file comment).
    int newtonIterations = 2;
    /// Conjugate-gradient iterations per Newton iteration at most, >= 1 (Bullet's default: 300;
    /// each iteration is a pass over all links). Fewer when the solve meets
    /// conjugateGradientTolerance first, and when the time left would not allow them (the first
    /// step, before one has been timed, makes at most 300). Stiff nets need about 10^4 per solve
    /// near the rest shape (see the file comment).
    int conjugateGradientIterations = 100000;
    /// Bullet's stopping test for its conjugate-gradient solve of a step's linear system A x = b
    /// (btConjugateGradient, preconditioned by the mass matrix M): stop when
    /// r·M⁻¹r < tolerance · min(1, b·M⁻¹b), r the solve's residual; dimensionless. >= 0;
    /// 0 = never stop before conjugateGradientIterations. Bullet's default is machine epsilon
    /// (2.2e-16), which a stiff net never reaches.
    double conjugateGradientTolerance = 1e-7;
    /// Damping along each link, N s/m (Bullet's mass-spring damping), >= 0; 0 = none.
    double linkDamping = 0;
};

/// Relaxes a MassSpringSystem with Bullet's deformable solver (see the file comment for how its
/// model differs from Eq. 3). name() and RelaxResult::backend are "bullet".
///
/// relax() checks the residual after every Bullet step (one pass of Eq. 3 by the project's
/// force code, and one of Bullet's own model when the two differ; a Bullet step costs
/// newtonIterations solves of up to conjugateGradientIterations such passes each). It honours
/// RelaxOptions::tolerance (at the material's stiffness), maxSeconds (a step gets at most the
/// conjugate-gradient iterations that fit in the time left, at the rate the last steps made them;
/// the limit is checked between steps), cancel (checked between steps, so one step may run
/// over), maxSteps (Bullet steps), progress, continuation and continuationFactor. The first stage
/// is always the softest the RK4 backend allows (EA = 20 times the mean load per held knot), not
/// previewStiffnessScale: Newton steps need small strains more than a close start. threads is
/// ignored (Bullet's solver is serial). A wind with pressure > 0 is refused with UserError:
/// Bullet's world has no matching load.
///
/// The positions returned are, in the last stage, those with the lowest residual of Bullet's own
/// model (its rest shape); before it (a stop during continuation) the last state, a preview.
/// Fixed knots are never moved. stopReason is "converged" (residual of Eq. 3 below the
/// tolerance), "stalled" (Bullet's model is at rest, Eq. 3 is not: compressed bars with
/// compression_ratio < 1; going on cannot help), "time limit", "step limit", "cancelled" or
/// "diverged" (the step collapsed; the last finite state is returned). RelaxResult::residual is
/// residual(system) at the returned positions; forceEvaluations counts the passes of Eq. 3 made
/// by the checks.
class BulletRelaxer final : public Relaxer {
  public:
    /// Throws UserError naming the first invalid setting.
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
