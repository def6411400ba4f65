// FastRelaxer's independent parts and focus regions (NewtonRelaxer.h): each relaxed as a system
// of its own by a relaxer of its own, its statistics added to the whole's.
#include "physics/fast/NewtonRelaxer.h"

#include "physics/Forces.h"
#include "physics/ThreadPool.h"
#include "physics/fast/Components.h"
#include "physics/fast/FocusRegion.h"
#include "physics/fast/NewtonRun.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <string>
#include <vector>

namespace netsculpt {

using newton::Clock;
using newton::secondsSince;

namespace {

/// Adds a part's run to the statistics of the whole (factorFlops: the mean per factorization).
void addPart(NewtonStatistics& whole, const NewtonStatistics& part) {
    const double flopsBefore = whole.factorFlops * static_cast<double>(whole.factorizations);
    whole.softIterations += part.softIterations;
    whole.hintIterations += part.hintIterations;
    whole.iterations += part.iterations;
    whole.factorizations += part.factorizations;
    whole.failedFactorizations += part.failedFactorizations;
    whole.singleFactorizations += part.singleFactorizations;
    whole.focusRegions += part.focusRegions;
    whole.softFocusRegions += part.softFocusRegions;
    whole.stallFocusRegions += part.stallFocusRegions;
    whole.softScale = std::min(whole.softScale, part.softScale);
    whole.reusedAnalysis = whole.reusedAnalysis && part.reusedAnalysis;
    whole.analysisSeconds += part.analysisSeconds;
    whole.factorSeconds += part.factorSeconds;
    whole.solveSeconds += part.solveSeconds;
    const double partFlops = part.factorFlops * static_cast<double>(part.factorizations);
    if (whole.factorizations > 0)
        whole.factorFlops =
            (flopsBefore + partFlops) / static_cast<double>(whole.factorizations);
    if (*whole.ordering == '\0')
        whole.ordering = part.ordering;
    else if (std::string(whole.ordering) != part.ordering)
        whole.ordering = "mixed";
}

/// A part's options: what is left of the whole run's time and steps, its bars' share of the
/// tension hint (in `tensions`), and progress reports that show the whole net (`shown`: the
/// whole system's positions, kept up to date with the part's) with the steps of the parts before.
RelaxOptions partOptionsFor(const RelaxOptions& options, const Part& part, bool lastPart,
                            std::int64_t stepsBefore, newton::Clock::time_point start,
                            std::vector<double>& tensions, std::vector<Vec3>& shown) {
    RelaxOptions partOptions = options;
    partOptions.maxSeconds = options.maxSeconds - secondsSince(start);
    if (options.maxSteps >= 0) // a part already in equilibrium converges with none left
        partOptions.maxSteps = std::max<std::int64_t>(0, options.maxSteps - stepsBefore);
    if (!options.startTensions.empty()) {
        tensions.resize(part.barOf.size());
        for (std::size_t b = 0; b < part.barOf.size(); ++b)
            tensions[b] = options.startTensions[part.barOf[b]];
        partOptions.startTensions = tensions;
    }
    if (options.progress)
        partOptions.progress = [&options, &part, &shown, lastPart, stepsBefore,
                                start](const RelaxProgress& p) {
            for (std::size_t k = 0; k < p.positions.size() && k < part.knotOf.size(); ++k)
                shown[part.knotOf[k]] = p.positions[k];
            RelaxProgress wholeProgress = p;
            wholeProgress.steps += stepsBefore;
            wholeProgress.seconds = secondsSince(start);
            if (!lastPart)
                wholeProgress.estimatedSecondsLeft = -1;
            if (!p.positions.empty())
                wholeProgress.positions = shown;
            options.progress(wholeProgress);
        };
    return partOptions;
}

/// Whether every free knot of a part is below the tolerance in the whole system's `force` (the
/// same bits as in the part's own field): such a part takes no step, so it needs no analysis.
bool inEquilibrium(const ForceField& whole, const std::vector<Vec3>& force,
                   const std::vector<std::uint32_t>& freeKnots, double tolerance) {
    for (std::uint32_t j : freeKnots)
        if (!(whole.residualOf(j, force[j]) < tolerance))
            return false;
    return true;
}

/// A relaxed part's positions into the whole system, its steps, force passes, statistics and
/// (the first part's that did not converge) stop reason into the whole's.
void takePart(MassSpringSystem& system, const Part& part, const RelaxResult& partResult,
              const NewtonStatistics& partStatistics, RelaxResult& result,
              NewtonStatistics& statistics) {
    for (std::size_t k = 0; k < part.knotOf.size(); ++k)
        system.position[part.knotOf[k]] = part.system.position[k];
    result.steps += partResult.steps;
    result.forceEvaluations += partResult.forceEvaluations;
    addPart(statistics, partStatistics);
    if (!partResult.converged && result.stopReason.empty())
        result.stopReason = partResult.stopReason;
}

/// A part's stop after which no other part is started.
bool stopsTheRest(const std::string& why) {
    return why == "time limit" || why == "step limit" || why == "cancelled";
}

/// The threads a run may use: RelaxOptions::threads, or for 0 the machine's.
std::size_t runThreads(const RelaxOptions& options) {
    return options.threads > 0 ? static_cast<std::size_t>(options.threads)
                               : std::max(1u, std::thread::hardware_concurrency());
}

/// How many of the parts `toRelax` to relax at the same time, sharing the run's threads: one (in
/// turn, each with all of them) unless there are two or more parts, the run has two threads or
/// more, no step limit is set (its count would depend on the order in which parts at the same
/// time take their steps), and no part has more than kTogetherLargestShare of their free knots
/// (a part that large would be slower on its share of the threads than the others together).
/// Then, with a thread count given, at most that many at a time; with the automatic one (the
/// whole machine) every part at once, up to kPartsPerThread per thread: where there are more
/// parts than cores the system shares the cores among them, so that a part that takes long does
/// not leave a core idle at the end while the parts queued behind it run on the other; and the
/// last part left uses the cores the others freed (SharedCores).
std::size_t concurrentParts(const RelaxOptions& options,
                            const std::vector<std::vector<std::uint32_t>>& components,
                            const std::vector<std::size_t>& toRelax) {
    constexpr double kTogetherLargestShare = 0.6;
    constexpr std::size_t kPartsPerThread = 4;
    const std::size_t threads = runThreads(options);
    if (toRelax.size() < 2 || threads < 2 || options.maxSteps >= 0)
        return 1;
    std::size_t total = 0, largest = 0;
    for (std::size_t c : toRelax) {
        total += components[c].size();
        largest = std::max(largest, components[c].size());
    }
    if (static_cast<double>(largest) > kTogetherLargestShare * static_cast<double>(total))
        return 1;
    const std::size_t atOnce = options.threads > 0 ? threads : kPartsPerThread * threads;
    return std::min(atOnce, toRelax.size());
}

/// A part counted among those going on for as long as it lives.
class PartGoingOn {
  public:
    explicit PartGoingOn(SharedCores& cores) : cores_(cores) { cores_.enter(); }
    ~PartGoingOn() { cores_.leave(); }
    PartGoingOn(const PartGoingOn&) = delete;
    PartGoingOn& operator=(const PartGoingOn&) = delete;

