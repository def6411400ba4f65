// Benchmark of the "fast" relaxation backend (kernel/physics/fast/NewtonRelaxer.h) against the
// RK4 one, at a realistic rope's stiffness (EA 2e5 N, compression ratio 0.01, knot 2 g, 6 g/m,
// bars 0.1 m), each net built through the model's edits and relaxed from its compiled Eq. 2
// geometry to max |F_j| / (m_j g) <= 1e-6:
//   tube-100x1000   100 rows x 1000 columns on a circular rail (100k knots), target < 5 s
//   tube-100x200    100 x 200 (20k knots), target < 0.5 s
//   slack-100x200   a sheet on an open rail whose last row is connected to a second, parallel
//                   rail nearer than the sheet's height (it starts slack), target < 0.5 s
//   slack-100x1000  the same sheet with 1000 columns (100k knots), target < 5 s
//   banner-RxC      (only when asked for, e.g. --scene banner-90x51) the installation's banner,
//                   R rows x C columns (BenchScenes.h), target < 5 s as for the installation;
//                   tube-RxC and slack-RxC likewise give those nets at any size
// For each: wall seconds, Newton iterations (soft stage + final), factorizations, residual,
// then the RK4 path under a time cap (residual reached) and the ratio of their times. Then the
// force pass (Eq. 3) at 20k and 100k knots: ns per bar with 1 and 2 threads, against the memory
// floor (about 52 bytes per bar at the streaming bandwidth measured with as many threads). Then
// the sparse Cholesky factorization and solve alone (scene "cholesky", CholeskyBench.h).
//
//   netsculpt-bench-fast                 everything (a few minutes, RK4 caps dominate)
//   netsculpt-bench-fast --quick         20x40 nets, short RK4 caps (CI smoke)
//   --scene NAME   only that net          --threads N   thread count (default automatic)
//   --rk4-cap S    RK4 time cap, s         --no-rk4      skip the RK4 runs
//   --cap S        the fast path's time cap, s (default 120)
//   --centre       each net moved so that its bounding box is centred on the origin
//   --trace        print the fast path's residual after every Newton iteration
//   --no-focus     every Newton iteration on the whole net, none on a region still out of
//                  balance alone (FastRelaxer::setFocusRegions; the gain of focusing)
//   --journal F    the sculpture of journal F from its Eq. 2 start instead of the scenes (the
//                  installation: netsculpt run scripts/installation.lua --out out -- --no-relax,
//                  then --journal out/installation.netj --no-rk4; target 5 s)
//   --perturb D    then how near a start has to be: the equilibrium found, every free knot moved
//                  D metres in a random direction (the same ones every run), relaxed again at
//                  the material's stiffness at once (no stages); iterations and where it ends
//   --perturb-hint with --perturb: that run starts with the equilibrium's own tensions as its
//                  hint (RelaxOptions::startTensions, as an edit's run does)

#include "BenchScenes.h"
#include "CholeskyBench.h"
#include "InstructionSet.h"

#include "commands/Document.h"
#include "physics/Forces.h"
#include "physics/Relaxer.h"
#include "physics/ThreadPool.h"
#include "physics/fast/NewtonRelaxer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace netsculpt;
using bench::secondsSince;

