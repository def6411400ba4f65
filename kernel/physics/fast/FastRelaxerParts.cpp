// FastRelaxer's independent parts and focus regions (NewtonRelaxer.h): each relaxed as a system
// of its own by a relaxer of its own, its statistics added to the whole's.
#include "physics/fast/NewtonRelaxer.h"

#include "physics/Forces.h"
#include "physics/fast/Components.h"
#include "physics/fast/FocusRegion.h"
#include "physics/fast/NewtonRun.h"

#include <algorithm>
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
    whole.focusRegions += part.focusRegions;
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
    std::vector<Vec3> shown; // the whole system's positions for progress reports
    if (options.progress)
        shown = system.position;
    std::vector<std::int64_t> scratch;
    std::vector<double> tensions;
    std::vector<Vec3> force(system.knotCount());
    whole.evaluate(system.position, force);
    ++result.forceEvaluations;
    for (std::size_t c = 0; c < components.size(); ++c) {
        if (!(options.maxSeconds - secondsSince(start) > 0)) {
            result.stopReason = "time limit";
            break;
        }
        if (inEquilibrium(whole, force, components[c], options.tolerance)) {
            ++statistics_.partsInEquilibrium; // untouched by an edit: no step, no analysis
            continue;
        }
        Part part = extractPart(system, components[c], scratch);
        const RelaxOptions partOptions = partOptionsFor(
            options, part, c + 1 == components.size(), result.steps, start, tensions, shown);
        const RelaxResult partResult = parts_[c]->relax(part.system, partOptions);
        for (std::size_t k = 0; k < part.knotOf.size(); ++k)
            system.position[part.knotOf[k]] = part.system.position[k];
        result.steps += partResult.steps;
        result.forceEvaluations += partResult.forceEvaluations;
        addPart(statistics_, parts_[c]->statistics());
        if (!partResult.converged && result.stopReason.empty())
            result.stopReason = partResult.stopReason;
        const std::string& why = partResult.stopReason;
        if (why == "time limit" || why == "step limit" || why == "cancelled")
            break; // the other parts keep their start
    }
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

RelaxResult FastRelaxer::relaxRegion(MassSpringSystem& system, const RelaxOptions& options,
                                     TimePoint start, const std::vector<std::uint32_t>& region,
                                     double tolerance, double blend,
                                     std::int64_t stepsBefore) {
    std::vector<std::int64_t> scratch;
    Part part = newton::regionSystem(system, region, blend, scratch);
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
    const RelaxResult result = focus_->relax(part.system, regionOptions);
    for (std::size_t k = 0; k < part.knotOf.size(); ++k)
        system.position[part.knotOf[k]] = part.system.position[k];
    const char* ordering = statistics_.ordering; // the system's own analysis, not the region's
    addPart(statistics_, focus_->statistics());
    statistics_.ordering = ordering;
    ++statistics_.focusRegions;
    return result;
}

} // namespace netsculpt