  private:
    SharedCores& cores_;
};

} // namespace

RelaxResult FastRelaxer::relaxParts(MassSpringSystem& system, const RelaxOptions& options,
                                    const std::vector<std::vector<std::uint32_t>>& components,
                                    TimePoint start) {
    ForceField whole(system); // validates the system, naming problems by its own numbers
    whole.setLoad(options.wind);
    newton::checkStart(system, options);
    statistics_ = NewtonStatistics{};
    statistics_.parts = static_cast<std::int64_t>(components.size());
    statistics_.reusedAnalysis = true; // until a part makes its own
    while (parts_.size() < components.size())
        parts_.push_back(std::make_unique<FastRelaxer>());
    for (const auto& part : parts_) {
        part->setFocusRegions(focusRegions_);
        part->regionLevel_ = regionLevel_;
    }
    RelaxResult result;
    result.backend = "fast";
    result.tolerance = options.tolerance;
    std::vector<Vec3> force(system.knotCount());
    whole.evaluate(system.position, force);
    ++result.forceEvaluations;
    std::vector<std::size_t> toRelax; // the parts out of balance
    for (std::size_t c = 0; c < components.size(); ++c) {
        if (inEquilibrium(whole, force, components[c], options.tolerance))
            ++statistics_.partsInEquilibrium; // untouched by an edit: no step, no analysis
        else
            toRelax.push_back(c);
    }
    const std::size_t workers = concurrentParts(options, components, toRelax);
    statistics_.partsTogether = static_cast<std::int64_t>(workers);
    if (workers > 1)
        relaxPartsTogether(system, options, components, toRelax, workers, start, result);
    else
        relaxPartsInTurn(system, options, components, toRelax, start, result);
    // Judged by the project's own measure on exactly the positions returned (the field's
    // maxResidual has the bits of residual()).
    whole.evaluate(system.position, force);
    result.residual = whole.maxResidual(force);
    ++result.forceEvaluations;
    result.converged = result.stopReason.empty() && result.residual < options.tolerance;
    if (result.stopReason.empty())
        result.stopReason = result.converged ? "converged" : "precision limit";
    result.seconds = secondsSince(start);
    return result;
}

void FastRelaxer::relaxPartsInTurn(MassSpringSystem& system, const RelaxOptions& options,
                                   const std::vector<std::vector<std::uint32_t>>& components,
                                   const std::vector<std::size_t>& toRelax, TimePoint start,
                                   RelaxResult& result) {
    std::vector<Vec3> shown; // the whole system's positions for progress reports
    if (options.progress)
        shown = system.position;
    std::vector<std::int64_t> scratch;
    std::vector<double> tensions;
    for (std::size_t c : toRelax) {
        if (!(options.maxSeconds - secondsSince(start) > 0)) {
            result.stopReason = "time limit";
            break;
        }
        Part part = extractPart(system, components[c], scratch);
        const RelaxOptions partOptions = partOptionsFor(
            options, part, c == toRelax.back(), result.steps, start, tensions, shown);
        const RelaxResult partResult = parts_[c]->relax(part.system, partOptions);
        takePart(system, part, partResult, parts_[c]->statistics(), result, statistics_);
        if (stopsTheRest(partResult.stopReason))
            break; // the other parts keep their start
    }
}

void FastRelaxer::relaxPartsTogether(MassSpringSystem& system, const RelaxOptions& options,
                                     const std::vector<std::vector<std::uint32_t>>& components,
                                     const std::vector<std::size_t>& toRelax, std::size_t workers,
                                     TimePoint start, RelaxResult& result) {
    // Each part as a system of its own (its options and hint made when it starts); the largest
    // parts first, so that the small ones fill in at the end.
    const std::size_t count = toRelax.size();
    std::vector<Part> parts(count);
    std::vector<std::vector<double>> tensions(count);
    std::vector<std::int64_t> scratch;
    for (std::size_t i = 0; i < count; ++i)
        parts[i] = extractPart(system, components[toRelax[i]], scratch);
    std::vector<std::size_t> order(count);
    for (std::size_t i = 0; i < count; ++i)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return components[toRelax[a]].size() > components[toRelax[b]].size();
    });

    // The run's threads shared: each part's pool runs a task on the part's fair share of them
    // (on a machine of two, one thread while two parts or more go on, both for the last one).
    SharedCores cores(static_cast<int>(runThreads(options)));
    for (std::size_t c : toRelax)
        parts_[c]->sharedCores_ = &cores;

    // Progress reports: one at a time, the whole net as the parts have it, their steps summed.
    std::mutex reporting;
    std::vector<Vec3> shown = options.progress ? system.position : std::vector<Vec3>{};
    std::vector<std::int64_t> stepsOf(count, 0);
    std::vector<RelaxResult> results(count);
    std::vector<char> ran(count, 0);
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stopped{false}; // a part stopped for the time limit or a cancel
    std::exception_ptr failure;
    const auto work = [&] {
        for (std::size_t n = next++; n < count; n = next++) {
            const std::size_t i = order[n];
            if (stopped || !(options.maxSeconds - secondsSince(start) > 0))
                continue; // the part keeps its start
            RelaxOptions partOptions =
                partOptionsFor(options, parts[i], false, 0, start, tensions[i], shown);
            if (options.progress) // (in place of partOptionsFor's: one at a time, steps summed)
                partOptions.progress = [&, i](const RelaxProgress& p) {
                    const std::lock_guard<std::mutex> lock(reporting);
                    for (std::size_t k = 0; k < p.positions.size(); ++k)
                        shown[parts[i].knotOf[k]] = p.positions[k];
                    stepsOf[i] = p.steps;
                    RelaxProgress wholeProgress = p;
                    wholeProgress.steps = 0;
                    for (std::int64_t steps : stepsOf)
                        wholeProgress.steps += steps;
                    wholeProgress.seconds = secondsSince(start);
                    wholeProgress.estimatedSecondsLeft = -1;
                    if (!p.positions.empty())
                        wholeProgress.positions = shown;
                    options.progress(wholeProgress);
                };
            try {
                const PartGoingOn going(cores);
                results[i] = parts_[toRelax[i]]->relax(parts[i].system, partOptions);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(reporting);
                if (!failure)
                    failure = std::current_exception();
                stopped = true;
                continue;
            }
            ran[i] = 1;
            if (stopsTheRest(results[i].stopReason))
                stopped = true;
        }
    };
    std::vector<std::thread> helpers;
    for (std::size_t t = 1; t < workers; ++t)
        helpers.emplace_back(work);
    work();
    for (std::thread& helper : helpers)
        helper.join();
    for (std::size_t c : toRelax)
        parts_[c]->sharedCores_ = nullptr;
    if (failure)
        std::rethrow_exception(failure);

    // The parts' results in the order of the parts, as in turn.
    for (std::size_t i = 0; i < count; ++i) {
        if (!ran[i]) {
            if (result.stopReason.empty())
                result.stopReason = options.cancel && options.cancel->load() ? "cancelled"
                                                                             : "time limit";
            continue;
        }
        takePart(system, parts[i], results[i], parts_[toRelax[i]]->statistics(), result,
                 statistics_);
    }
}

