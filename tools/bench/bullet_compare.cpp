// Benchmark of the three relaxation backends side by side (issue 6): "bullet" (Bullet's
// deformable mass-spring solver, physics/bullet/BulletRelaxer.h), "rk4" (the paper's overdamped
// RK4, physics/Relaxer.h) and "fast" (Newton, physics/fast/NewtonRelaxer.h). Each relaxes the same
// nets, built through the model's edits (BenchScenes.h) and started at their Eq. 2 geometry, to
// the same tolerance (residual of Eq. 3, max |F_j| / (m_j g) <= 1e-6, judged by the project's own
// residual() on the positions each backend returns), under one wall-time cap per run:
//   tube    a tube on a circular rail (Fig. 10)
//   sheet   a sheet between two parallel rails, slack at the start (Fig. 11's kind of join)
// at about 2k, 20k and 200k knots, in two materials:
//   rope    the realistic rope: EA 2e5 N, compression ratio 0.01, knot 2 g, 6 g/m, bars 0.1 m
//   cr=1    the same rope with compression ratio 1, where Bullet's model (one stiffness both
//           ways) and Eq. 3 coincide; with the real rope Bullet's rest shape is not one of Eq. 3
//           wherever bars end up compressed, and it stops "stalled" (BulletRelaxer.h)
// For each run: wall and CPU seconds of relax(), how it stopped, the residual reached and the steps
// (RK4 steps, Newton iterations or Bullet steps); then a table with the ratios bullet / fast and
// rk4 / fast of the times to converge ("> X" when the slower one hit the cap: it needs longer).
//
//   netsculpt-bench-compare                 2k, 20k and 200k knots, 15 s cap (about 8 min)
//   netsculpt-bench-compare --quick         200-knot nets, 0.3 s cap (a smoke run, seconds)
//   --sizes LIST   comma-separated, of 0.2k, 2k, 20k, 200k     --cap S   per-run cap, s
//   --threads N    force-evaluation threads of rk4 and fast (Bullet's solver is serial)
//   --backends LIST   comma-separated, of bullet, rk4, fast (default: all three)
//   --shapes LIST  comma-separated, of tube, sheet (default: both)
//   --bullet-cg N  Bullet's conjugate-gradient iteration cap per Newton iteration
//                  (BulletSettings::conjugateGradientIterations; default: the backend's)
//   --bullet-cg-tol X  Bullet's conjugate-gradient stopping tolerance
//                  (BulletSettings::conjugateGradientTolerance; default: the backend's)
//   --bullet-newton N  Newton iterations per Bullet step (BulletSettings::newtonIterations)

#include "BenchScenes.h"
#include "InstructionSet.h"

#include "physics/Backends.h"
#include "physics/Forces.h"
#include "physics/Relaxer.h"
#include "physics/bullet/BulletRelaxer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace netsculpt;

namespace {

constexpr double kTolerance = 1e-6;
constexpr double kDefaultCap = 15; // s per run
constexpr double kQuickCap = 0.3;  // s per run
// In the table's order.
const std::vector<std::string> kBackends = {"bullet", "rk4", "fast"};

struct NetSize {
    std::string label;
    int rows, columns; ///< the same for both shapes
};

const std::vector<NetSize>& knownSizes() {
    static const std::vector<NetSize> sizes = {
        {"0.2k", 10, 20}, {"2k", 40, 50}, {"20k", 100, 200}, {"200k", 200, 1000}};
    return sizes;
}

enum class Shape { tube, sheet };

struct NamedMaterial {
    std::string name;
    Material material;
};

std::vector<NamedMaterial> materials() {
    Material coincident = bench::realisticRope();
    coincident.compressionRatio = 1;
    return {{"rope", bench::realisticRope()}, {"cr=1", coincident}};
}

struct Settings {
    std::vector<NetSize> sizes;
    std::vector<std::string> backends = kBackends;
    std::vector<Shape> shapes = {Shape::tube, Shape::sheet};
    double cap = -1; ///< s; < 0 = the default for the mode
    int threads = 0;
    bool quick = false;
    BulletSettings bullet; ///< the bullet backend's solver knobs
};

/// One backend's run on one net.
struct Run {
    std::string backend;
    std::string stopReason;
    bool converged = false;
    double seconds = 0; ///< wall time of relax()
    /// CPU time of the process during relax(), all threads (the machine may be shared)
    double cpuSeconds = 0;
    double residual = 0; ///< residual() of Eq. 3 at the positions returned
    long long steps = 0;
};

/// One net in one material, with every backend's run.
struct Comparison {
    std::string net, material;
    std::size_t knots = 0;
    std::vector<Run> runs; ///< in Settings::backends' order

