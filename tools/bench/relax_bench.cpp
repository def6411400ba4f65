// Benchmark of the force function (Eq. 3) and the overdamped RK4 relaxation (Eq. 7) on
// hand-built tubes and sheets of about 2k, 20k and 200k knots, with a soft preview material
// (EA 200 N) and a realistic rope (EA 2e5 N, compression ratio 0.01, knot 2 g, 6 g/m, bars
// 0.1 m). Prints force passes per second, ns per bar, knot updates per second, and for the
// relaxation the evaluations and wall time to converge, or the residual reached in a time cap.
//
//   netsculpt-bench-relax            full run, about 2.5 minutes
//   netsculpt-bench-relax --quick    the 2k nets only, short caps (CI smoke)
//   --threads N                      force the thread count (default: automatic)

#include "InstructionSet.h"

#include "physics/Forces.h"
#include "physics/ReferenceNets.h"
#include "physics/Relaxer.h"
#include "physics/ThreadPool.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

using namespace netsculpt;

namespace {

struct Net {
    const char* shape;
    int rows, columns;
    double capSeconds; ///< relaxation time cap in the full run
};

MassSpringSystem build(const Net& net, const NetMaterial& material) {
    if (std::strcmp(net.shape, "tube") == 0) {
        TubeSpec spec;
        spec.rows = net.rows;
        spec.columns = net.columns;
        spec.barLength = 0.1;
        spec.radius = net.columns * 0.1 / (2 * 3.141592653589793); // rail spacing 0.1 m
        spec.material = material;
        return makeTube(spec);
    }
    SheetSpec spec;
    spec.rows = net.rows;
    spec.columns = net.columns;
    spec.barLength = 0.1;
    spec.spacing = 0.1;
    spec.material = material;
    return makeSheet(spec);
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Force passes per second over at least minSeconds.
double forcePassesPerSecond(const MassSpringSystem& system, int threads, double minSeconds) {
    ForceField field(system);
    field.setLoad(std::nullopt, 1.0);
    std::vector<Vec3> force(system.knotCount());
    ThreadPool pool(threads);
    ThreadPool* usePool = threads > 1 ? &pool : nullptr;
    field.evaluate(system.position, force, usePool); // warm the caches
    long passes = 0;
    const auto start = std::chrono::steady_clock::now();
    double elapsed = 0;
    do {
        for (int i = 0; i < 10; ++i)
            field.evaluate(system.position, force, usePool);
        passes += 10;
        elapsed = secondsSince(start);
    } while (elapsed < minSeconds);
    return static_cast<double>(passes) / elapsed;
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false;
    int threads = 0;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0)
            quick = true;
        else if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            threads = std::atoi(argv[++i]);
        else {
            std::fprintf(stderr, "usage: %s [--quick] [--threads N]\n", argv[0]);
            return 2;
        }
    }

    const std::vector<Net> nets = {
        {"tube", 50, 40, 5},    {"sheet", 50, 40, 5},    // 2,000 knots
        {"tube", 160, 125, 10}, {"sheet", 160, 125, 10}, // 20,000
        {"tube", 500, 400, 15}, {"sheet", 500, 400, 15}, // 200,000
    };
    NetMaterial rope; // the defaults: EA 2e5 N, ratio 0.01, 2 g, 6 g/m
    NetMaterial preview = rope;
    preview.stiffness = 200;
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());

    std::printf("netsculpt relax benchmark (%s), %u hardware threads, built for %s\n\n",
                quick ? "quick" : "full", hardware, bench::instructionSet());
    std::printf("force function (Eq. 3), realistic rope at the start geometry\n");
    std::printf("%-6s %8s %8s %8s | %12s %9s %14s | %12s %9s\n", "net", "knots", "bars", "",
                "passes/s 1T", "ns/bar", "knot-upd/s", "passes/s 2T", "ns/bar");
    for (const Net& net : nets) {
        if (quick && net.rows > 50)
            continue;
        const MassSpringSystem system = build(net, rope);
        const double minSeconds = quick ? 0.1 : 0.5;
        const double one = forcePassesPerSecond(system, 1, minSeconds);
        const double two = forcePassesPerSecond(system, 2, minSeconds);
        const double bars = static_cast<double>(system.barCount());
        std::printf("%-6s %8zu %8zu %8s | %12.1f %9.2f %14.3e | %12.1f %9.2f\n", net.shape,
                    system.knotCount(), system.barCount(), "", one, 1e9 / (one * bars),
                    one * static_cast<double>(system.knotCount()), two, 1e9 / (two * bars));
    }

    std::printf("\nRK4 relaxation, tolerance 1e-6, continuation on, threads %s\n",
                threads == 0 ? "automatic" : std::to_string(threads).c_str());
    std::printf("%-6s %8s %-8s | %-11s %10s %12s %10s %9s %14s\n", "net", "knots", "material",
                "stop", "residual", "evaluations", "steps", "seconds", "knot-upd/s");
    for (const Net& net : nets) {
        if (quick && net.rows > 50)
            continue;
        for (const auto& [name, material] :
             {std::pair{"preview", preview}, std::pair{"rope", rope}}) {
            MassSpringSystem system = build(net, material);
            RelaxOptions options;
            options.maxSeconds = quick ? 1.0 : net.capSeconds;
            options.threads = threads;
            const RelaxResult result = relaxRk4(system, options);
            std::printf("%-6s %8zu %-8s | %-11s %10.3e %12lld %10lld %9.2f %14.3e\n", net.shape,
                        system.knotCount(), name, result.stopReason.c_str(), result.residual,
                        static_cast<long long>(result.forceEvaluations),
                        static_cast<long long>(result.steps), result.seconds,
                        static_cast<double>(result.forceEvaluations) *
                            static_cast<double>(system.knotCount()) / result.seconds);
            std::fflush(stdout);
        }
    }
    return 0;
}
