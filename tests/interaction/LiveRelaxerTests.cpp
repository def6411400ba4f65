// The live relaxation controller: it publishes shapes without blocking the caller, restarts from
// the given positions on every edit, and Refine converges at the material's stiffness.

#include "InteractionTestSupport.h"

#include "interaction/LiveRelaxer.h"
#include "physics/Forces.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#ifdef __linux__
#include <sys/resource.h>
#endif

using namespace netsculpt;
using namespace netsculpt::test;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

} // namespace

TEST_CASE("live relaxer: preview publishes a settled soft shape, refine converges at full stiffness", "[live]") {
    Scene scene; // drawn in to the ring below: a taut net that settles in a fraction of a second
    scene.doc.execute(ConnectToRailCommand{scene.net, scene.ring, 0, false});
    const MassSpringSystem& system = scene.doc.compiled().system;
    LiveRelaxer live;
    CHECK(live.latest() == nullptr);

    const auto start = Clock::now();
    live.preview(system, 7);
    CHECK(secondsSince(start) < 0.05); // never blocks the caller
    REQUIRE(live.waitIdle(60));
    auto state = live.latest();
    REQUIRE(state);
    CHECK(state->generation == 7);
    CHECK(state->phase == LivePhase::Preview);
    CHECK_FALSE(state->running);
    CHECK(state->converged);
    CHECK(state->stopReason == "converged");
    CHECK(state->residual < live.options().previewTolerance);
    CHECK(state->stiffnessScale < 1);
    REQUIRE(state->positions.size() == system.knotCount());
    // The net moved from where Eq. 1-2 put it; fixed knots did not move.
    const std::uint32_t middle = scene.doc.compiled().knotOf(scene.net, 3, 0);
    CHECK(distance(state->positions[middle], system.position[middle]) > 0.01);
    for (std::size_t j = 0; j < system.knotCount(); ++j)
        if (system.fixed[j]) CHECK(state->positions[j] == system.position[j]);

    // Refine from the preview's shape: the residual at the material's stiffness gets below 1e-6.
    MassSpringSystem warm = system;
    warm.position = state->positions;
    const double before = residual(warm);
    live.refine(warm, 8);
    REQUIRE(live.waitIdle(120));
    state = live.latest();
    CHECK(state->generation == 8);
    CHECK(state->phase == LivePhase::Refine);
    CHECK(state->converged);
    CHECK(state->stiffnessScale == 1);
    warm.position = state->positions;
    CHECK(residual(warm) < 1e-6);
    CHECK(residual(warm) < before);
    CHECK(state->residual == Approx(residual(warm)).margin(1e-12));
}

TEST_CASE("live relaxer: a new edit cancels the run in progress and restarts from its positions", "[live]") {
    Scene scene;
    scene.doc.execute(SetRowsCommand{scene.net, 60});
    MassSpringSystem big = scene.doc.compiled().system;
    LiveRelaxOptions options;
    options.previewTolerance = 1e-12; // runs until cancelled
    LiveRelaxer live(options);
    live.preview(big, 1);
    const auto start = Clock::now();
    while (!live.latest() && secondsSince(start) < 10) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    REQUIRE(live.latest());
    CHECK(live.latest()->running);
    // the run publishes the shape it has reached while it goes on
    CHECK(live.latest()->positions.size() == big.knotCount());

    scene.doc.execute(SetRowsCommand{scene.net, 6});
    const MassSpringSystem& small = scene.doc.compiled().system;
    live.preview(small, 2);
    const auto restart = Clock::now();
    while (secondsSince(restart) < 10) {
        const auto s = live.latest();
        if (s && s->generation == 2) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    CHECK(secondsSince(restart) < 2);
    CHECK(live.latest()->generation == 2);
    CHECK(live.latest()->positions.size() == small.knotCount());
    live.cancel();
    REQUIRE(live.waitIdle(10));
    CHECK(live.latest()->stopReason == "cancelled");
    CHECK_FALSE(live.latest()->running);
}

TEST_CASE("live relaxer: a system that cannot be relaxed reports an error", "[live]") {
    MassSpringSystem loose;
    loose.position = {{0, 0, 0}, {0, 0, -1}};
    loose.mass = {1, 1};
    loose.fixed = {0, 0};
    loose.hold = {{}, {}};
    loose.refStart = {0, 0, 0};
    loose.barA = {0};
    loose.barB = {1};
    loose.restLength = {1};
    loose.kTension = {100};
    loose.kCompression = {1};
    loose.linearDensity = {0};
    loose.barPiece = {PieceId(1)};
    LiveRelaxer live;
    live.preview(loose, 3);
    REQUIRE(live.waitIdle(10));
    REQUIRE(live.latest());
    CHECK(live.latest()->stopReason == "error");
    CHECK_THAT(live.latest()->error, Catch::Matchers::Contains("no knot is fixed"));
}

#ifdef __linux__
namespace {

/// Nice values of this process's threads, from /proc/self/task/*/stat (field 19).
std::vector<int> threadNiceValues() {
    std::vector<int> values;
    for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
        std::ifstream stat(task.path() / "stat");
        std::string line;
        std::getline(stat, line);
        std::istringstream fields(line.substr(line.rfind(')') + 2)); // after the thread's name
        std::string field;
        for (int i = 3; i <= 19 && fields >> field; ++i)
            if (i == 19) values.push_back(std::stoi(field));
    }
    return values;
}

} // namespace

TEST_CASE("live relaxer: setNiceness lowers the worker's priority from the next run", "[live]") {
    Scene scene;
    const int base = getpriority(PRIO_PROCESS, 0);
    REQUIRE(base <= 12);
    LiveRelaxer live;
    auto lowered = [&] {
        const std::vector<int> nice = threadNiceValues();
        return std::count(nice.begin(), nice.end(), base + 7);
    };
    live.preview(scene.doc.compiled().system, 1);
    REQUIRE(live.waitIdle(60));
    CHECK(lowered() == 0);
    live.setNiceness(7);
    live.preview(scene.doc.compiled().system, 2);
    REQUIRE(live.waitIdle(60));
    CHECK(lowered() == 1); // the worker, not the caller
    CHECK(getpriority(PRIO_PROCESS, 0) == base);
}
#endif
