#include "StudioOptions.h"

#include "interaction/Handles.h"
#include "model/Error.h"

#include <charconv>
#include <cstdlib>

namespace netsculpt::studio {

namespace {

/// The exit status of a usage error, as netsculpt's (tools/cli/README.md).
constexpr int kExitUsageError = 2;

int parseInt(const std::string& text, const std::string& option, int lo, int hi) {
    int value = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size() || value < lo || value > hi)
        throw UserError(option + " expects a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                        ", got \"" + text + "\"");
    return value;
}

/// A number of seconds, fractions allowed ("0.5").
double parseSeconds(const std::string& text, const std::string& option, double lo, double hi) {
    double value = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size() || !(value >= lo && value <= hi))
        throw UserError(option + " expects a number of seconds from " + std::to_string(int(lo)) +
                        " to " + std::to_string(int(hi)) + ", got \"" + text + "\"");
    return value;
}

} // namespace

std::string studioUsage() {
    return "usage: netsculpt-studio [--script FILE.lua | --open FILE | --demo | --demo-knots N]\n"
           "                        [--play EVENTS] [--screenshot OUT.png] [--exit-after-frames N]\n"
           "                        [--journal PATH] [--size WxH] [--no-relax] [--settle SECONDS]\n"
           "                        [--no-vsync] [--samples N] [--colour piece|tension]\n"
           "                        [--print-handles MODE]\n";
}

std::filesystem::path defaultSessionJournal() {
    std::filesystem::path base;
    if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg) base = xdg;
    else if (const char* home = std::getenv("HOME"); home && *home) base = std::filesystem::path(home) / ".local/share";
    else base = std::filesystem::temp_directory_path();
    return base / "netsculpt" / "session.netj";
}

StudioOptions parseStudioOptions(const std::vector<std::string>& args) {
    StudioOptions o;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size())
                throw UserError(a + " needs a value");
            return args[++i];
        };
        if (a == "--script") o.script = value();
        else if (a == "--open") o.open = value();
        else if (a == "--demo") o.demo = true;
        else if (a == "--demo-knots") o.demoKnots = parseInt(value(), a, 16, 2'000'000);
        else if (a == "--play") o.play = value();
        else if (a == "--screenshot") o.screenshot = value();
        else if (a == "--exit-after-frames") o.exitAfterFrames = parseInt(value(), a, 1, 100'000'000);
        else if (a == "--journal") o.journal = value();
        else if (a == "--no-relax") o.relax = false;
        else if (a == "--no-vsync") o.vsync = false;
        else if (a == "--samples") o.samples = parseInt(value(), a, 0, 16);
        else if (a == "--settle") o.settleSeconds = parseSeconds(value(), a, 0, 3600);
        else if (a == "--colour" || a == "--color") {
            o.colourBy = value();
            if (o.colourBy != "piece" && o.colourBy != "tension")
                throw UserError("--colour expects piece or tension, got \"" + o.colourBy + "\"");
        } else if (a == "--print-handles") {
            o.printHandles = value();
            bool known = false;
            for (Mode m : kAllModes) known = known || modeName(m) == *o.printHandles;
            if (!known) throw UserError("--print-handles expects a mode: view, new net, divide, rows, columns, bar length, connect");
        } else if (a == "--size") {
            const std::string& v = value();
            const auto x = v.find('x');
            if (x == std::string::npos) throw UserError("--size expects WxH, e.g. 1280x800, got \"" + v + "\"");
            o.width = parseInt(v.substr(0, x), "--size width", 64, 16384);
            o.height = parseInt(v.substr(x + 1), "--size height", 64, 16384);
        } else if (a == "--help" || a == "-h") {
            o.help = true;
            return o;
        } else {
            throw UserError("unknown argument \"" + a + "\"");
        }
    }
    const int sources = int(o.script.has_value()) + int(o.open.has_value()) + int(o.demo || o.demoKnots > 0);
    if (sources > 1)
        throw UserError("give at most one of --script, --open and --demo");
    if (o.play) o.vsync = false;
    return o;
}

CommandLine readCommandLine(const std::vector<std::string>& args, std::ostream& out,
                            std::ostream& err) {
    CommandLine commandLine;
    try {
        commandLine.options = parseStudioOptions(args);
    } catch (const UserError& e) {
        err << "netsculpt-studio: error: " << e.what()
            << "\nRun with --help for more information.\n";
        commandLine.exitStatus = kExitUsageError;
        return commandLine;
    }
    if (commandLine.options.help) {
        out << studioUsage();
        commandLine.exitStatus = 0;
    }
    return commandLine;
}

} // namespace netsculpt::studio