    /// The run of `backend`; null when it was not run.
    const Run* find(const std::string& backend) const {
        for (const Run& run : runs)
            if (run.backend == backend)
                return &run;
        return nullptr;
    }
};

// ---- command line ------------------------------------------------------------------------------

bool parseSizes(const std::string& list, std::vector<NetSize>& sizes) {
    std::stringstream stream(list);
    std::string label;
    while (std::getline(stream, label, ',')) {
        bool found = false;
        for (const NetSize& size : knownSizes())
            if (size.label == label) {
                sizes.push_back(size);
                found = true;
            }
        if (!found) {
            std::fprintf(stderr, "unknown size '%s': use 0.2k, 2k, 20k or 200k\n", label.c_str());
            return false;
        }
    }
    return !sizes.empty();
}

bool parseBackends(const std::string& list, std::vector<std::string>& backends) {
    backends.clear();
    std::stringstream stream(list);
    std::string name;
    while (std::getline(stream, name, ',')) {
        if (std::find(kBackends.begin(), kBackends.end(), name) == kBackends.end()) {
            std::fprintf(stderr, "unknown backend '%s': use bullet, rk4 or fast\n", name.c_str());
            return false;
        }
        backends.push_back(name);
    }
    return !backends.empty();
}

bool parseShapes(const std::string& list, std::vector<Shape>& shapes) {
    shapes.clear();
    std::stringstream stream(list);
    std::string name;
    while (std::getline(stream, name, ',')) {
        if (name == "tube")
            shapes.push_back(Shape::tube);
        else if (name == "sheet")
            shapes.push_back(Shape::sheet);
        else {
            std::fprintf(stderr, "unknown shape '%s': use tube or sheet\n", name.c_str());
            return false;
        }
    }
    return !shapes.empty();
}

void applyModeDefaults(Settings& settings) {
    if (settings.sizes.empty())
        for (const NetSize& size : knownSizes())
            if ((size.label == "0.2k") == settings.quick)
                settings.sizes.push_back(size);
    if (settings.cap < 0)
        settings.cap = settings.quick ? kQuickCap : kDefaultCap;
}

bool parseArguments(int argc, char** argv, Settings& settings) {
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        const bool hasValue = i + 1 < argc;
        if (arg == "--quick")
            settings.quick = true;
        else if (arg == "--sizes" && hasValue) {
            if (!parseSizes(argv[++i], settings.sizes))
                return false;
        } else if (arg == "--backends" && hasValue) {
            if (!parseBackends(argv[++i], settings.backends))
                return false;
        } else if (arg == "--shapes" && hasValue) {
            if (!parseShapes(argv[++i], settings.shapes))
                return false;
        } else if (arg == "--cap" && hasValue) {
            settings.cap = std::atof(argv[++i]);
            if (!(settings.cap > 0))
                return false;
        } else if (arg == "--threads" && hasValue)
            settings.threads = std::atoi(argv[++i]);
        else if (arg == "--bullet-cg" && hasValue) {
            settings.bullet.conjugateGradientIterations = std::atoi(argv[++i]);
            if (settings.bullet.conjugateGradientIterations < 1)
                return false;
        } else if (arg == "--bullet-newton" && hasValue) {
            settings.bullet.newtonIterations = std::atoi(argv[++i]);
            if (settings.bullet.newtonIterations < 1)
                return false;
        } else if (arg == "--bullet-cg-tol" && hasValue) {
            settings.bullet.conjugateGradientTolerance = std::atof(argv[++i]);
            if (!(settings.bullet.conjugateGradientTolerance >= 0))
                return false;
        } else
            return false;
    }
    applyModeDefaults(settings);
    return true;
}

