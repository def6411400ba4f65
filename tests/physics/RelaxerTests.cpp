// The overdamped RK4 relaxation (Eq. 7) against independent solutions and its contracts.
// Materials are soft (EA 50..100 N) so that each case converges in well under a second.
#include "HangGuard.h"
#include "ShapeDistance.h"
#include "model/Error.h"
#include "physics/Forces.h"
#include "physics/ReferenceNets.h"
#include "physics/Relaxer.h"
#include "physics/fast/NewtonRelaxer.h"

#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <cstring>
#include <numbers>

using namespace netsculpt;
using netsculpt::test::maxDistance;
using Catch::Matchers::WithinAbs;

namespace {

NetMaterial softRope(double stiffness = 100) {
    NetMaterial material;
    material.stiffness = stiffness;
    return material; // ratio 0.01, knot 2 g, 6 g/m
}

MassSpringSystem smallSheet(double stiffness = 100) {
    SheetSpec spec;
    spec.rows = 6;
    spec.columns = 8;
    spec.material = softRope(stiffness);
    return makeSheet(spec);
}

bool allFinite(const MassSpringSystem& s) {
    for (const Vec3& p : s.position)
        if (!p.isFinite())
            return false;
    return true;
}

bool sameBits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

/// The discrete catenary, solved here independently of the force code: a chain of n links of
/// rest length l and axial stiffness EA between (0,0,0) and (span,0,0), interior knots of
/// weight w. By symmetry each support carries half the interior weight, so the vertical force
/// component in link i is V_i = w ((n-1)/2 - i) and the horizontal one H is the same in every
/// link; link i has tension T_i = sqrt(H^2 + V_i^2), stretched length l (1 + T_i / EA) and
/// direction (H, -V_i) / T_i. H is found by bisection so that the links span `span`.
std::vector<Vec3> discreteCatenary(int n, double l, double stiffness, double w, double span) {
    auto shape = [&](double h) {
        std::vector<Vec3> p{{0, 0, 0}};
        for (int i = 0; i < n; ++i) {
            const double v = w * ((n - 1) / 2.0 - i), t = std::hypot(h, v);
            p.push_back(p.back() + Vec3{h, 0, -v} * (l * (1 + t / stiffness) / t));
        }
        return p;
    };
    double low = 1e-9, high = 1e3;
    for (int i = 0; i < 200 && high - low > 1e-15 * high; ++i) {
        const double mid = 0.5 * (low + high);
        (shape(mid).back().x < span ? low : high) = mid;
    }
    return shape(0.5 * (low + high));
}

} // namespace

TEST_CASE("A hanging chain relaxes to the discrete catenary", "[relax]") {
    const int links = 20;
    const double bar = 0.1, stiffness = 100, span = 1.6;
    const NetMaterial material = softRope(stiffness);
    MassSpringSystem chain = makeChain({0, 0, 0}, {span, 0, 0}, links, bar, material, 0.3);
    const double w = (material.knotMass + material.linearDensity * bar) * 9.81;
    REQUIRE(chain.mass[5] * 9.81 == Approx(w).epsilon(1e-14));

    RelaxOptions options;
    options.tolerance = 1e-9;
    const RelaxResult result = relaxRk4(chain, options);
    REQUIRE(result.converged);
    CHECK(result.stopReason == "converged");

    // Position error <= residual force / stiffness of the slowest mode: about 1e-9 * w over
    // (H / l) (pi / n)^2 ~ 0.07 N/m, i.e. ~1e-8 m; 1e-6 m leaves a wide margin.
    const std::vector<Vec3> expected = discreteCatenary(links, bar, stiffness, w, span);
    CHECK(maxDistance(chain.position, expected) < 1e-6);
    CHECK(expected.back().x == Approx(span).epsilon(1e-12)); // the reference itself closes
}

// The same chain of real rope (EA 2e5 N, which RK4 cannot reach), relaxed by the fast path.
TEST_CASE("A chain of real rope relaxes by the fast path to the discrete catenary", "[relax][fast]") {
    const int links = 20;
    const double bar = 0.1, span = 1.6;
    const NetMaterial material; // the real rope: EA 2e5 N, ratio 0.01, knot 2 g, 6 g/m
    MassSpringSystem chain = makeChain({0, 0, 0}, {span, 0, 0}, links, bar, material, 0.3);
    const double w = (material.knotMass + material.linearDensity * bar) * 9.81;

    RelaxOptions options;
    options.tolerance = 1e-7; // the rope's forces carry the coordinates' rounding times EA / l
    REQUIRE(relaxFast(chain, options).converged);
    // As above: 1e-7 w over ~0.07 N/m, ~4e-8 m (the tension, and so the slowest mode, is the
    // soft chain's within its stretch). Measured: 4e-12 m.
    const std::vector<Vec3> expected = discreteCatenary(links, bar, material.stiffness, w, span);
    CHECK(maxDistance(chain.position, expected) < 1e-6);
    CHECK(expected.back().x == Approx(span).epsilon(1e-12));
}

