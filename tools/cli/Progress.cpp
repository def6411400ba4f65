#include "Progress.h"

#include "model/Error.h"
#include "model/Ids.h"

#include <cstdio>
#include <unistd.h>

namespace netsculpt::cli {

namespace {

std::string seconds(double s) {
    char text[32];
    if (s < 60)
        std::snprintf(text, sizeof text, "%.1f s", s);
    else
        std::snprintf(text, sizeof text, "%d min %02d s", int(s / 60), int(s) % 60);
    return text;
}

} // namespace

ProgressLine::ProgressLine(Verbosity verbosity)
    : enabled_(verbosity != Verbosity::Quiet && isatty(fileno(stderr)) != 0),
      verbose_(verbosity == Verbosity::Verbose) {}

void ProgressLine::update(const RelaxProgress& p) {
    if (!enabled_)
        return;
    char line[160];
    const std::string left =
        p.estimatedSecondsLeft >= 0 ? ", about " + seconds(p.estimatedSecondsLeft) + " left" : "";
    std::snprintf(line, sizeof line, "relaxing: residual %.2e, %lld steps, %s%s", p.residual,
                  static_cast<long long>(p.steps), seconds(p.seconds).c_str(), left.c_str());
    std::fprintf(stderr, "\r%s\033[K", line);
    std::fflush(stderr);
    shown_ = true;
}

void ProgressLine::clear() {
    if (!shown_)
        return;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    shown_ = false;
}

void ProgressLine::finish(const RelaxResult& result) {
    clear();
    if (verbose_)
        std::fprintf(stderr, "netsculpt: relaxation %s\n", describeRelaxResult(result).c_str());
}

std::string describeRelaxResult(const RelaxResult& r) {
    char text[200];
    const char* how = r.converged ? "converged" : "stopped";
    // The CLI's relaxations are cancelled by Ctrl-C only (Interrupt.h).
    const std::string why = r.stopReason == "cancelled" ? "Ctrl-C" : r.stopReason;
    std::snprintf(text, sizeof text, "%s%s%s%s after %lld steps, %s, residual %.3g (%s)", how,
                  r.converged ? "" : " (", r.converged ? "" : why.c_str(), r.converged ? "" : ")",
                  static_cast<long long>(r.steps), seconds(r.seconds).c_str(), r.residual,
                  r.backend.c_str());
    std::string described = text;
    if (r.unsettledAt)
        described += ", largest at " + toString(r.unsettledAt->piece) + " row " +
                     std::to_string(r.unsettledAt->row) + " column " +
                     std::to_string(r.unsettledAt->column);
    // The floor is set by the rope's stiffness against a unit in the last place of the knots'
    // coordinates: about 4e-8 knot weights for real rope on a 2 m tube 5 m up, more for a net
    // reaching 100 m and beyond from the middle of its rails.
    if (r.stopReason == "precision limit")
        described += "; the knots are as near the equilibrium as their coordinates can be written, "
                     "which is above the tolerance " +
                     formatNumber(r.tolerance) + ": relax with a tolerance above the residual";
    return described;
}

} // namespace netsculpt::cli
