// The Bullet cross-check backend (kernel/physics/bullet/BulletRelaxer.h): its shape against the
// RK4 backend's on four sculptures built with the model's edits, and its contract as a Relaxer.

#include "HangGuard.h"
#include "physics_bullet/Sculptures.h"

#include "model/Error.h"
#include "physics/Forces.h"
#include "physics/Relaxer.h"
#include "physics/bullet/BulletRelaxer.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

using namespace netsculpt;
using namespace netsculpt::test;

namespace {

double maxDistance(const MassSpringSystem& a, const MassSpringSystem& b) {
    double d = 0;
    for (std::size_t j = 0; j < a.knotCount(); ++j)
        d = std::max(d, distance(a.position[j], b.position[j]));
    return d;
}

double height(const MassSpringSystem& s) {
    auto [low, high] = std::minmax_element(s.position.begin(), s.position.end(),
                                           [](const Vec3& a, const Vec3& b) { return a.z < b.z; });
    return high->z - low->z;
}

/// Eq. 3 as Bullet models it: the same system with k_c = k_s, judged by the project's force code.
double symmetricResidual(const MassSpringSystem& s) {
    MassSpringSystem copy = s;
    copy.kCompression = copy.kTension;
    return residual(copy);
}

/// Largest l_eq - l over the bars (0 if none is compressed), m.
double maxCompression(const MassSpringSystem& s) {
    double c = 0;
    for (std::size_t b = 0; b < s.barCount(); ++b)
        c = std::max(c, s.restLength[b] - distance(s.position[s.barA[b]], s.position[s.barB[b]]));
    return c;
}

/// max over free knots of |sum over the knot's compressed bars of (k_s - k_c)(l_eq - l)| / (m g):
/// how far apart Eq. 3 and Bullet's model (k_c = k_s) can judge the same shape.
double compressionForceGap(const MassSpringSystem& s) {
    std::vector<Vec3> gap(s.knotCount());
    for (std::size_t b = 0; b < s.barCount(); ++b) {
        const Vec3 d = s.position[s.barB[b]] - s.position[s.barA[b]];
        const double l = d.norm();
        if (l >= s.restLength[b] || l == 0)
            continue;
        const Vec3 f = d * ((s.kTension[b] - s.kCompression[b]) * (l - s.restLength[b]) / l);
        gap[s.barA[b]] += f;
        gap[s.barB[b]] -= f;
    }
    const double g = s.gravity.norm();
    double worst = 0;
    for (std::size_t j = 0; j < s.knotCount(); ++j)
        if (!s.fixed[j])
            worst = std::max(worst, gap[j].norm() / (s.mass[j] * g));
    return worst;
}

using Builder = std::function<CrossCheckSculpture(const Material&)>;

std::vector<Builder> fourSculptures(double barSpread) {
    return {
        [](const Material& m) { return tubeOnRing(m); },
        [=](const Material& m) { return sheetBetweenRails(m, 1, barSpread); },
        [](const Material& m) { return tubeBetweenRings(m); },
        [=](const Material& m) { return gearStack(m, 1, barSpread); },
    };
}

/// Convergence and step limits decide these tests, not the time limit.
RelaxOptions options(double tolerance) {
    RelaxOptions o;
    o.tolerance = tolerance;
    o.maxSeconds = kHangGuardSeconds;
    return o;
}

} // namespace

// Soft rope (EA = 50 N, so both backends converge in well under a second) with
// compression_ratio = 1: Eq. 3 and Bullet's links are then the same model, and the two shapes are
// two approximations of one equilibrium. Each is within its residual r of it: every knot's force
// is at most r m g. A hanging net answers a load of a fraction e of its weight with displacements
// of about e H (a pendulum of length H tilted by e), so the shapes differ by about
// (r_rk4 + r_bullet) H; the bound allows 10 times that. Measured: 2e-7 to 7e-7 of H with
// r_rk4 = 1e-6.
TEST_CASE("bullet and rk4 agree where their models coincide", "[bullet][crosscheck]") {
    Material soft;
    soft.stiffness = 50;
    soft.compressionRatio = 1;
    const double rk4Tolerance = 1e-6, bulletTolerance = 1e-9;
    for (const Builder& build : fourSculptures(0)) {
        CrossCheckSculpture c = build(soft);
        MassSpringSystem byRk4 = c.compiled.system, byBullet = c.compiled.system;
        const RelaxResult rk4 = relaxRk4(byRk4, options(rk4Tolerance));
        const RelaxResult bullet = relaxBullet(byBullet, options(bulletTolerance));
        const double h = height(byBullet), d = maxDistance(byRk4, byBullet);
        const double bulletResidual = residual(byBullet);
        std::printf("[bullet tight] %-24s knots %4zu | rk4 %.2e in %.2f s | bullet %.2e in %.2f s, %lld steps | "
                    "max distance / height %.2e (H = %.3f m)\n",
                    c.name.c_str(), byRk4.knotCount(), rk4.residual, rk4.seconds, bulletResidual,
                    bullet.seconds, static_cast<long long>(bullet.steps), d / h, h);
        INFO(c.name);
        REQUIRE(rk4.converged);
        REQUIRE(bullet.converged);
        CHECK(bullet.backend == "bullet");
        CHECK(bullet.stopReason == "converged");
        // The project's own force function on Bullet's shape: below Bullet's tolerance.
        CHECK(bulletResidual < bulletTolerance);
        CHECK(bullet.residual == bulletResidual);
        CHECK(d / h < 10 * (rk4.residual + bulletResidual));
    }
}

