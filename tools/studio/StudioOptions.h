#pragma once
// netsculpt-studio's command line.

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace netsculpt::studio {

struct StudioOptions {
    std::optional<std::filesystem::path> script;     ///< --script FILE.lua: build the sculpture with a script
    std::optional<std::filesystem::path> open;       ///< --open JOURNAL: start from a saved design
    bool demo = false;                               ///< --demo: start from the built-in demo sculpture
    int demoKnots = 0;                               ///< --demo-knots N: a one-tube demo of about N knots
    std::optional<std::filesystem::path> play;       ///< --play EVENTS: replay recorded window events
    std::optional<std::filesystem::path> screenshot; ///< --screenshot out.png after the last frame
    int exitAfterFrames = -1;                        ///< --exit-after-frames N; -1 = run until closed
    std::optional<std::filesystem::path> journal;    ///< --journal PATH; default: the session journal
    int width = 1280, height = 800;                  ///< --size WxH, px
    bool relax = true;                               ///< --no-relax: show the initial geometry only
    double settleSeconds = 0;                        ///< --settle S: before the screenshot, wait for the relaxation
    int samples = -1; ///< --samples N: multisample anti-aliasing (0 = off); -1 = 4, or 0 on a software renderer
    bool vsync = true;                               ///< --no-vsync (implied by --play)
    std::optional<std::string> printHandles;         ///< --print-handles MODE: pixel positions after frame 1
    std::string colourBy = "piece";                  ///< --colour piece|tension
    bool help = false;                               ///< --help, -h: print the usage, start nothing
};

/// The session journal when --journal is not given: $XDG_DATA_HOME/netsculpt/session.netj, or
/// ~/.local/share/netsculpt/session.netj.
std::filesystem::path defaultSessionJournal();

/// Parses argv. Throws UserError naming the bad argument. --help stops the parse: `help` set,
/// nothing after it read.
StudioOptions parseStudioOptions(const std::vector<std::string>& args);
std::string studioUsage();

/// The command line as main() acts on it: the options to start with, or the status to exit with.
struct CommandLine {
    StudioOptions options;
    std::optional<int> exitStatus; ///< set: start nothing, exit with it
};

/// Reads `args` (argv after the program's name): after --help the usage is on `out` and the exit
/// status 0; after a bad argument the error is on `err` as netsculpt words a usage error
/// ("netsculpt-studio: error: <what>", then "Run with --help for more information.") and the
/// exit status 2.
CommandLine readCommandLine(const std::vector<std::string>& args, std::ostream& out,
                            std::ostream& err);

} // namespace netsculpt::studio