// ---- runs --------------------------------------------------------------------------------------

MassSpringSystem buildNet(Shape shape, const NetSize& size, const Material& material) {
    return shape == Shape::tube
               ? bench::tubeOnCircularRail(size.rows, size.columns, material)
               : bench::sheetBetweenParallelRails(size.rows, size.columns, material);
}

std::string netName(Shape shape, const NetSize& size) {
    return (shape == Shape::tube ? "tube " : "sheet ") + std::to_string(size.rows) + "x" +
           std::to_string(size.columns);
}

Run relaxWith(const std::string& backend, const MassSpringSystem& start, const Settings& settings) {
    MassSpringSystem system = start;
    RelaxOptions options;
    options.tolerance = kTolerance;
    options.maxSeconds = settings.cap;
    options.threads = settings.threads;
    const std::unique_ptr<Relaxer> relaxer = backend == "bullet"
                                                 ? std::make_unique<BulletRelaxer>(settings.bullet)
                                                 : makeRelaxer(backend);
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t cpu0 = std::clock();
    const RelaxResult result = relaxer->relax(system, options);
    Run run;
    run.seconds = bench::secondsSince(t0);
    run.cpuSeconds = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
    run.backend = backend;
    run.stopReason = result.stopReason;
    run.residual = residual(system);
    run.converged = run.residual <= kTolerance;
    run.steps = static_cast<long long>(result.steps);
    return run;
}

void printRunHeader() {
    std::printf("%-16s %-5s %8s | %-7s %-11s %9s %9s %10s %9s\n", "net", "mat.", "knots", "backend",
                "stop", "seconds", "cpu s", "residual", "steps");
}

void printRun(const Comparison& c, const Run& run) {
    std::printf("%-16s %-5s %8zu | %-7s %-11s %9.3f %9.3f %10.2e %9lld\n", c.net.c_str(),
                c.material.c_str(), c.knots, run.backend.c_str(), run.stopReason.c_str(),
                run.seconds, run.cpuSeconds, run.residual, run.steps);
    std::fflush(stdout);
}

Comparison compare(Shape shape, const NetSize& size, const NamedMaterial& material,
                   const Settings& settings) {
    const MassSpringSystem start = buildNet(shape, size, material.material);
    Comparison c{netName(shape, size), material.name, start.knotCount(), {}};
    for (const std::string& backend : settings.backends) {
        c.runs.push_back(relaxWith(backend, start, settings));
        printRun(c, c.runs.back());
    }
    return c;
}

// ---- summary -----------------------------------------------------------------------------------

/// "1.23 s" when converged, else "> 20 s (r 4.5e-01)" or "stalled (r ...)" with the residual
/// reached; "-" when not run.
std::string timeText(const Run* run) {
    char text[64];
    if (!run)
        return "-";
    if (run->converged)
        std::snprintf(text, sizeof text, "%.3g s", run->seconds);
    else if (run->stopReason == "time limit")
        std::snprintf(text, sizeof text, "> %.3g s (r %.1e)", run->seconds, run->residual);
    else
        std::snprintf(text, sizeof text, "%s (r %.1e)", run->stopReason.c_str(), run->residual);
    return text;
}

