#include "physics/bullet/BulletRelaxer.h"

#include "model/Error.h"
#include "physics/Forces.h"

// Bullet's inline code trips GCC's flow-based -Wmaybe-uninitialized when inlined here (reported
// at its lines even though they are system headers); the warning is about Bullet, not us.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btDeformableGravityForce.h>
#include <BulletSoftBody/btDeformableMassSpringForce.h>
#include <BulletSoftBody/btDeformableMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

static_assert(sizeof(btScalar) == sizeof(double),
              "the Bullet backend needs Bullet in double precision (BT_USE_DOUBLE_PRECISION)");

namespace netsculpt {

namespace {

using Clock = std::chrono::steady_clock;

// Longest automatic time step: this many times the longest pendulum period of the net, so that
// the inertia term M / dt^2 of backward Euler is negligible next to the stiffness and a step
// acts as a Newton step on F(x) = 0.
constexpr double kStepPeriods = 100;
// First automatic time step: a knot falling freely for one step would fall this fraction of the
// shortest bar (g dt^2 = f l). At the initial geometry the bars are unstressed, so nothing but
// the inertia M / dt^2 resists sideways motion; a long first step would throw the net about.
constexpr double kFirstStepFall = 0.1;
// Step control (switched evolution relaxation): dt *= previous residual / residual, clamped.
constexpr double kStepShrink = 0.5;
constexpr double kStepGrowth = 4;
// A residual of Bullet's model above kBlowUpFactor times the stage's best is a blow-up: back to
// the best state, at rest, with a quarter of the step; a step below kMinStepFraction of the
// first: diverged.
constexpr double kBlowUpFactor = 1e3;
constexpr double kRejectGrowth = 10;
constexpr double kMinStepFraction = 1e-6;
// Newton's exact matrix (compressed links included) is used once the residual of Bullet's model
// is below this; a step with it that raises the residual is undone, and the positive matrix is
// used for the next kFullMatrixPause steps.
constexpr double kFullMatrixBelow = 1e-2;
constexpr std::int64_t kFullMatrixPause = 8;
// Continuation, as in the RK4 backend: soft stages stop at this residual of Bullet's model (they
// only bring the shape near the next stage's), and the first stage keeps EA at least this many
// times the mean load per held knot.
constexpr double kStageTolerance = 1e-3;
constexpr double kPreviewLoadFactor = 20;
// Conjugate-gradient iterations per solve allowed before one has been timed (Bullet's default
// limit); the time per iteration is measured on steps that make at least kTimedIterations; a step
// cut short by the time limit still makes kMinStepIterations.
constexpr double kUntimedIterations = 300;
constexpr std::int64_t kTimedIterations = 50;
constexpr int kMinStepIterations = 10;

btVector3 toBullet(const Vec3& v) { return {v.x, v.y, v.z}; }
Vec3 fromBullet(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

/// Bullet's mass-spring force (btDeformableMassSpringForce) with two changes, both needed for
/// a net and neither touching the equilibrium's model:
/// - a stiffness per link (kTension of bar b for link b) instead of one for all links; the
///   force is Bullet's formula, f = k (|d| - l_rest) d / |d|, the same both ways;
/// - its force differential (the stiffness matrix of the implicit step) is Bullet's, except that
///   the transverse "geometric" term k (|d| - l_rest) / |d| of a compressed link is dropped
///   rather than made negative. Bullet's conjugate-gradient solve gives up at the first direction
///   of negative curvature (btConjugateGradient::solve), which a compressed link brings into the
///   matrix as soon as dt^2 k exceeds the knot mass; a net in the folds of its initial geometry
///   has many. Only the path changes: the force, and so the rest state, are Bullet's.
/// Damping stays Bullet's (one coefficient along each link). Acts on one soft body whose link j
/// is bar j.
class NetSpringForce final : public btDeformableMassSpringForce {
  public:
    NetSpringForce(std::vector<btScalar> stiffness, btScalar damping)
        : btDeformableMassSpringForce(1.0, damping, true), stiffness_(std::move(stiffness)),
          damped_(damping > 0) {}

    // Without damping (the default) Bullet would still walk every link, normalising its
    // direction, in each conjugate-gradient product; skip that.
    void addScaledDampingForce(btScalar scale, TVStack& force) override {
        if (damped_)
            btDeformableMassSpringForce::addScaledDampingForce(scale, force);
    }
    void addScaledDampingForceDifferential(btScalar scale, const TVStack& dv, TVStack& df) override {
        if (damped_)
            btDeformableMassSpringForce::addScaledDampingForceDifferential(scale, dv, df);
    }
    void buildDampingForceDifferentialDiagonal(btScalar scale, TVStack& diagA) override {
        if (damped_)
            btDeformableMassSpringForce::buildDampingForceDifferentialDiagonal(scale, diagA);
    }
    double totalDampingEnergy(btScalar dt) override {
        return damped_ ? btDeformableMassSpringForce::totalDampingEnergy(dt) : 0.0;
    }

    void addScaledElasticForce(btScalar scale, TVStack& force) override {
        for (int i = 0; i < m_softBodies.size(); ++i) {
            const btSoftBody* body = m_softBodies[i];
            if (!body->isActive())
                continue;
            for (int j = 0; j < body->m_links.size(); ++j) {
                const btSoftBody::Link& link = body->m_links[j];
                const btVector3 dir = link.m_n[1]->m_q - link.m_n[0]->m_q;
                const btVector3 unit =
                    dir.norm() > SIMD_EPSILON ? dir.normalized() : btVector3(0, 0, 0);
                const btVector3 f = scale * stiffness_[std::size_t(j)] * (dir - unit * link.m_rl);
                force[link.m_n[0]->index] += f;
                force[link.m_n[1]->index] -= f;
            }
        }
    }

    void addScaledElasticForceDifferential(btScalar scale, const TVStack& dx, TVStack& df) override {
        ++products_;
        for (int i = 0; i < m_softBodies.size(); ++i) {
            const btSoftBody* body = m_softBodies[i];
            if (!body->isActive())
                continue;
            for (int j = 0; j < body->m_links.size(); ++j) {
                const btSoftBody::Link& link = body->m_links[j];
                const int a = link.m_n[0]->index, b = link.m_n[1]->index;
                const btVector3 dir = link.m_n[0]->m_q - link.m_n[1]->m_q;
                const btScalar length = dir.norm();
                if (!(length > SIMD_EPSILON))
                    continue;
                const btVector3 unit = dir / length;
                const btVector3 dxDiff = dx[a] - dx[b];
                const btScalar k = scale * stiffness_[std::size_t(j)];
                // Bullet's (l - l_rest) / l, but not below 0: see the class comment.
                const btScalar strainRatio =
                    fullMatrix_ ? (length - link.m_rl) / length : std::max(btScalar(0), (length - link.m_rl) / length);
                btVector3 d = -k * unit.dot(dxDiff) * unit;
                d += k * unit.dot(dxDiff) * strainRatio * unit;
                d -= k * strainRatio * dxDiff;
                df[a] += d;
                df[b] -= d;
            }
        }
    }

    double totalElasticEnergy(btScalar) override {
        double energy = 0;
        for (int i = 0; i < m_softBodies.size(); ++i) {
            const btSoftBody* body = m_softBodies[i];
            for (int j = 0; j < body->m_links.size(); ++j) {
                const btSoftBody::Link& link = body->m_links[j];
                const btScalar stretch = (link.m_n[1]->m_q - link.m_n[0]->m_q).norm() - link.m_rl;
                energy += 0.5 * stiffness_[std::size_t(j)] * stretch * stretch;
            }
        }
        return energy;
    }

    /// true: Bullet's force differential unchanged (Newton's exact matrix, indefinite where links
    /// are compressed); false: compressed links' transverse term dropped (positive semidefinite).
    void setFullMatrix(bool on) { fullMatrix_ = on; }
    /// Products with the force differential so far: one per conjugate-gradient iteration, plus
    /// one per solve for its start.
    std::int64_t products() const { return products_; }

  private:
    bool fullMatrix_ = false;
    std::int64_t products_ = 0;
    std::vector<btScalar> stiffness_; ///< N/m per link
    bool damped_;
};

/// Bullet's deformable solver with the knobs it keeps protected: Newton iterations per step and
/// the conjugate-gradient iteration limit and tolerance (btKrylovSolver's m_maxIterations and
/// m_tolerance, used as Bullet uses them).
class StaticDeformableSolver final : public btDeformableBodySolver {
  public:
    void configure(int newtonIterations, double conjugateGradientTolerance) {
        m_maxNewtonIterations = newtonIterations;
        m_newtonTolerance = 0; // run all of them
        m_cg.setTolerance(conjugateGradientTolerance);
    }
    void setConjugateGradientIterations(int iterations) { m_cg.m_maxIterations = iterations; }
};

/// Everything Bullet needs, torn down in the right order (the soft body leaves the world before
/// either is deleted; the world before its solvers, broadphase and dispatcher).
class BulletScene {
  public:
    BulletScene(const MassSpringSystem& system, const BulletSettings& settings);
    ~BulletScene() {
        if (world_ && body_)
            world_->removeSoftBody(body_.get());
    }
    BulletScene(const BulletScene&) = delete;
    BulletScene& operator=(const BulletScene&) = delete;

    /// One backward Euler step whose conjugate-gradient solves stop after at most `iterations`;
    /// returns its products with the force differential (its conjugate-gradient iterations, plus
    /// one per solve).
    std::int64_t step(double timeStep, int iterations) {
        bodySolver_.setConjugateGradientIterations(iterations);
        const std::int64_t before = springs_->products();
        world_->stepSimulation(timeStep, 0);
        return springs_->products() - before;
    }
    /// Every link stiffness times scale (stiffness continuation): the force is replaced by one
    /// with the scaled stiffness (the world keeps a pointer to it).
    void setStiffnessScale(double scale);
    void setFullMatrix(bool on) { springs_->setFullMatrix(on); }
    /// Kinetic damping: every node at rest (v_n = 0 for the next backward Euler step).
    void stopNodes() {
        for (int j = 0; j < body_->m_nodes.size(); ++j) {
            btSoftBody::Node& node = body_->m_nodes[j];
            node.m_v = node.m_vn = btVector3(0, 0, 0);
        }
    }
    /// Copies the node positions out; false if one is not finite.
    bool readPositions(std::vector<Vec3>& out) const {
        bool finite = true;
        for (int j = 0; j < body_->m_nodes.size(); ++j) {
            out[std::size_t(j)] = fromBullet(body_->m_nodes[j].m_x);
            finite = finite && out[std::size_t(j)].isFinite();
        }
        return finite;
    }
    /// Restores positions (and zero velocity) after a non-finite state.
    void writePositions(const std::vector<Vec3>& positions) {
        for (int j = 0; j < body_->m_nodes.size(); ++j) {
            btSoftBody::Node& node = body_->m_nodes[j];
            node.m_x = node.m_q = toBullet(positions[std::size_t(j)]);
            node.m_v = node.m_vn = btVector3(0, 0, 0);
        }
    }

  private:
    btSoftBodyRigidBodyCollisionConfiguration collisionConfiguration_;
    btCollisionDispatcher dispatcher_{&collisionConfiguration_};
    btDbvtBroadphase broadphase_;
    StaticDeformableSolver bodySolver_;
    btDeformableMultiBodyConstraintSolver constraintSolver_;
    std::unique_ptr<btDeformableMultiBodyDynamicsWorld> world_;
    std::unique_ptr<btDeformableGravityForce> gravity_;
    std::unique_ptr<NetSpringForce> springs_;
    std::unique_ptr<btSoftBody> body_;
    std::vector<btScalar> stiffness_; ///< kTension per link at scale 1, N/m
    double damping_ = 0;
};

void BulletScene::setStiffnessScale(double scale) {
    if (springs_)
        world_->removeForce(body_.get(), springs_.get());
    std::vector<btScalar> k(stiffness_);
    for (btScalar& v : k)
        v *= scale;
    springs_ = std::make_unique<NetSpringForce>(std::move(k), damping_);
    world_->addForce(body_.get(), springs_.get());
}

BulletScene::BulletScene(const MassSpringSystem& system, const BulletSettings& settings) {
    constraintSolver_.setDeformableSolver(&bodySolver_);
    bodySolver_.configure(settings.newtonIterations, settings.conjugateGradientTolerance);
    world_ = std::make_unique<btDeformableMultiBodyDynamicsWorld>(
        &dispatcher_, &broadphase_, &constraintSolver_, &collisionConfiguration_, &bodySolver_);
    const btVector3 g = toBullet(system.gravity);
    world_->setGravity(g);
    world_->getWorldInfo().m_gravity = g;
    // Implicit backward Euler. Bullet's implicit solve only works in projection mode (its KKT
    // preconditioner reports "implicit not implemented"): fixed nodes are projected out of the
    // conjugate-gradient solve. Strain limiting, which projection mode switches on, acts only
    // on face-rigid contacts, of which a net has none.
    world_->setImplicit(true);
    world_->setUseProjection(true);
    // Bullet's energy line search (setLineSearch) was tried: its backtracking gives up (no update
    // at all) below a step scale of 1e-8, which here happened at most steps; the step control in
    // relax() does better.
    world_->setLineSearch(false);

    const std::size_t knots = system.knotCount();
    std::vector<btVector3> x(knots);
    std::vector<btScalar> m(knots);
    for (std::size_t j = 0; j < knots; ++j) {
        x[j] = toBullet(system.position[j]);
        m[j] = system.fixed[j] ? 0.0 : system.mass[j]; // mass 0 = inverse mass 0 = pinned
    }
    body_ = std::make_unique<btSoftBody>(&world_->getWorldInfo(), int(knots), x.data(), m.data());
    for (std::size_t b = 0; b < system.barCount(); ++b)
        body_->appendLink(int(system.barA[b]), int(system.barB[b]), nullptr, false);
    // appendLink takes the current distance as rest length and flags the runtime constants for a
    // rebuild that would reset the rest lengths to current distances; do the rebuild now, then set
    // the bar lengths and clear the flag.
    body_->updateConstants();
    for (std::size_t b = 0; b < system.barCount(); ++b) {
        btSoftBody::Link& link = body_->m_links[int(b)];
        link.m_rl = system.restLength[b];
        link.m_c1 = link.m_rl * link.m_rl;
        link.m_bbending = 0;
    }
    body_->m_bUpdateRtCst = false;

    body_->m_cfg.collisions = 0; // no self-collision: Eq. 3 has none
    body_->m_cfg.drag = 0;
    body_->setActivationState(DISABLE_DEACTIVATION);
    world_->addSoftBody(body_.get());

    stiffness_.assign(system.kTension.begin(), system.kTension.end());
    damping_ = settings.linkDamping;
    gravity_ = std::make_unique<btDeformableGravityForce>(g);
    world_->addForce(body_.get(), gravity_.get());
    setStiffnessScale(1.0);
}

/// Largest height of the net (free knots below the highest fixed knot), m; at least a bar.
double netHeight(const MassSpringSystem& system) {
    double top = -std::numeric_limits<double>::infinity(), bottom = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < system.knotCount(); ++j) {
        if (system.fixed[j])
            top = std::max(top, system.position[j].z);
        bottom = std::min(bottom, system.position[j].z);
    }
    double longestBar = 0;
    for (double l : system.restLength)
        longestBar = std::max(longestBar, l);
    return std::max(std::isfinite(top) ? top - bottom : 0.0, longestBar);
}

void validate(const BulletSettings& s) {
    auto fail = [](const std::string& name, double value, const std::string& allowed) {
        throw UserError("bullet backend: " + name + " = " + formatNumber(value) + "; expected " + allowed);
    };
    if (!std::isfinite(s.initialTimeStep) || s.initialTimeStep < 0)
        fail("initialTimeStep", s.initialTimeStep, "0 (automatic) or a finite number of seconds > 0");
    if (!std::isfinite(s.maxTimeStep) || s.maxTimeStep < 0)
        fail("maxTimeStep", s.maxTimeStep, "0 (automatic) or a finite number of seconds > 0");
    if (s.newtonIterations < 1)
        fail("newtonIterations", s.newtonIterations, "a count >= 1");
    if (s.conjugateGradientIterations < 1)
        fail("conjugateGradientIterations", s.conjugateGradientIterations, "a count >= 1");
    if (!std::isfinite(s.conjugateGradientTolerance) || s.conjugateGradientTolerance < 0)
        fail("conjugateGradientTolerance", s.conjugateGradientTolerance,
             "a finite number >= 0 (0 = every conjugateGradientIterations)");
    if (!std::isfinite(s.linkDamping) || s.linkDamping < 0)
        fail("linkDamping", s.linkDamping, "a finite number >= 0");
}

/// The continuation's first stiffness scale: the softest the RK4 backend allows (Relaxer.cpp),
/// where the softest bar's EA is kPreviewLoadFactor times the mean load per held knot. Bullet's
/// steps are Newton steps, which need the first stage's strains modest, not the shape close:
/// a stiffer start (RelaxOptions::previewStiffnessScale) made stiff nets whose initial geometry
/// is far from their rest shape (a last row connected to a distant rail) cycle without end. More
/// stages cost little: each one starts near its rest shape and takes a few steps.
double firstStageScale(const MassSpringSystem& system, const RelaxOptions& options) {
    if (!options.continuation)
        return 1.0;
    double minAxialStiffness = std::numeric_limits<double>::infinity(); // EA, N
    for (std::size_t b = 0; b < system.barCount(); ++b)
        minAxialStiffness = std::min(minAxialStiffness, system.kTension[b] * system.restLength[b]);
    std::size_t held = 0;
    for (std::uint8_t f : system.fixed)
        held += f;
    const double meanHeldLoad = totalWeight(system) / double(std::max<std::size_t>(held, 1));
    const double floor = kPreviewLoadFactor * meanHeldLoad / minAxialStiffness;
    return std::min(1.0, floor);
}

/// Max over free knots of |F_j| / (m_j |g|) for the field at positions (+inf if not finite).
double maxResidual(ForceField& field, const std::vector<Vec3>& positions, std::vector<Vec3>& force) {
    field.evaluate(positions, force);
    double worst = 0;
    for (std::size_t j = 0; j < field.knotCount(); ++j) {
        if (field.isFixed(j))
            continue;
        const double r = field.residualOf(j, force[j]);
        if (!std::isfinite(r))
            return std::numeric_limits<double>::infinity();
        worst = std::max(worst, r);
    }
    return worst;
}

} // namespace

BulletRelaxer::BulletRelaxer(const BulletSettings& settings) : settings_(settings) {
    validate(settings_);
}

RelaxResult BulletRelaxer::relax(MassSpringSystem& system, const RelaxOptions& options) {
    const auto start = Clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    validate(options);
    if (options.wind) {
        validatedWindDirection(*options.wind);
        if (options.wind->pressure > 0)
            throw UserError("relax: backend \"bullet\" has no wind load (wind pressure " +
                            formatNumber(options.wind->pressure) + " N/m); use backend \"rk4\" for wind");
    }

    ForceField project(system); // validates the system
    const std::size_t knots = system.knotCount();
    for (std::size_t j = 0; j < knots; ++j)
        if (!system.position[j].isFinite())
            throw UserError("mass-spring system: knot " + std::to_string(j) + " has a non-finite position");
    std::size_t freeCount = 0;
    for (std::uint8_t f : system.fixed)
        freeCount += f ? 0 : 1;
    if (freeCount > 0 && freeCount == knots)
        throw UserError("mass-spring system: no knot is fixed, so the net has no equilibrium (it would fall)");

    // Bullet's own model, Eq. 3 with k_c = k_s: what Bullet actually drives to zero. It steers the
    // time step and the stages and tells a stall (Bullet at rest, Eq. 3 not) apart.
    std::unique_ptr<ForceField> ownModel;
    if (system.kCompression != system.kTension) {
        MassSpringSystem copy = system;
        copy.kCompression = copy.kTension;
        ownModel = std::make_unique<ForceField>(copy);
    }

    std::vector<Vec3> positions = system.position, force(knots);
    std::int64_t evaluations = 0, steps = 0;
    auto projectResidual = [&] { ++evaluations; return maxResidual(project, positions, force); };
    auto ownResidual = [&](double projectValue) {
        if (!ownModel)
            return projectValue;
        ++evaluations;
        return maxResidual(*ownModel, positions, force);
    };

    RelaxResult result;
    result.backend = "bullet";
    std::string stopReason;
    double scale = 1.0;
    if (freeCount == 0 || projectResidual() < options.tolerance)
        stopReason = "converged";
    else
        scale = firstStageScale(system, options);
    double stageFactor = 1.0;
    if (scale < 1.0) {
        const double stages = std::ceil(std::log(1.0 / scale) / std::log(options.continuationFactor) - 1e-9);
        stageFactor = std::pow(1.0 / scale, 1.0 / stages);
    }

    const double g = std::sqrt(system.gravity.dot(system.gravity));
    double shortestBar = std::numeric_limits<double>::infinity();
    for (double l : system.restLength)
        shortestBar = std::min(shortestBar, l);
    const double maxStep = settings_.maxTimeStep > 0
                               ? settings_.maxTimeStep
                               : kStepPeriods * 2 * std::numbers::pi * std::sqrt(netHeight(system) / g);
    const double firstStep = std::min(maxStep, settings_.initialTimeStep > 0
                                                   ? settings_.initialTimeStep
                                                   : std::sqrt(kFirstStepFall * shortestBar / g));
    const double minStep = firstStep * kMinStepFraction;
    double step = firstStep;

    std::unique_ptr<BulletScene> scene;
    if (stopReason.empty())
        scene = std::make_unique<BulletScene>(system, settings_);

    RelaxProgress progress;
    double lastProgress = -std::numeric_limits<double>::infinity();
    auto report = [&](double residualNow, double now) {
        progress.residual = residualNow;
        progress.steps = steps;
        progress.seconds = now;
        progress.stiffnessScale = scale;
        progress.estimatedSecondsLeft = -1;
        if (options.progress)
            options.progress(progress);
    };

    // The state returned: in the last stage the lowest residual of Bullet's model seen (its rest
    // shape, which is what a cross-check wants even where Eq. 3 judges it worse than a state on
    // the way); before the last stage, the last state (the shape is then only a preview).
    std::vector<Vec3> best = positions;
    double bestResidual = std::numeric_limits<double>::infinity();
    // The restart state after a blow-up: the lowest residual of Bullet's model in the stage.
    std::vector<Vec3> restState = positions;
    double restResidual = 0;
    // The state the last step started from, to undo a step made with the exact matrix.
    std::vector<Vec3> accepted = positions;
    double acceptedResidual = 0;
    std::int64_t fullMatrixFrom = 0; // steps before this one use the positive matrix
    auto beginStage = [&] {
        scene->setStiffnessScale(scale);
        project.setLoad(std::nullopt, scale);
        if (ownModel)
            ownModel->setLoad(std::nullopt, scale);
        restResidual = acceptedResidual = ownResidual(projectResidual());
        restState = accepted = positions;
        bestResidual = std::numeric_limits<double>::infinity();
    };
    if (stopReason.empty())
        beginStage();

    // Seconds per conjugate-gradient iteration, measured on the last step that made enough of
    // them to time; 0 = not known yet.
    double secondsPerIteration = 0;
    while (stopReason.empty()) {
        const bool fullMatrix = acceptedResidual < kFullMatrixBelow && steps >= fullMatrixFrom;
        scene->setFullMatrix(fullMatrix);
        // A step's solve may need many conjugate-gradient iterations (thousands on a stiff net);
        // the time limit is checked between steps, so a step gets at most what fits in the time
        // left (the last one is cut short rather than overrunning the limit), and until a step
        // has been timed, Bullet's default.
        const double before = seconds();
        const double fit = secondsPerIteration > 0
                               ? std::max(0.0, options.maxSeconds - before) / secondsPerIteration /
                                     settings_.newtonIterations // per solve
                               : kUntimedIterations;
        const int iterations = int(std::min(double(settings_.conjugateGradientIterations),
                                            std::max(double(kMinStepIterations), fit)));
        const std::int64_t made = scene->step(step, iterations);
        if (made >= kTimedIterations)
            secondsPerIteration = (seconds() - before) / double(made);
        ++steps;
        if (settings_.kineticDamping)
            scene->stopNodes();
        const bool finite = scene->readPositions(positions);
        const double r = finite ? projectResidual() : std::numeric_limits<double>::infinity();
        const double own = std::isfinite(r) ? ownResidual(r) : r;
        if (!(own <= kBlowUpFactor * restResidual)) {
            // Blow-up (or not finite): back to the stage's best state, at rest, shorter step.
            scene->writePositions(restState);
            positions = accepted = restState;
            acceptedResidual = restResidual;
            step *= 0.25;
            if (fullMatrix)
                fullMatrixFrom = steps + kFullMatrixPause;
            if (step < minStep) {
                stopReason = "diverged";
                break;
            }
        } else if (own > kRejectGrowth * acceptedResidual) {
            // Much worse than the state the step started from: undo it, retry with half the step.
            scene->writePositions(accepted);
            positions = accepted;
            step *= 0.5;
            if (fullMatrix)
                fullMatrixFrom = steps + kFullMatrixPause;
        } else if (fullMatrix && own > acceptedResidual) {
            // The exact matrix did worse than the state it started from (a compressed link made
            // it indefinite): undo the step, go on with the positive matrix for a while.
            scene->writePositions(accepted);
            positions = accepted;
            fullMatrixFrom = steps + kFullMatrixPause;
        } else {
            if (own < restResidual) {
                restResidual = own;
                restState = positions;
            }
            if (scale < 1.0 || own < bestResidual) {
                bestResidual = own;
                best = positions;
            }
            if (scale < 1.0) {
                if (own < std::max(options.tolerance, kStageTolerance)) {
                    // Next continuation stage: stiffen, go on from the same positions.
                    scale = scale * stageFactor > 0.999999 ? 1.0 : scale * stageFactor;
                    beginStage();
                    continue;
                }
            } else if (r < options.tolerance) {
                stopReason = "converged";
                break;
            } else if (ownModel && own < options.tolerance) {
                stopReason = "stalled";
                break;
            }
            // Switched evolution relaxation: the step grows as the residual falls (a Newton step
            // in the limit) and shrinks when it rises.
            if (settings_.adaptiveTimeStep)
                step = std::min(maxStep, step * std::clamp(acceptedResidual / own, kStepShrink, kStepGrowth));
            accepted = positions;
            acceptedResidual = own;
        }
        const double now = seconds();
        if (options.cancel && options.cancel->load(std::memory_order_relaxed))
            stopReason = "cancelled";
        else if (now >= options.maxSeconds)
            stopReason = "time limit";
        else if (options.maxSteps >= 0 && steps >= options.maxSteps)
            stopReason = "step limit";
        if (now - lastProgress >= options.progressInterval) {
            report(std::isfinite(r) ? r : acceptedResidual, now);
            lastProgress = now;
        }
    }

    for (std::size_t j = 0; j < knots; ++j)
        if (!system.fixed[j])
            system.position[j] = best[j];
    scale = 1.0;
    result.residual = residual(system);
    result.converged = result.residual < options.tolerance;
    result.stopReason = stopReason;
    result.steps = steps;
    result.forceEvaluations = evaluations + 1;
    result.seconds = seconds();
    report(result.residual, result.seconds);
    return result;
}

RelaxResult relaxBullet(MassSpringSystem& system, const RelaxOptions& options,
                        const BulletSettings& settings) {
    return BulletRelaxer(settings).relax(system, options);
}

} // namespace netsculpt
