// Benchmark of the studio's live preview: how long after an edit the re-relaxed shape of a
// 20,000-knot sculpture is there to show. It drives the studio's own path without a window: the
// document executes a drag's commands (merged, as a drag does; each recompiles and warm-starts
// from the shape shown), the LiveRelaxer (kernel/interaction/LiveRelaxer.h, the studio's options:
// soft preview stiffness, tolerance 1e-3, the default backend) re-relaxes, and the latency is the
// wall time from the edit to the converged preview shape being published. At 30 frames per second
// a frame lasts 33 ms. It also times every shape the LiveRelaxer publishes (its onPublish hook):
// the interval between two shapes of one run is how smoothly the net settles on screen while a
// longer re-relaxation goes on (the first settle from the Eq. 2 start is the long one).
//
// Drags (each step one command, one after the other):
//   bar length   +0.5 % per step (same topology: the fast backend reuses its analysis)
//   rows         +1 row per step (new topology: a new ordering and analysis every step)
//
//   netsculpt-bench-live                 the studio's 20k-knot demo tube, 20 + 10 steps
//   netsculpt-bench-live --knots N       another size      --steps N   steps per drag
//   --sheet                              a slack sheet between two parallel rails instead of the
//                                        tube (interaction/DemoScenes.h), the same size
//   --backend NAME                       the preview's backend (default: the studio's)
//   --preview-scale S                    the preview's stiffness scale (default: the studio's)
//   --threads N                          the preview's threads (default: the studio's, every
//                                        hardware thread but the one it keeps for its frames)
//   --settle-threads N                   the threads of the runs no drag waits on: the first
//                                        settle, --connect's drop and a refine (default: the
//                                        studio's, every hardware thread)
//   --double-steps                       the hinted steps in double precision throughout (the
//                                        studio's are single, refined in double)
//   --only bar|rows                      one of the two drags (for profiling)
//   --connect                            instead of the drags, the slack sheet's connection: it
//                                        settles hanging from its top rail alone, then its last
//                                        row is connected to the lower rail (one edit)
//   --continuous                         instead of the drags, one as fast as the frames: a bar-
//                                        length step of +0.1 % at every frame (30 a second) for
//                                        --steps frames, each restarting the preview while the
//                                        last may still run, the shape on screen taken as the
//                                        studio takes it; how often it moved, and how long the
//                                        last step took to settle (with --only rows, a row a frame)
//   --refine-gap S                       after each settled drag step a refine starts, as the
//                                        studio's does, and the next edit comes S seconds later
//                                        (a drag that pauses), cutting it short
//   --on-screen                          keeps every published shape and prints, for both drags,
//                                        how far the shape on screen one to four frames after
//                                        each edit is from the settled one (before the first
//                                        shape: the document's warm start of the edit; the
//                                        copies cost the worker about 0.1 ms a shape)

#include "BenchScenes.h"
#include "InstructionSet.h"
#include "commands/Document.h"
#include "commands/HeapSettings.h"
#include "geometry/ShapeHash.h"
#include "interaction/DemoScenes.h"
#include "interaction/LiveRelaxer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

using namespace netsculpt;

namespace {

using Clock = std::chrono::steady_clock;
using bench::largestDistance;
using bench::secondsSince;
constexpr double kFrameSeconds = 1.0 / 30;

/// Waits until the run for `generation` has ended; returns its final state.
std::shared_ptr<const LiveState> awaitRun(const LiveRelaxer& live, std::uint64_t generation) {
    for (;;) {
        live.waitIdle(1.0);
        const auto state = live.latest();
        if (state && state->generation == generation && !state->running)
            return state;
    }
}

/// When the shapes of each run were published (LiveState::seconds, from the run's start), and with
/// keepShapes the shapes themselves, until taken.
class PublicationLog {
  public:
    explicit PublicationLog(bool keepShapes) : keepShapes_(keepShapes) {}
    bool keepsShapes() const { return keepShapes_; }
    /// A shape counts once: the end of a run publishes again the positions of its last report.
    void record(const LiveState& state) {
        if (state.positions.empty())
            return;
        std::lock_guard lock(mutex_);
        if (!times_.empty() && times_.back().generation == state.generation &&
            times_.back().steps == state.steps)
            return;
        times_.push_back({state.generation, state.steps, state.seconds});
        if (keepShapes_)
            shapes_.push_back({state.generation, state.seconds, state.positions});
    }
    /// Publication times of one run, in order.
    std::vector<double> of(std::uint64_t generation) const {
        std::lock_guard lock(mutex_);
        std::vector<double> times;
        for (const Entry& entry : times_)
            if (entry.generation == generation)
                times.push_back(entry.seconds);
        return times;
    }
    struct Shape {
        std::uint64_t generation;
        double seconds;
        std::vector<Vec3> positions;
    };
    /// The shapes kept of one run, in order; the log forgets them.
    std::vector<Shape> takeShapes(std::uint64_t generation) {
        std::lock_guard lock(mutex_);
        std::vector<Shape> taken, kept;
        for (Shape& shape : shapes_)
            (shape.generation == generation ? taken : kept).push_back(std::move(shape));
        shapes_ = std::move(kept);
        return taken;
    }