namespace {

enum class Shape { Tube, Slack, Banner };

struct Scene {
    std::string name;
    Shape shape;
    int rows, columns;
    double targetSeconds;
};

/// The net through the model's edits (BenchScenes.h); it starts at the Eq. 2 geometry.
MassSpringSystem build(const Scene& scene) {
    const Material rope = bench::realisticRope();
    switch (scene.shape) {
    case Shape::Slack:
        return bench::sheetBetweenParallelRails(scene.rows, scene.columns, rope);
    case Shape::Banner:
        return bench::bannerOnWavyRail(scene.rows, scene.columns, rope);
    case Shape::Tube:
        break;
    }
    return bench::tubeOnCircularRail(scene.rows, scene.columns, rope);
}

/// A net asked for by its shape and size: "tube-RxC", "slack-RxC" or "banner-RxC", R and C
/// from 2 to 1000 (its target: 0.5 s up to 20,000 knots, 5 s above); nothing for any other name.
std::vector<Scene> sizedScene(const std::string& name) {
    const std::pair<const char*, Shape> shapes[] = {{"tube-%dx%d%c", Shape::Tube},
                                                    {"slack-%dx%d%c", Shape::Slack},
                                                    {"banner-%dx%d%c", Shape::Banner}};
    for (const auto& [format, shape] : shapes) {
        int rows = 0, columns = 0;
        char end = 0;
        if (std::sscanf(name.c_str(), format, &rows, &columns, &end) != 2 || rows < 2 ||
            columns < 2 || rows > 1000 || columns > 1000)
            continue;
        const bool small = rows * columns <= 20000 && shape != Shape::Banner;
        return {{name, shape, rows, columns, small ? 0.5 : 5.0}};
    }
    return {};
}

std::size_t compressedBars(const MassSpringSystem& system) {
    std::size_t count = 0;
    for (double t : barTensions(system))
        count += t < 0 ? 1 : 0;
    return count;
}

struct RunSettings {
    int threads = 0;
    double fastCap = 120, rk4Cap = 60;
    bool rk4 = true, trace = false;
    bool centre = false;      ///< the net moved so that its bounding box is centred on the origin
    bool focus = true;        ///< FastRelaxer::setFocusRegions
    double perturb = 0;       ///< m; > 0: perturbedRun after the fast path
    bool perturbHint = false; ///< perturbedRun hinted with the equilibrium's tensions
};

/// Moves every knot so that the net's bounding box is centred on the system's origin: the nearer
/// it, the finer the coordinates' last place, which sets the residual's floor. The compiler's
/// origin already does that to a metre (MassSpringSystem::origin; before it, a 100 m sheet laid
/// from x = 0 stopped at the precision limit, 1.6e-6, and centred it converged); this also
/// centres y and z and nets within 32 m of (0, 0, 0).
void centreOnOrigin(MassSpringSystem& system) {
    Vec3 lo = system.position.front(), hi = lo;
    for (const Vec3& p : system.position) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const Vec3 centre = (lo + hi) * 0.5;
    for (Vec3& p : system.position)
        p -= centre;
}

/// A direction drawn uniformly from the unit sphere (rejection from the cube; the generator's raw
/// output only, so the same directions on every standard library).
Vec3 randomDirection(std::mt19937& random) {
    const auto unit = [&] {
        return 2.0 * static_cast<double>(random()) / static_cast<double>(std::mt19937::max()) - 1.0;
    };
    for (;;) {
        const Vec3 v{unit(), unit(), unit()};
        const double n = v.norm();
        if (n > 1e-3 && n <= 1.0)
            return v * (1.0 / n);
    }
}

/// How near a start has to be: `equilibrium` with every free knot moved `distance` in a random
/// direction, relaxed at the material's stiffness at once (RelaxOptions::continuation off: a
/// start this near would otherwise be judged by its residual, often cold), and how far from
/// `equilibrium` it ends. With `hinted`, the run starts with the equilibrium's own tensions as
/// its hint: how near a start has to be for an edit's mixed iterations.
void perturbedRun(const MassSpringSystem& equilibrium, double distance, const RelaxOptions& options,
                  bool focus, bool hinted) {
    MassSpringSystem system = equilibrium;
    std::mt19937 random(37);
    for (std::size_t j = 0; j < system.knotCount(); ++j)
        if (!system.fixed[j])
            system.position[j] += randomDirection(random) * distance;
    RelaxOptions direct = options;
    direct.continuation = false;
    const std::vector<double> tensions = hinted ? barTensions(equilibrium) : std::vector<double>{};
    direct.startTensions = tensions;
    FastRelaxer fast;
    fast.setFocusRegions(focus);
    const RelaxResult result = fast.relax(system, direct);
    const double farthest = bench::largestDistance(system.position, equilibrium.position);
    std::printf("moved %.3g m%s: %s in %.3f s, residual %.3g, %lld Newton iterations (%lld "
                "hinted); every knot within %.3g m of the equilibrium found first\n",
                distance, hinted ? ", its tensions as the hint" : "",
                result.converged ? "converged" : "NOT converged", result.seconds, result.residual,
                static_cast<long long>(fast.statistics().iterations),
                static_cast<long long>(fast.statistics().hintIterations), farthest);
}

/// The fast path (and RK4 unless --no-rk4) on `start`, against the target in seconds.
void runSystem(const std::string& name, MassSpringSystem start, double targetSeconds,
               const RunSettings& settings) {
    if (settings.centre)
        centreOnOrigin(start);
    std::printf("\n== %s: %zu knots, %zu bars (target %.2g s)\n", name.c_str(),
                start.knotCount(), start.barCount(), targetSeconds);

    MassSpringSystem system = start;
    RelaxOptions options;
    options.threads = settings.threads;
    options.maxSeconds = settings.fastCap;
    if (settings.trace) {
        options.progressInterval = 0;
        options.progress = [](const RelaxProgress& p) {
            std::printf("  iteration %lld  %.3f s  scale %.3g  residual %.3g\n",
                        static_cast<long long>(p.steps), p.seconds, p.stiffnessScale, p.residual);
        };
    }
    FastRelaxer fast;
    fast.setFocusRegions(settings.focus);
    const RelaxResult result = fast.relax(system, options);
    const NewtonStatistics& stats = fast.statistics();
    const std::string outcome =
        result.converged ? "converged" : "NOT converged (" + result.stopReason + ")";
    std::printf("fast: %s in %.3f s (%s), residual %.3g, %lld Newton iterations (%lld soft at "
                "scale %.3g), %lld factorizations (%lld failed)\n",
                outcome.c_str(), result.seconds,
                result.converged && result.seconds <= targetSeconds ? "within target"
                                                                          : "over target",
                result.residual, static_cast<long long>(stats.iterations),
                static_cast<long long>(stats.softIterations), stats.softScale,
                static_cast<long long>(stats.factorizations),
                static_cast<long long>(stats.failedFactorizations));
    if (stats.parts > 1)
        std::printf(stats.partsTogether > 1
                        ? "      %lld independent parts, relaxed %lld at a time, sharing the "
                          "threads\n"
                        : "      %lld independent parts, relaxed one by one\n",
                    static_cast<long long>(stats.parts),
                    static_cast<long long>(stats.partsTogether));
    if (stats.focusRegions > 0)
        std::printf("      %lld regions still out of balance relaxed on their own (%lld in the "
                    "softer stages, %lld where the last stage stalled)\n",
                    static_cast<long long>(stats.focusRegions),
                    static_cast<long long>(stats.softFocusRegions),
                    static_cast<long long>(stats.stallFocusRegions));
    // With parts at the same time the times are summed over them (thread time, not wall time).
    const bool together = stats.partsTogether > 1;
    std::printf("      analysis %.3f s (%s ordering), factorizations %.3f s (%.3g flops each, "
                "%.2f GFlop/s%s), solves %.3f s", stats.analysisSeconds, stats.ordering,
                stats.factorSeconds, stats.factorFlops,
                stats.factorizations > 0
                    ? stats.factorFlops * static_cast<double>(stats.factorizations) /
                          stats.factorSeconds * 1e-9
                    : 0.0,
                together ? " per thread" : "", stats.solveSeconds);
    const auto cores = static_cast<std::int64_t>(std::thread::hardware_concurrency());
    if (together)
        std::printf(" (summed over the parts relaxed at the same time%s)",
                    stats.partsTogether > cores ? ", each part's including its waits for a core"
                                                : "");
    else
        std::printf(", rest %.3f s",
                    result.seconds - stats.analysisSeconds - stats.factorSeconds -
                        stats.solveSeconds);
    std::printf("; %zu bars in compression at the end\n", compressedBars(system));
    if (settings.perturb > 0 && result.converged)
        perturbedRun(system, settings.perturb, options, settings.focus, settings.perturbHint);
    if (!settings.rk4)
        return;
    MassSpringSystem reference = start;
    RelaxOptions rk4Options = options;
    rk4Options.maxSeconds = settings.rk4Cap;
    const RelaxResult slow = relaxRk4(reference, rk4Options);
    std::printf("rk4:  %s in %.3f s, residual %.3g, %lld force evaluations\n",
                slow.converged ? "converged" : "NOT converged (time cap)", slow.seconds,
                slow.residual, static_cast<long long>(slow.forceEvaluations));
    std::printf("ratio rk4 / fast: %s%.1f\n", slow.converged ? "" : ">= ",
                slow.seconds / std::max(result.seconds, 1e-9));
}

void runScene(const Scene& scene, const RunSettings& settings) {
    runSystem(scene.name, build(scene), scene.targetSeconds, settings);
}

/// Streaming read bandwidth with the pool's threads, bytes per second: the best of 20 sums of a
/// 256 MiB array (far beyond the caches), split over the threads as a force pass is. Eight
/// running sums per thread keep it bound by memory; a single running sum (what this measured
/// until 2026-11) is bound by the latency of an addition instead and reads only ~10 GB/s here.
double readBandwidth(ThreadPool& pool) {
    static const std::vector<double> data(std::size_t(1) << 25, 1.0);
    std::vector<double> partial(pool.chunkCount(data.size()));
    double best = 0, total = 0;
    constexpr int kPasses = 20;
    for (int pass = 0; pass < kPasses; ++pass) {
        const auto t0 = std::chrono::steady_clock::now();
        pool.parallelFor(data.size(), [&](std::size_t begin, std::size_t end, std::size_t chunk) {
            double sum[8] = {};
            std::size_t i = begin;
            for (; i + 8 <= end; i += 8)
                for (std::size_t k = 0; k < 8; ++k)
                    sum[k] += data[i + k];
            for (; i < end; ++i)
                sum[0] += data[i];
            partial[chunk] =
                ((sum[0] + sum[1]) + (sum[2] + sum[3])) + ((sum[4] + sum[5]) + (sum[6] + sum[7]));
        });
        const double seconds = secondsSince(t0);
        for (double p : partial)
            total += p;
        best = std::max(best, static_cast<double>(data.size() * sizeof(double)) / seconds);
    }
    if (total != kPasses * static_cast<double>(data.size()))
        std::printf("(read check failed: %g)\n", total);
    return best;
}

/// Wall seconds of single force passes repeated for `seconds`: the best one and the median.
struct PassTimes {
    double best = 0, median = 0;
    std::size_t passes = 0;
};
PassTimes timePasses(const MassSpringSystem& system, ThreadPool* pool, double seconds) {
    ForceField field(system);
    field.setLoad(std::nullopt, 1.0);
    std::vector<Vec3> force(system.knotCount());
    field.evaluate(system.position, force, pool); // first touch of the scratch and the output
    std::vector<double> times;
    const auto start = std::chrono::steady_clock::now();
    do {
        const auto t0 = std::chrono::steady_clock::now();
        field.evaluate(system.position, force, pool);
        times.push_back(secondsSince(t0));
    } while (secondsSince(start) < seconds);
    std::sort(times.begin(), times.end());
    return {times.front(), times[times.size() / 2], times.size()};
}

/// One force pass (ForceField::evaluate, Eq. 3) on tubes of 20k and 100k knots, with 1 and 2
/// threads, in ns per bar against the memory floor: about 52 bytes move per bar (the issue's
/// estimate: the bar's ends and constants, and its share of the positions read and the forces
/// written) at the read bandwidth measured with as many threads. On a shared machine the best
/// pass is what an idle one would do; the median is what the current load allows.
void forcePass(bool quick) {
    std::vector<MassSpringSystem> nets;
    for (int columns : quick ? std::vector<int>{200} : std::vector<int>{200, 1000})
        nets.push_back(build(Scene{"force pass", Shape::Tube, 100, columns, 0}));
    std::printf("\n== force pass (Eq. 3): ns per bar, best and median pass over %.1f s; floor = "
                "52 bytes per bar at the streaming read bandwidth with as many threads\n",
                quick ? 0.2 : 1.0);
    for (int threads : {1, 2}) {
        ThreadPool pool(threads);
        const double bandwidth = readBandwidth(pool);
        const double floorNs = 52.0 / bandwidth * 1e9;
        std::printf("%d thread%s: read %.1f GB/s, floor %.2f ns per bar\n", threads,
                    threads > 1 ? "s" : "", bandwidth * 1e-9, floorNs);
        for (const MassSpringSystem& net : nets) {
            const PassTimes t = timePasses(net, threads > 1 ? &pool : nullptr, quick ? 0.2 : 1.0);
            const double bars = static_cast<double>(net.barCount());
            std::printf("  %zu knots, %zu bars: best %.2f ns per bar (%.3f ms, %.1fx the floor), "
                        "median %.2f (%.1fx), %zu passes\n",
                        net.knotCount(), net.barCount(), t.best / bars * 1e9, t.best * 1e3,
                        t.best / bars * 1e9 / floorNs, t.median / bars * 1e9,
                        t.median / bars * 1e9 / floorNs, t.passes);
        }
    }
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false;
    RunSettings settings;
    settings.rk4Cap = -1;
    std::string only, journal;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick")
            quick = true;
        else if (arg == "--no-rk4")
            settings.rk4 = false;
        else if (arg == "--trace")
            settings.trace = true;
        else if (arg == "--threads" && i + 1 < argc)
            settings.threads = std::atoi(argv[++i]);
        else if (arg == "--rk4-cap" && i + 1 < argc)
            settings.rk4Cap = std::atof(argv[++i]);
        else if (arg == "--centre")
            settings.centre = true;
        else if (arg == "--no-focus")
            settings.focus = false;
        else if (arg == "--cap" && i + 1 < argc)
            settings.fastCap = std::atof(argv[++i]);
        else if (arg == "--scene" && i + 1 < argc)
            only = argv[++i];
        else if (arg == "--journal" && i + 1 < argc)
            journal = argv[++i];
        else if (arg == "--perturb-hint")
            settings.perturbHint = true;
        else if (arg == "--perturb" && i + 1 < argc) {
            settings.perturb = std::atof(argv[++i]);
            if (!(settings.perturb > 0 && settings.perturb < 1e3)) {
                std::fprintf(stderr,
                             "netsculpt-bench-fast: --perturb %s: a distance in metres, "
                             "above 0 and below 1000\n",
                             argv[i]);
                return 2;
            }
        } else {
            std::fprintf(stderr,
                         "usage: %s [--quick] [--threads N] [--rk4-cap S] [--no-rk4] "
                         "[--scene NAME | --journal FILE.netj] [--cap S] [--centre] "
                         "[--trace] [--no-focus] [--perturb D [--perturb-hint]]\n",
                         argv[0]);
            return 2;
        }
    }
    if (settings.perturbHint && !(settings.perturb > 0)) {
        std::fprintf(stderr, "netsculpt-bench-fast: --perturb-hint hints the run from a perturbed "
                             "equilibrium: give --perturb D too\n");
        return 2;
    }
    if (!journal.empty()) {
        try {
            const Document doc = Document::open(journal);
            runSystem(journal, doc.compiled().system, 5.0, settings);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "netsculpt-bench-fast: %s\n", e.what());
            return 1;
        }
        return 0;
    }
    // A net asked for by its size runs alone.
    std::vector<Scene> scenes = sizedScene(only);
    if (scenes.empty())
        scenes = quick ? std::vector<Scene>{{"tube-20x40", Shape::Tube, 20, 40, 0.05},
                                            {"slack-20x40", Shape::Slack, 20, 40, 0.05}}
                       : std::vector<Scene>{{"tube-100x200", Shape::Tube, 100, 200, 0.5},
                                            {"slack-100x200", Shape::Slack, 100, 200, 0.5},
                                            {"tube-100x1000", Shape::Tube, 100, 1000, 5.0},
                                            {"slack-100x1000", Shape::Slack, 100, 1000, 5.0}};
    const bool known = only.empty() || only == "force" || only == "cholesky" ||
                       std::any_of(scenes.begin(), scenes.end(),
                                   [&](const Scene& scene) { return scene.name == only; });
    if (!known) {
        std::fprintf(stderr, "netsculpt-bench-fast: no scene \"%s\"; the scenes are tube-100x200, "
                             "slack-100x200, tube-100x1000, slack-100x1000, force, cholesky, and "
                             "tube-RxC, slack-RxC or banner-RxC for R and C from 2 to 1000\n",
                     only.c_str());
        return 2;
    }
    if (settings.rk4Cap < 0)
        settings.rk4Cap = quick ? 2.0 : 60.0;
    const std::string threads =
        settings.threads == 0 ? "automatic" : std::to_string(settings.threads);
    std::printf("netsculpt-bench-fast: rope EA 2e5 N, tolerance 1e-6, threads %s, %u hardware "
                "threads, built for %s\n", threads.c_str(), std::thread::hardware_concurrency(),
                bench::instructionSet());
    try {
        for (const Scene& scene : scenes)
            if (only.empty() || only == scene.name)
                runScene(scene, settings);
        if (only.empty() || only == "force")
            forcePass(quick);
        if (only.empty() || only == "cholesky")
            bench::choleskyTimes(quick);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "netsculpt-bench-fast: %s\n", e.what());
        return 1;
    }
    return 0;
}