// Realistic-ish rope: compression_ratio = 0.01 (slack rope hardly resists compression), EA =
// 200 N, and pieces of different bar lengths (so k = EA / l differs from link to link). Here the
// models differ in the bars that end up compressed, and with slack bars a net can have several
// rest shapes: from the same start the two backends may settle in different ones (measured: the
// tube between two rings and the gear stack have rest shapes 0.3 m apart, both equilibria of
// Eq. 3). So RK4 starts from Bullet's shape and finds the equilibrium of Eq. 3 next to it.
// - Bullet's shape is at rest in its own model: Eq. 3 with k_c = k_s, evaluated by the project's
//   force code, is below the tolerance.
// - The project's residual of Bullet's shape is then all due to its compressed bars: at most that
//   plus the gap (k_s - k_c)(l_eq - l) summed over each knot's compressed bars, / (m g).
// - From there RK4 moves the knots only as far as letting those bars go slack allows: a bar that
//   shortens by c lets its ends swing sideways by up to sqrt(2 l c), with c at most the largest
//   compression in RK4's shape; plus 10 r H for the residuals as above.
TEST_CASE("bullet's rest shape is next to one of eq. 3 where the models differ", "[bullet][crosscheck]") {
    Material rope;
    rope.stiffness = 200;
    rope.compressionRatio = 0.01;
    const double tolerance = 1e-6;
    for (const Builder& build : fourSculptures(0.2)) {
        CrossCheckSculpture c = build(rope);
        MassSpringSystem byBullet = c.compiled.system;
        const RelaxResult bullet = relaxBullet(byBullet, options(tolerance));
        MassSpringSystem byRk4 = byBullet;
        RelaxOptions warm = options(tolerance);
        warm.continuation = false;
        const RelaxResult rk4 = relaxRk4(byRk4, warm);

        const double h = height(byBullet), d = maxDistance(byRk4, byBullet);
        const double own = symmetricResidual(byBullet), gap = compressionForceGap(byBullet);
        const double compression = maxCompression(byRk4);
        double longestBar = 0;
        for (double l : byRk4.restLength)
            longestBar = std::max(longestBar, l);
        const double bound = std::sqrt(2 * longestBar * compression) + 10 * (rk4.residual + own) * h;
        std::printf("[bullet rope]  %-24s knots %4zu | bullet %s in %.2f s, own residual %.2e, eq. 3 residual %.2e "
                    "(gap %.2e) | rk4 from there moves %.2e m = %.2e H (bound %.2e m, max compression %.2e m)\n",
                    c.name.c_str(), byBullet.knotCount(), bullet.stopReason.c_str(), bullet.seconds, own,
                    bullet.residual, gap, d, d / h, bound, compression);
        INFO(c.name);
        REQUIRE((bullet.stopReason == "converged" || bullet.stopReason == "stalled"));
        REQUIRE(rk4.converged);
        CHECK(own < tolerance);
        CHECK(bullet.residual <= own + gap + 1e-9);
        CHECK(d <= bound);
    }
}

TEST_CASE("a bullet run that ends early returns a finite state and says why", "[bullet]") {
    Material soft;
    soft.stiffness = 50;
    soft.compressionRatio = 1;
    const CrossCheckSculpture c = tubeOnRing(soft);
    const MassSpringSystem start = c.compiled.system;

    SECTION("step limit") {
        MassSpringSystem s = start;
        RelaxOptions o = options(1e-12);
        o.maxSteps = 3;
        const RelaxResult r = relaxBullet(s, o);
        CHECK(r.stopReason == "step limit");
        CHECK(r.steps == 3);
        CHECK_FALSE(r.converged);
        CHECK(r.residual == residual(s));
        CHECK(maxDistance(s, start) > 0);
    }
    SECTION("time limit") {
        MassSpringSystem s = start;
        RelaxOptions o = options(1e-12);
        o.maxSeconds = 1e-9;
        const RelaxResult r = relaxBullet(s, o);
        CHECK(r.stopReason == "time limit");
        CHECK(r.steps == 1);
        CHECK(std::isfinite(r.residual));
    }
    SECTION("cancel") {
        MassSpringSystem s = start;
        std::atomic<bool> cancel{true};
        RelaxOptions o = options(1e-12);
        o.cancel = &cancel;
        int reports = 0;
        o.progress = [&](const RelaxProgress& p) {
            ++reports;
            CHECK(std::isfinite(p.residual));
        };
        const RelaxResult r = relaxBullet(s, o);
        CHECK(r.stopReason == "cancelled");
        CHECK(reports >= 1);
    }
    for (std::size_t j = 0; j < start.knotCount(); ++j)
        REQUIRE(start.position[j].isFinite());
}

