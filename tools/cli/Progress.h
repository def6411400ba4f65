#pragma once
// The progress line of long work (relaxation) on a terminal: residual, steps, time and the
// estimated time left, rewritten in place with \r on stderr. Quiet when stderr is not a terminal
// or with --quiet; with --verbose every relaxation also ends with a summary line.

#include "physics/Relaxer.h"

#include <string>

namespace netsculpt::cli {

enum class Verbosity { Quiet, Normal, Verbose };

class ProgressLine {
  public:
    /// Shows progress when `verbosity` is not Quiet and stderr is a terminal.
    explicit ProgressLine(Verbosity verbosity);
    void update(const RelaxProgress& progress);
    /// Clears the line; in verbose mode prints a summary of the result.
    void finish(const RelaxResult& result);
    /// Clears the line only, for a command whose output is the result itself.
    void clear();
    bool enabled() const { return enabled_; }

  private:
    bool enabled_ = false;
    bool verbose_ = false;
    bool shown_ = false;
};

/// "converged in 1234 steps, 2.1 s, residual 8.1e-07 (rk4)" / "stopped (time limit) after ...".
std::string describeRelaxResult(const RelaxResult& result);

} // namespace netsculpt::cli