RelaxResult FastRelaxer::relaxRegion(MassSpringSystem& system, const RelaxOptions& options,
                                     TimePoint start, const std::vector<std::uint32_t>& region,
                                     double tolerance, double blend, double scale,
                                     std::int64_t stepsBefore) {
    std::vector<std::int64_t> scratch;
    Part part = newton::regionSystem(system, region, blend, scale, scratch);
    RelaxOptions withoutHint = options;
    withoutHint.startTensions = {};
    std::vector<double> tensions;
    std::vector<Vec3> shown;
    if (options.progress)
        shown = system.position;
    RelaxOptions regionOptions =
        partOptionsFor(withoutHint, part, false, stepsBefore, start, tensions, shown);
    regionOptions.tolerance = regionLevel_ ? tolerance : tolerance * newton::kFocusTolerance;
    regionOptions.continuation = false; // from where the stage left it
    regionOptions.maxSteps = regionOptions.maxSteps >= 0
                                 ? std::min(regionOptions.maxSteps, newton::kFocusMaxSteps)
                                 : newton::kFocusMaxSteps;
    if (!focus_) {
        focus_ = std::make_unique<FastRelaxer>();
        focus_->regionLevel_ = true;
    }
    focus_->sharedCores_ = sharedCores_;
    const RelaxResult result = focus_->relax(part.system, regionOptions);
    for (std::size_t k = 0; k < part.knotOf.size(); ++k)
        system.position[part.knotOf[k]] = part.system.position[k];
    const char* ordering = statistics_.ordering; // the system's own analysis, not the region's
    addPart(statistics_, focus_->statistics());
    statistics_.ordering = ordering;
    ++statistics_.focusRegions;
    if (scale < 1.0)
        ++statistics_.softFocusRegions;
    return result;
}

} // namespace netsculpt