/// How many times longer `other` takes than `fast` to converge: a number; "> X" when `other`
/// hit the cap (it needs longer); "< X" when fast hit it and `other` converged; "never" when
/// `other` stopped unconverged before the cap (going on cannot help); "-" when unknown.
std::string ratioText(const Run* other, const Run* fast) {
    if (!other || !fast)
        return "-";
    const double ratio = other->seconds / fast->seconds;
    const bool otherCapped = !other->converged && other->stopReason == "time limit";
    char text[32];
    if (fast->converged && other->converged)
        std::snprintf(text, sizeof text, "%.3g", ratio);
    else if (fast->converged && otherCapped)
        std::snprintf(text, sizeof text, "> %.3g", ratio);
    else if (fast->converged)
        std::snprintf(text, sizeof text, "never");
    else if (other->converged && fast->stopReason == "time limit")
        std::snprintf(text, sizeof text, "< %.3g", ratio);
    else
        return "-";
    return text;
}

void printSummary(const std::vector<Comparison>& comparisons, double cap) {
    std::printf("\nTime to residual <= %.0e (each run capped at %.3g s; r = residual reached)\n",
                kTolerance, cap);
    std::printf("%-16s %-5s %8s | %-22s | %-22s | %-22s | %-11s | %-11s\n", "net", "mat.", "knots",
                "bullet", "rk4", "fast", "bullet/fast", "rk4/fast");
    for (const Comparison& c : comparisons) {
        const Run *bullet = c.find("bullet"), *rk4 = c.find("rk4"), *fast = c.find("fast");
        std::printf("%-16s %-5s %8zu | %-22s | %-22s | %-22s | %-11s | %-11s\n", c.net.c_str(),
                    c.material.c_str(), c.knots, timeText(bullet).c_str(), timeText(rk4).c_str(),
                    timeText(fast).c_str(), ratioText(bullet, fast).c_str(),
                    ratioText(rk4, fast).c_str());
    }
}

/// The 1, 5 and 15 minute load averages (as `uptime` prints them); the machine may be shared.
std::string loadAverage() {
    std::ifstream file("/proc/loadavg");
    std::string one, five, fifteen;
    if (!(file >> one >> five >> fifteen))
        return "unknown";
    return one + " " + five + " " + fifteen;
}

void printPreamble(const Settings& settings) {
    std::printf("netsculpt-bench-compare: tolerance %.0e, cap %.3g s per run, threads %s, %u "
                "hardware threads, built for %s\n",
                kTolerance, settings.cap,
                settings.threads == 0 ? "automatic" : std::to_string(settings.threads).c_str(),
                std::thread::hardware_concurrency(), bench::instructionSet());
    std::printf(
        "rope: EA 2e5 N, compression ratio 0.01, knot 2 g, 6 g/m, bar 0.1 m; cr=1: the same "
        "with compression ratio 1\n");
    std::printf("bullet: %d Newton iterations per step, at most %d conjugate-gradient iterations "
                "per Newton iteration, tolerance %.3g\n",
                settings.bullet.newtonIterations, settings.bullet.conjugateGradientIterations,
                settings.bullet.conjugateGradientTolerance);
    std::printf("load average at start: %s\n\n", loadAverage().c_str());
}

} // namespace

int main(int argc, char** argv) {
    Settings settings;
    if (!parseArguments(argc, argv, settings)) {
        std::fprintf(
            stderr,
            "usage: %s [--quick] [--sizes 0.2k,2k,20k,200k] [--cap S] "
            "[--threads N] [--backends bullet,rk4,fast] [--shapes tube,sheet] [--bullet-cg N] "
            "[--bullet-cg-tol X] [--bullet-newton N]\n",
            argv[0]);
        return 2;
    }
    printPreamble(settings);
    printRunHeader();
    std::vector<Comparison> comparisons;
    try {
        for (const NetSize& size : settings.sizes)
            for (Shape shape : settings.shapes)
                for (const NamedMaterial& material : materials())
                    comparisons.push_back(compare(shape, size, material, settings));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "netsculpt-bench-compare: %s\n", e.what());
        return 1;
    }
    printSummary(comparisons, settings.cap);
    std::printf("load average at the end: %s\n", loadAverage().c_str());
    return 0;
}