// The realistic rope (EA 2e5 N) on a 480-knot tube: near the rest shape each step's linear solve
// needs thousands of conjugate-gradient iterations (BulletRelaxer.h, "Solver settings"). With
// the backend's defaults (Bullet's tolerance test at 1e-7, up to 100,000 iterations, 2 Newton
// iterations) it converges in 26 steps; with Bullet's own (300 iterations, machine epsilon, 1
// Newton iteration) it needed 1,817 (7 s), and has not converged after 10 times the defaults'.
TEST_CASE("bullet's default solver settings converge a stiff net that bullet's own leave hovering",
          "[bullet]") {
    const CrossCheckSculpture c = tubeOnRing(Material{}, 2);
    MassSpringSystem byDefaults = c.compiled.system, byBulletOwn = c.compiled.system;
    const RelaxResult defaults = relaxBullet(byDefaults, options(1e-6));
    REQUIRE(defaults.converged);
    CHECK(defaults.stopReason == "converged");

    BulletSettings bulletOwn;
    bulletOwn.conjugateGradientIterations = 300;
    bulletOwn.conjugateGradientTolerance = 2.220446049250313e-16;
    bulletOwn.newtonIterations = 1;
    RelaxOptions limited = options(1e-6);
    limited.maxSteps = 10 * defaults.steps;
    const RelaxResult own = relaxBullet(byBulletOwn, limited, bulletOwn);
    std::printf("[bullet stiff] tube on a ring, rope     knots %4zu | defaults %.2e in %lld steps, "
                "%.2f s | bullet's own settings %.2e after %lld steps, %.2f s\n",
                byDefaults.knotCount(), defaults.residual, static_cast<long long>(defaults.steps),
                defaults.seconds, own.residual, static_cast<long long>(own.steps), own.seconds);
    CHECK_FALSE(own.converged);
    CHECK(own.stopReason == "step limit");
}

// A step's solve gets only the conjugate-gradient iterations that fit in the time left: with no
// tolerance test and a limit of 10^6 iterations, one step on the stiff tube would take about half a
// minute; the run must still stop near its time limit.
TEST_CASE("a long bullet solve does not overrun the time limit", "[bullet]") {
    const CrossCheckSculpture c = tubeOnRing(Material{}, 2);
    MassSpringSystem s = c.compiled.system;
    BulletSettings endless;
    endless.conjugateGradientIterations = 1'000'000;
    endless.conjugateGradientTolerance = 0;
    RelaxOptions o = options(1e-6);
    o.maxSeconds = 0.3;
    const RelaxResult r = relaxBullet(s, o, endless);
    CHECK(r.stopReason == "time limit");
    CHECK(r.steps >= 2);
    CHECK(r.seconds < 3);
    CHECK(std::isfinite(r.residual));
}

TEST_CASE("bullet keeps fixed knots, is deterministic, and stops at once when already at rest", "[bullet]") {
    Material soft;
    soft.stiffness = 50;
    soft.compressionRatio = 1;
    const CrossCheckSculpture c = gearStack(soft, 1, 0.2);
    MassSpringSystem a = c.compiled.system, b = c.compiled.system;
    const RelaxResult ra = relaxBullet(a, options(1e-8));
    const RelaxResult rb = relaxBullet(b, options(1e-8));
    REQUIRE(ra.converged);
    CHECK(ra.steps == rb.steps);
    bool identical = true, fixedKept = true;
    for (std::size_t j = 0; j < a.knotCount(); ++j) {
        identical = identical && a.position[j] == b.position[j];
        if (a.fixed[j])
            fixedKept = fixedKept && a.position[j] == c.compiled.system.position[j];
    }
    CHECK(identical);
    CHECK(fixedKept);

    const MassSpringSystem rested = a;
    const RelaxResult again = relaxBullet(a, options(1e-8));
    CHECK(again.stopReason == "converged");
    CHECK(again.steps == 0);
    CHECK(maxDistance(a, rested) == 0);
}

TEST_CASE("bullet refuses what it cannot do, naming it", "[bullet]") {
    Material soft;
    soft.stiffness = 50;
    CrossCheckSculpture c = tubeOnRing(soft);
    BulletRelaxer relaxer;
    CHECK(relaxer.name() == "bullet");

    RelaxOptions windy;
    windy.wind = Wind{{1, 0, 0}, 10};
    CHECK_THROWS_WITH(relaxer.relax(c.compiled.system, windy), Catch::Contains("wind"));

    RelaxOptions bad;
    bad.tolerance = -1;
    CHECK_THROWS_AS(relaxer.relax(c.compiled.system, bad), UserError);

    BulletSettings settings;
    settings.conjugateGradientIterations = 0;
    CHECK_THROWS_WITH(BulletRelaxer(settings), Catch::Contains("conjugateGradientIterations"));
    settings = {};
    settings.conjugateGradientTolerance = -1e-8;
    CHECK_THROWS_WITH(BulletRelaxer(settings), Catch::Contains("conjugateGradientTolerance"));
    settings = {};
    settings.maxTimeStep = -1;
    CHECK_THROWS_WITH(BulletRelaxer(settings), Catch::Contains("maxTimeStep"));
}