TEST_CASE("After convergence the rails carry the weight and every free knot is balanced",
          "[relax]") {
    MassSpringSystem sheet = smallSheet();
    RelaxOptions options;
    options.tolerance = 1e-7;
    const RelaxResult result = relaxRk4(sheet, options);
    REQUIRE(result.converged);
    CHECK(result.residual < options.tolerance);
    CHECK(result.residual == residual(sheet)); // measured on exactly the positions returned
    CHECK(result.forceEvaluations >= 4 * result.steps);

    for (double r : knotResiduals(sheet))
        CHECK(r < options.tolerance);

    // Bar forces cancel in the sum, so sum of reactions - W z = sum of free-knot forces, whose
    // size is at most sum of tolerance * m_j g <= tolerance * W.
    const double weight = totalWeight(sheet);
    Vec3 sum;
    for (const Vec3& reaction : reactions(sheet))
        sum += reaction;
    CHECK((sum - Vec3{0, 0, weight}).norm() <= options.tolerance * weight);
    CHECK(sum.z > 0);
}

TEST_CASE("Continuation and a direct run reach the same shape", "[relax]") {
    MassSpringSystem soft = smallSheet(), direct = soft;
    RelaxOptions options;
    options.tolerance = 1e-9;
    std::vector<double> scales;
    options.progressInterval = 0;
    options.progress = [&](const RelaxProgress& p) {
        if (scales.empty() || scales.back() != p.stiffnessScale)
            scales.push_back(p.stiffnessScale);
    };
    REQUIRE(relaxRk4(soft, options).converged);
    CHECK(scales.size() >= 2); // went through soft stages
    CHECK(scales.front() < 0.1);
    CHECK(scales.back() == 1.0);

    options.continuation = false;
    options.progress = nullptr;
    REQUIRE(relaxRk4(direct, options).converged);
    // Both are within (residual force) / (slowest stiffness) of the equilibrium: 48 knots of
    // 1e-9 * 2.6e-2 N over ~0.07 N/m (tension / bar * (pi / 2 rows)^2) is ~2e-8 m.
    CHECK(maxDistance(soft.position, direct.position) < 1e-6);
}

TEST_CASE("Rails brought closer than the net's length leave bars in compression on k_c",
          "[relax]") {
    SheetSpec spec;
    spec.rows = 7;
    spec.columns = 8;
    spec.material = softRope();
    spec.bottomRailOffset = Vec3{0, 0, -0.2}; // the net hangs 0.52 m when straight
    MassSpringSystem net = makeSheet(spec);

    auto compressedBars = [&] {
        int count = 0;
        const std::vector<double> tension = barTensions(net);
        for (std::size_t b = 0; b < net.barCount(); ++b) {
            const double length = distance(net.position[net.barA[b]], net.position[net.barB[b]]);
            if (length < net.restLength[b]) {
                ++count;
                CHECK(tension[b] == Approx(net.kCompression[b] * (length - net.restLength[b]))
                                        .margin(1e-12)); // N: bars at the rest length to rounding
            }
        }
        return count;
    };
    CHECK(compressedBars() > 0);

    RelaxOptions options;
    options.tolerance = 1e-7;
    const RelaxResult result = relaxRk4(net, options);
    REQUIRE(result.converged);
    CHECK(compressedBars() > 0);
}