  private:
    struct Entry {
        std::uint64_t generation;
        std::int64_t steps;
        double seconds;
    };
    const bool keepShapes_;
    mutable std::mutex mutex_;
    std::vector<Entry> times_;
    std::vector<Shape> shapes_;
};

/// What the screen shows during a step's re-relaxation, against the shape it settles in: per
/// step, the largest distance of any knot from its settled place in the shape on screen k frames
/// after the edit began (the last shape published by then, or the one before the edit).
struct ShownDistances {
    static constexpr int kFrames = 4;
    std::vector<double> atFrame[kFrames]; ///< m, per step, 1 ... kFrames frames after the edit
    std::vector<double> moved; ///< m, per step: the settled shape against the one at the edit
    /// `shapes` are one run's publications (seconds from the run's start), which began
    /// `editSeconds` after the edit; `before` the shape shown at the edit (the document's warm
    /// start), `settled` the last.
    void add(const std::vector<PublicationLog::Shape>& shapes, double editSeconds,
             const std::vector<Vec3>& before, const std::vector<Vec3>& settled) {
        moved.push_back(largestDistance(before, settled));
        for (int k = 1; k <= kFrames; ++k) {
            const std::vector<Vec3>* shown = &before;
            for (const auto& shape : shapes)
                if (editSeconds + shape.seconds <= k * kFrameSeconds &&
                    shape.positions.size() == settled.size())
                    shown = &shape.positions;
            atFrame[k - 1].push_back(largestDistance(*shown, settled));
        }
    }
};

/// When the shapes of runs came: the first after the run's start, the intervals after it.
struct Publications {
    std::vector<double> first; ///< per run, s from its start to its first shape
    std::vector<double> gaps;  ///< s between consecutive shapes of one run
    void add(const std::vector<double>& times) {
        if (times.empty())
            return;
        first.push_back(times.front());
        for (std::size_t i = 1; i < times.size(); ++i)
            gaps.push_back(times[i] - times[i - 1]);
    }
};

struct StepTiming {
    double editSeconds = 0;    ///< the command: validation, recompilation, warm start
    double relaxSeconds = 0;   ///< preview() to the converged shape published
    bool converged = false;
    std::int64_t steps = 0;    ///< the backend's steps (Newton iterations for the fast one)
};

/// Relaxes the document's current system as the studio does after an edit (`dragging`: a step
/// of a drag, the handle held); shows the result (copies the positions back, so the next edit
/// warm-starts from them).
StepTiming previewNow(Document& doc, LiveRelaxer& live, std::uint64_t generation, bool dragging) {
    StepTiming timing;
    const auto t0 = Clock::now();
    live.preview(doc.compiled().system, generation, dragging);
    const auto state = awaitRun(live, generation);
    timing.relaxSeconds = secondsSince(t0);
    timing.converged = state->converged;
    timing.steps = state->steps;
    if (state->positions.size() == doc.compiled().system.knotCount())
        doc.adoptPositions(state->positions, false);
    return timing;
}

double percentile(std::vector<double> values, double p) {
    std::sort(values.begin(), values.end());
    const auto i = static_cast<std::size_t>(p * static_cast<double>(values.size() - 1) + 0.5);
    return values[i];
}

void printPublications(const char* what, const Publications& p) {
    if (p.first.empty())
        return;
    std::printf("  %s: %zu run(s), %zu shapes; first shape after the run's start median %.1f ms",
                what, p.first.size(), p.first.size() + p.gaps.size(), 1e3 * percentile(p.first, 0.5));
    if (!p.gaps.empty())
        std::printf(", then one every %.1f ms (median; max %.1f ms, %.0f shapes/s)",
                    1e3 * percentile(p.gaps, 0.5), 1e3 * *std::max_element(p.gaps.begin(), p.gaps.end()),
                    1 / percentile(p.gaps, 0.5));
    std::printf("\n");
}

void printShownDistances(const ShownDistances& d) {
    if (d.moved.empty())
        return;
    std::printf("  on screen k frames after the edit, the largest distance of a knot from its "
                "settled place, median (90%%) over %zu steps:", d.moved.size());
    for (int k = 1; k <= ShownDistances::kFrames; ++k)
        std::printf("%s k=%d %.2g (%.2g) mm", k == 1 ? "" : ",", k,
                    1e3 * percentile(d.atFrame[k - 1], 0.5),
                    1e3 * percentile(d.atFrame[k - 1], 0.9));
    std::printf("; a step moves a knot by up to %.3g (%.3g) mm\n", 1e3 * percentile(d.moved, 0.5),
                1e3 * percentile(d.moved, 0.9));
}

/// A drag of `steps` steps, each settled before the next; with refineGap >= 0 a refine starts
/// after each settled step and the next edit comes that many seconds later.
void runDrag(const char* name, Document& doc, LiveRelaxer& live, PublicationLog& log,
             std::uint64_t& generation, int steps, double refineGap,
             const std::function<Command(int)>& commandAt) {
    std::vector<double> edit, relax, total, iterations;
    Publications shown;
    ShownDistances distances;
    int converged = 0, withinFrame = 0;
    for (int step = 1; step <= steps; ++step) {
        const auto t0 = Clock::now();
        doc.execute(commandAt(step), /*merge=*/true);
        const double editSeconds = secondsSince(t0);
        // On screen until the preview's first shape: the document's warm start of the edit (the
        // shape before it, new rows where the document places them).
        const std::vector<Vec3> atEdit =
            log.keepsShapes() ? doc.compiled().system.position : std::vector<Vec3>{};
        const StepTiming timing = previewNow(doc, live, ++generation, true);
        if (refineGap >= 0) { // the studio's refine after a settled preview, cut short by the drag
            live.refine(doc.compiled().system, ++generation);
            std::this_thread::sleep_for(std::chrono::duration<double>(refineGap));
        }
        shown.add(log.of(generation));
        if (log.keepsShapes()) // --on-screen
            distances.add(log.takeShapes(generation), editSeconds, atEdit,
                          doc.compiled().system.position);
        edit.push_back(editSeconds);
        relax.push_back(timing.relaxSeconds);
        iterations.push_back(static_cast<double>(timing.steps));
        total.push_back(editSeconds + timing.relaxSeconds);
        converged += timing.converged ? 1 : 0;
        withinFrame += editSeconds + timing.relaxSeconds <= kFrameSeconds ? 1 : 0;
    }
    doc.endGesture();
    // The shape after the drag, hashed bit for bit: the same on every run and thread count.
    const std::uint64_t hash = shapeHash(doc.compiled().system.position);
    std::printf("%-11s shape hash %016llx\n", name, static_cast<unsigned long long>(hash));
    std::printf("%-11s %5d steps  edit median %6.1f ms  re-relax median %6.1f ms (max %6.1f)  "
                "edit to shape median %6.1f ms, 90%% %6.1f ms  within one 30 fps frame: %d/%d  "
                "converged: %d/%d  steps median %.0f\n",
                name, steps, 1e3 * percentile(edit, 0.5), 1e3 * percentile(relax, 0.5),
                1e3 * *std::max_element(relax.begin(), relax.end()), 1e3 * percentile(total, 0.5),
                1e3 * percentile(total, 0.9), withinFrame, steps, converged, steps, percentile(iterations, 0.5));
    printPublications("shapes shown", shown);
    printShownDistances(distances);
}

constexpr double kVisibleMotion = 1e-4; ///< m: a knot moved by more than this is a new shape

/// A drag as fast as the frames: one step per frame (as a mouse moving a few pixels a frame gives),
/// each restarting the preview, the screen taking the current edit's latest shape at every frame
/// as the studio's frame loop does (App::syncLive). Counts the frames, during the drag, that showed
/// a new shape of the edit then current (a knot moved by more than kVisibleMotion), and times the
/// settling after the last step.
void runContinuousDrag(Document& doc, LiveRelaxer& live, std::uint64_t& generation, int steps,
                       const std::function<Command(int)>& commandAt) {
    const auto t0 = Clock::now();
    std::uint64_t seen = 0;
    int framesWithNewShape = 0, frames = 0;
    double lastEdit = 0;
    std::string ended;
    for (int frame = 0;; ++frame) {
        const std::chrono::duration<double> sinceStart(frame * kFrameSeconds);
        std::this_thread::sleep_until(t0 + std::chrono::duration_cast<Clock::duration>(sinceStart));
        const auto state = live.latest();
        const bool current = state && state->generation == generation;
        if (current && state->sequence != seen) {
            seen = state->sequence;
            const std::vector<Vec3>& shown = doc.compiled().system.position;
            if (state->positions.size() == shown.size()) {
                // a shape of the step made at the frame before, visibly moved
                if (frame <= steps && largestDistance(shown, state->positions) > kVisibleMotion)
                    ++framesWithNewShape;
                doc.adoptPositions(state->positions, false);
            }
        }
        if (frame >= steps && current && !state->running) {
            ended = state->stopReason;
            break;
        }
        if (frame < steps) {
            doc.execute(commandAt(frame + 1), /*merge=*/true);
            live.preview(doc.compiled().system, ++generation, true);
            lastEdit = secondsSince(t0);
            frames = frame + 1;
        }
    }
    doc.endGesture();
    std::printf("continuous  %d steps, one a frame: %d of the %d frames after them showed a new "
                "shape of the step then current (a knot moved by more than 0.1 mm); the last step "
                "settled (%s) %.2f s after it, to the frame\n",
                frames, framesWithNewShape, frames, ended.c_str(), secondsSince(t0) - lastEdit);
}

/// The sheet's last row connected to its lower rail ("bottom") after it has settled hanging
/// from the top one: one edit that swings the whole sheet into its U.
void runConnect(Document& doc, LiveRelaxer& live, PublicationLog& log,
                std::uint64_t& generation, PieceId piece) {
    RailId bottom;
    for (const auto& [id, rail] : doc.sculpture().rails)
        if (rail.name == "bottom")
            bottom = id;
    const auto t0 = Clock::now();
    doc.execute(ConnectToRailCommand{piece, bottom, 0.0, false});
    const double editSeconds = secondsSince(t0);
    const StepTiming timing = previewNow(doc, live, ++generation, false); // on the release
    std::printf("connect     edit %.1f ms  re-relax %.2f s (%s, %lld steps)\n", 1e3 * editSeconds,
                timing.relaxSeconds, timing.converged ? "converged" : "not converged",
                static_cast<long long>(timing.steps));
    Publications shown;
    shown.add(log.of(generation));
    printPublications("shapes shown", shown);
}

} // namespace

