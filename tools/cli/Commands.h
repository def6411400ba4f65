#pragma once
// The netsculpt subcommands. Each returns the process exit code (0 success); user errors are
// thrown as UserError and reported by main() as "netsculpt: error: ..." with exit code 1.

#include "Progress.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace netsculpt::cli {

struct RunArgs {
    std::filesystem::path script;
    std::vector<std::string> args;   ///< the script's arguments (arg[1..])
    std::filesystem::path out; ///< the output folder (created when missing); empty: out/<script>
    bool unsafe = false;
    std::vector<std::filesystem::path> libraries; ///< --lib: folders of shared Lua modules
    double maxMemoryMiB = 512;    ///< 0 = no limit
    double maxInstructions = 1e9; ///< 0 = no budget
    double maxSeconds = 0;        ///< wall-clock limit of the whole run, s; 0 = none
    std::string backend;          ///< overrides every doc:relax; empty = the script's
    bool journal = true;
};
int runScript(const RunArgs& a, Verbosity verbosity);

int replayJournal(const std::filesystem::path& journal, const std::filesystem::path& out,
                  Verbosity verbosity);
int journalToLua(const std::filesystem::path& journal);

struct RelaxArgs {
    std::filesystem::path document;
    std::string backend = "auto";
    double tolerance = 1e-6;
    double maxSeconds = 60;
    std::int64_t maxSteps = -1;
    std::filesystem::path out = ".";
};
/// The exit code of a relax that stopped short of its tolerance (its shape is written all the
/// same), so that a script signing off a design can tell.
constexpr int kExitNotConverged = 3;
/// Relaxes and writes the snapshot: 0, or kExitNotConverged; warns on stderr when the relaxed
/// shape stretches bars beyond what rope can (the report's "Check the design").
int relaxDocument(const RelaxArgs& a, Verbosity verbosity);

struct ExportArgs {
    std::filesystem::path document;
    std::vector<std::filesystem::path> files;
    std::string colourBy = "piece";
    double tubeRadius = 0;
    int width = 1600;
    int height = 1200;
    std::string view = "all";
    /// Relax a shape that is not an equilibrium first (as report does); false: as it is.
    bool relaxFirst = true;
    /// Write the rails alone (exportRailsFile: .csv, .obj, .dxf); nothing is relaxed.
    bool rails = false;
};
/// Writes the files: 0, or kExitNotConverged when the relaxation it ran stopped short.
int exportDocument(const ExportArgs& a, Verbosity verbosity);

enum class ReportFormat { Markdown, Json, PiecesCsv, AttachmentsCsv };
struct ReportArgs {
    std::filesystem::path document;
    ReportFormat format = ReportFormat::Markdown;
    /// Relax a shape that is not an equilibrium before reporting it (a journal holds none: its
    /// loads would be those of the Eq. 2 start); false: report it as it is, with a warning.
    bool relaxFirst = true;
};
/// Prints the report: 0, or kExitNotConverged when the relaxation it ran stopped short.
int reportDocument(const ReportArgs& a, Verbosity verbosity);

} // namespace netsculpt::cli