TEST_CASE("Relaxation is bit-identical with one and two threads", "[relax][determinism]") {
    SECTION("after a fixed number of steps, larger net") {
        SheetSpec spec;
        spec.rows = 30;
        spec.columns = 40;
        spec.material = softRope();
        MassSpringSystem one = makeSheet(spec), two = one;
        RelaxOptions options;
        options.maxSteps = 300;
        options.threads = 1;
        const RelaxResult a = relaxRk4(one, options);
        options.threads = 2;
        const RelaxResult b = relaxRk4(two, options);
        CHECK(a.stopReason == "step limit");
        CHECK(a.steps == 300);
        CHECK(b.steps == 300);
        CHECK(a.residual == b.residual);
        CHECK(sameBits(one.position, two.position));
    }
    SECTION("after convergence, with wind") {
        SheetSpec spec;
        spec.rows = 4;
        spec.columns = 5;
        spec.material = softRope();
        MassSpringSystem one = makeSheet(spec), two = one;
        RelaxOptions options;
        options.wind = Wind{{0, 1, 0}, 0.02};
        options.threads = 1;
        const RelaxResult a = relaxRk4(one, options);
        options.threads = 2;
        const RelaxResult b = relaxRk4(two, options);
        REQUIRE(a.converged);
        CHECK(a.steps == b.steps);
        CHECK(sameBits(one.position, two.position));
    }
}

TEST_CASE("Wind: the rails take the weight and the wind's total force", "[relax]") {
    MassSpringSystem sheet = smallSheet();
    RelaxOptions options;
    options.tolerance = 1e-7;
    options.wind = Wind{{0, 2, 0}, 0.05};
    options.maxSeconds = test::kHangGuardSeconds; // under 1 s in Release
    REQUIRE(relaxRk4(sheet, options).converged);
    CHECK(residual(sheet, options.wind) < options.tolerance);
    CHECK(residual(sheet) > 1e-3); // without the wind it is not in balance

    Vec3 windTotal; // independently: q L times the normal part of the direction, per bar
    for (std::size_t b = 0; b < sheet.barCount(); ++b) {
        const Vec3 d = sheet.position[sheet.barB[b]] - sheet.position[sheet.barA[b]];
        const Vec3 u = d / d.norm(), dir{0, 1, 0};
        windTotal += (dir - u * dir.dot(u)) * (0.05 * d.norm());
    }
    Vec3 sum;
    for (const Vec3& reaction : reactions(sheet, options.wind))
        sum += reaction;
    const double weight = totalWeight(sheet);
    CHECK((sum - (Vec3{0, 0, weight} - windTotal)).norm() <= options.tolerance * weight);
    CHECK(windTotal.y > 0.01);
}

TEST_CASE("A violent start never leaves NaN and still relaxes", "[relax][robust]") {
    MassSpringSystem sheet = smallSheet();
    for (std::size_t j = 0; j < sheet.knotCount(); ++j)
        if (!sheet.fixed[j])
            sheet.position[j] = sheet.position[j] * 1000.0 + Vec3{0, 0, -50}; // stretched 1000x
    RelaxOptions options;
    options.tolerance = 1e-6;
    options.maxSeconds = test::kHangGuardSeconds; // 0.4 s in Release
    const RelaxResult result = relaxRk4(sheet, options);
    CHECK(allFinite(sheet));
    CHECK(std::isfinite(result.residual));
    CHECK(result.converged);

    MassSpringSystem collapsed = smallSheet(); // every free knot at one point: zero-length bars
    for (std::size_t j = 0; j < collapsed.knotCount(); ++j)
        if (!collapsed.fixed[j])
            collapsed.position[j] = {0.3, 0, -0.2};
    const RelaxResult second = relaxRk4(collapsed, options);
    CHECK(allFinite(collapsed));
    CHECK(second.converged);
}