int main(int argc, char** argv) {
    keepFreedMemoryForReuse(); // as the studio does
    int knots = 20000, steps = 20;
    std::string only;
    bool sheet = false, connect = false, onScreen = false, continuous = false;
    double refineGap = -1;
    LiveRelaxOptions options; // the studio's
    options.threads = threadsBesideTheFrames();
    options.settleThreads = threadsForSettling();
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--knots" && i + 1 < argc)
            knots = std::atoi(argv[++i]);
        else if (arg == "--steps" && i + 1 < argc)
            steps = std::atoi(argv[++i]);
        else if (arg == "--threads" && i + 1 < argc)
            options.threads = std::atoi(argv[++i]);
        else if (arg == "--settle-threads" && i + 1 < argc)
            options.settleThreads = std::atoi(argv[++i]);
        else if (arg == "--sheet")
            sheet = true;
        else if (arg == "--connect")
            sheet = connect = true;
        else if (arg == "--refine-gap" && i + 1 < argc)
            refineGap = std::atof(argv[++i]);
        else if (arg == "--continuous")
            continuous = true;
        else if (arg == "--on-screen")
            onScreen = true;
        else if (arg == "--double-steps")
            options.singlePrecisionSteps = false;
        else if (arg == "--preview-scale" && i + 1 < argc)
            options.previewStiffnessScale = std::atof(argv[++i]);
        else if (arg == "--backend" && i + 1 < argc)
            options.backend = argv[++i];
        else if (arg == "--only" && i + 1 < argc && (std::string(argv[i + 1]) == "bar" ||
                                                     std::string(argv[i + 1]) == "rows"))
            only = argv[++i];
        else {
            std::fprintf(stderr,
                         "usage: %s [--knots N] [--steps N] [--backend NAME] "
                         "[--preview-scale S] [--threads N] [--settle-threads N] "
                         "[--sheet] [--double-steps] "
                         "[--only bar|rows] [--connect] [--continuous] [--on-screen] "
                         "[--refine-gap S]\n",
                         argv[0]);
            return 2;
        }
    }
    if (knots < 100 || steps < 1 || options.threads < 1 || options.settleThreads < 1) {
        std::fprintf(stderr, "netsculpt-bench-live: --knots must be >= 100, --steps, --threads "
                             "and --settle-threads >= 1\n");
        return 2;
    }
    try {
        Document doc;
        if (sheet)
            buildLargeSlackSheet(doc, knots, !connect);
        else
            buildLargeDemoSculpture(doc, knots);
        const PieceId piece = doc.sculpture().pieces.begin()->first;
        const Piece start = doc.sculpture().pieces.begin()->second;
        const MassSpringSystem& system = doc.compiled().system;
        const char* scene = connect ? "a sheet hanging from one of two rails"
                            : sheet ? "a slack sheet between two rails"
                                    : "the studio's demo tube";
        std::printf("netsculpt-bench-live: %s, %zu knots, %zu bars, %d x %d; "
                    "preview backend %s, stiffness x%.3g, tolerance %.0e, %d thread(s) (%d for "
                    "runs no drag waits on), hinted steps in %s precision; built for %s\n",
                    scene, system.knotCount(), system.barCount(), start.rows, start.columns,
                    options.backend.c_str(), previewScale(system, options.previewStiffnessScale),
                    options.previewTolerance, options.threads, options.settleThreads,
                    options.singlePrecisionSteps ? "single" : "double", bench::instructionSet());
        PublicationLog log(onScreen);
        options.onPublish = [&log](const LiveState& state) { log.record(state); };
        LiveRelaxer live(options);
        std::uint64_t generation = 1;
        const StepTiming settle = previewNow(doc, live, generation, false);
        std::printf("first settle from the Eq. 2 start: %.2f s (%s, %lld steps)\n",
                    settle.relaxSeconds, settle.converged ? "converged" : "not converged",
                    static_cast<long long>(settle.steps));
        Publications settling;
        settling.add(log.of(generation));
        printPublications("shapes shown while it settles", settling);
        if (connect) {
            runConnect(doc, live, log, generation, piece);
            return 0;
        }
        const double bar = start.bar.at(0);
        const int rows = doc.sculpture().pieces.at(piece).rows;
        if (continuous) {
            runContinuousDrag(doc, live, generation, steps, [&](int step) -> Command {
                if (only == "rows")
                    return SetRowsCommand{piece, rows + step};
                return SetBarLengthCommand{piece, std::nullopt, std::nullopt,
                                           bar * (1 + 0.001 * step)};
            });
            return 0;
        }
        if (only != "rows")
            runDrag("bar length", doc, live, log, generation, steps, refineGap,
                    [&](int step) -> Command {
                        return SetBarLengthCommand{piece, std::nullopt, std::nullopt,
                                                   bar * (1 + 0.005 * step)};
                    });
        if (only != "bar")
            runDrag("rows", doc, live, log, generation,
                    only == "rows" ? steps : std::max(1, steps / 2), refineGap,
                    [&](int step) -> Command { return SetRowsCommand{piece, rows + step}; });
    } catch (const std::exception& e) {
        std::fprintf(stderr, "netsculpt-bench-live: %s\n", e.what());
        return 1;
    }
    return 0;
}