TEST_CASE("Stops: cancel, step limit, time limit, already converged", "[relax]") {
    RelaxOptions options;
    std::atomic<bool> cancel{false};

    SECTION("cancel") {
        MassSpringSystem sheet = smallSheet();
        options.cancel = &cancel;
        options.progressInterval = 0;
        int calls = 0;
        options.progress = [&](const RelaxProgress&) {
            if (++calls == 10)
                cancel = true;
        };
        const RelaxResult result = relaxRk4(sheet, options);
        CHECK(result.stopReason == "cancelled");
        CHECK_FALSE(result.converged);
        CHECK(result.steps == 10); // the 10th report comes before the 10th step
        CHECK(allFinite(sheet));
    }
    SECTION("step limit 0 leaves the positions alone") {
        MassSpringSystem sheet = smallSheet();
        const std::vector<Vec3> start = sheet.position;
        options.maxSteps = 0;
        const RelaxResult result = relaxRk4(sheet, options);
        CHECK(result.stopReason == "step limit");
        CHECK(result.steps == 0);
        CHECK(sameBits(sheet.position, start));
        CHECK(result.residual == residual(sheet));
    }
    SECTION("time limit") {
        SheetSpec spec;
        spec.rows = 40;
        spec.columns = 40;
        MassSpringSystem big = makeSheet(spec); // realistic rope: far from converging in 50 ms
        options.maxSeconds = 0.05;
        int calls = 0;
        RelaxProgress last;
        options.progress = [&](const RelaxProgress& p) { ++calls, last = p; };
        const RelaxResult result = relaxRk4(big, options);
        CHECK(result.stopReason == "time limit");
        CHECK_FALSE(result.converged);
        CHECK(result.seconds >= 0.05);
        CHECK(result.seconds < 2.0);
        CHECK(calls >= 2); // the start and the end
        CHECK(last.steps == result.steps);
        CHECK(last.residual == result.residual);
    }
    SECTION("a relaxed net is converged at once and not moved") {
        MassSpringSystem sheet = smallSheet();
        REQUIRE(relaxRk4(sheet, options).converged);
        const std::vector<Vec3> relaxed = sheet.position;
        const RelaxResult again = relaxRk4(sheet, options);
        CHECK(again.converged);
        CHECK(again.steps == 0);
        CHECK(sameBits(sheet.position, relaxed));
    }
}

TEST_CASE("A tube on a circular rail relaxes with every row a regular polygon", "[relax]") {
    TubeSpec spec;
    spec.rows = 6;
    spec.columns = 12;
    spec.radius = 0.2;
    spec.material = softRope();
    MassSpringSystem tube = makeTube(spec);
    RelaxOptions options;
    options.tolerance = 1e-8;
    REQUIRE(relaxRk4(tube, options).converged);

    for (int row = 0; row < spec.rows; ++row) {
        double minRadius = INFINITY, maxRadius = 0, minZ = INFINITY, maxZ = -INFINITY;
        for (int c = 0; c < spec.columns; ++c) {
            const Vec3 p = tube.position[static_cast<std::size_t>(row * spec.columns + c)];
            const double radius = std::hypot(p.x, p.y);
            minRadius = std::min(minRadius, radius);
            maxRadius = std::max(maxRadius, radius);
            minZ = std::min(minZ, p.z);
            maxZ = std::max(maxZ, p.z);
        }
        INFO("row " << row);
        CHECK(maxRadius - minRadius < 1e-9 * spec.radius);
        CHECK(maxZ - minZ < 1e-9 * spec.radius);
        if (row > 0)
            CHECK(maxRadius < spec.radius); // the tube narrows below the rail
    }
}

TEST_CASE("Invalid options and systems are user errors", "[relax]") {
    MassSpringSystem sheet = smallSheet();
    auto rejects = [&](auto change, const char* word) {
        RelaxOptions options;
        change(options);
        try {
            (void)relaxRk4(sheet, options);
            FAIL("accepted");
        } catch (const UserError& e) {
            CHECK_THAT(e.what(), Catch::Matchers::Contains(word));
        }
    };
    rejects([](RelaxOptions& o) { o.tolerance = 0; }, "tolerance = 0");
    rejects([](RelaxOptions& o) { o.tolerance = NAN; }, "tolerance");
    rejects([](RelaxOptions& o) { o.maxSeconds = INFINITY; }, "maxSeconds");
    rejects([](RelaxOptions& o) { o.maxSteps = -2; }, "maxSteps = -2");
    rejects([](RelaxOptions& o) { o.threads = -1; }, "threads");
    rejects([](RelaxOptions& o) { o.progressInterval = -1; }, "progressInterval");
    rejects([](RelaxOptions& o) { o.previewStiffnessScale = 2; }, "previewStiffnessScale = 2");
    rejects([](RelaxOptions& o) { o.continuationFactor = 1; }, "continuationFactor");
    rejects([](RelaxOptions& o) { o.wind = Wind{{0, 0, 0}, 1}; }, "wind direction");

    const std::vector<Vec3> before = sheet.position;
    MassSpringSystem floating = smallSheet();
    std::fill(floating.fixed.begin(), floating.fixed.end(), 0);
    CHECK_THROWS_WITH((void)relaxRk4(floating), Catch::Matchers::Contains("no knot is fixed"));
    MassSpringSystem broken = smallSheet();
    broken.position[10].x = NAN;
    CHECK_THROWS_WITH((void)relaxRk4(broken), Catch::Matchers::Contains("knot 10"));
    CHECK(sameBits(sheet.position, before));
}
