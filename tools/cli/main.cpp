// netsculpt: the command-line tool (tools/cli/README.md). Exit codes: 0 success, 1 user error
// ("netsculpt: error: ..."), 2 usage error, 3 a relaxation stopped short, 130 Ctrl-C.

#include "Commands.h"
#include "Interrupt.h"
#include "ParseErrors.h"
#include "commands/HeapSettings.h"

#include "model/Error.h"
#include "physics/Backends.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>
#include <memory>
#include <new>
#include <string_view>

#ifndef NETSCULPT_VERSION
#define NETSCULPT_VERSION "unknown"
#endif

namespace {

using namespace netsculpt;
using namespace netsculpt::cli;

struct Options {
    bool quiet = false;
    bool verbose = false;
    RunArgs run;
    std::filesystem::path journal;
    std::filesystem::path replayOut;
    RelaxArgs relax;
    ExportArgs exporting;
    ReportArgs report;
    bool reportJson = false;
    std::string reportCsv;
};

/// A number above 0 (or at least 0): CLI11's PositiveNumber and NonNegativeNumber name their
/// range instead, with its top written out in 309 digits ("not in range 0.000000 to 1797...").
CLI::Validator numberAbove(bool zeroAllowed) {
    const std::string allowed = zeroAllowed ? "a number >= 0" : "a number > 0";
    return CLI::Validator(
        [zeroAllowed, allowed](std::string& text) -> std::string {
            double value = 0;
            const bool number = CLI::detail::lexical_cast(text, value);
            if (number && std::isfinite(value) && (value > 0 || (zeroAllowed && value == 0)))
                return {};
            return "must be " + allowed + ", got " + text;
        },
        zeroAllowed ? "NUMBER >= 0" : "NUMBER > 0");
}

/// A relaxation tolerance: > 0 and at most kMaxTolerance.
CLI::Validator toleranceRange() {
    const std::string allowed = "a number > 0 and at most " + formatNumber(kMaxTolerance);
    return CLI::Validator(
        [allowed](std::string& text) -> std::string {
            double value = 0;
            const bool number = CLI::detail::lexical_cast(text, value);
            if (number && value > 0 && value <= kMaxTolerance)
                return {};
            return "must be " + allowed + ", got " + text;
        },
        "NUMBER in (0, " + formatNumber(kMaxTolerance) + "]");
}

/// A whole number from `lowest` to 10^15 (a count of steps or instructions).
CLI::Validator wholeNumberFrom(int lowest) {
    const std::string allowed = "a whole number from " + std::to_string(lowest) + " to 10^15";
    return CLI::Validator(
        [lowest, allowed](std::string& text) -> std::string {
            double value = 0;
            const bool number = CLI::detail::lexical_cast(text, value);
            if (number && value >= lowest && value <= 1e15 && value == std::floor(value))
                return {};
            return "must be " + allowed + ", got " + text;
        },
        "WHOLE NUMBER >= " + std::to_string(lowest));
}

/// CLI11's help, but a positional is listed as the usage line names it (DOC, FILE...) beside what
/// it is: CLI11 writes its type and whether it is required ("DOC TEXT REQUIRED"), words that tell
/// a user nothing the usage line does not. An option keeps them: its type, range and default.
class HelpFormatter : public CLI::Formatter {
  public:
    std::string make_option_opts(const CLI::Option* option) const override {
        if (option->get_positional())
            return option->get_items_expected_max() > 1 ? "..." : "";
        return CLI::Formatter::make_option_opts(option);
    }
};

void addRun(CLI::App& app, Options& o) {
    CLI::App* run = app.add_subcommand("run", "Run a sculpture script (sandboxed unless --unsafe)");
    run->add_option("SCRIPT", o.run.script, "The Lua script")->required();
    run->add_option(
        "ARGS", o.run.args,
        "Arguments for the script (its global `arg`); put -- before ones starting with -");
    run->add_option("--out,-o", o.run.out,
                    "Output folder: where doc:save/doc:export write and the journal goes "
                    "(default: out/<script name>)");
    run->add_flag("--unsafe", o.run.unsafe, "Lift the sandbox (file, process and C module access)");
    run->add_option("--lib", o.run.libraries,
                    "A folder of shared Lua modules the script may require and read (repeatable)")
        ->check(CLI::ExistingDirectory);
    run->add_option("--max-seconds", o.run.maxSeconds,
                    "Wall-clock limit of the run, s (0 = none): the script is stopped when it "
                    "is up, whatever it is doing")
        ->capture_default_str()
        ->check(numberAbove(true));
    run->add_option("--max-memory", o.run.maxMemoryMiB,
                    "Memory limit of the script's Lua state, MiB (0 = none)")
        ->capture_default_str()
        ->check(numberAbove(true));
    run->add_option("--max-instructions", o.run.maxInstructions,
                    "Lua instruction budget (0 = none)")
        ->capture_default_str()
        ->check(wholeNumberFrom(0));
    run->add_option("--backend", o.run.backend,
                    "Relax every doc:relax with this backend (overrides the script)")
        ->check(CLI::IsMember(relaxerNames()));
    run->add_flag("!--no-journal", o.run.journal,
                  "Do not journal the session to OUT/<script name>.netj");
}

void addJournalCommands(CLI::App& app, Options& o) {
    CLI::App* replay =
        app.add_subcommand("replay", "Replay a journal, check it and print the sculpture's hash");
    replay->add_option("JOURNAL", o.journal, "The journal (.netj)")->required();
    replay->add_option("--out,-o", o.replayOut, "Write the replayed journal to OUT/<name>.netj");
    CLI::App* toLua =
        app.add_subcommand("to-lua", "Print a journal (or snapshot) as an equivalent Lua script");
    toLua->add_option("JOURNAL", o.journal, "The journal (.netj) or snapshot (.nets)")->required();
}

void addRelax(CLI::App& app, Options& o) {
    CLI::App* relax =
        app.add_subcommand("relax", "Relax a sculpture and save the shape as OUT/<name>.nets");
    relax->add_option("DOC", o.relax.document, "A journal (.netj) or snapshot (.nets)")->required();
    relax->add_option("--backend", o.relax.backend, "Relaxation backend")
        ->capture_default_str()
        ->check(CLI::IsMember(relaxerNames()));
    relax->add_option("--tolerance", o.relax.tolerance, "Converged when max |F|/(m|g|) is below it")
        ->capture_default_str()
        ->check(toleranceRange());
    relax->add_option("--max-seconds", o.relax.maxSeconds, "Wall-time limit, s")
        ->capture_default_str()
        ->check(numberAbove(false));
    relax->add_option("--max-steps", o.relax.maxSteps, "Step limit (-1 = none)")
        ->capture_default_str()
        ->check(wholeNumberFrom(-1));
    relax->add_option("--out,-o", o.relax.out, "Output folder")->capture_default_str();
}

void addExport(CLI::App& app, Options& o) {
    CLI::App* exporting =
        app.add_subcommand("export", "Export a sculpture's shape (format by extension)");
    exporting->add_option("DOC", o.exporting.document, "A journal (.netj) or snapshot (.nets)")
        ->required();
    CLI::Option* noRelax =
        exporting->add_flag("!--no-relax", o.exporting.relaxFirst,
                            "Export the shape as it is; without it a shape that is not relaxed (a "
                            "journal's) is relaxed first");
    exporting
        ->add_option("FILE", o.exporting.files,
                     "The files to write, by extension: .csv .obj .ply .glb .json .svg .png .dxf "
                     "(with --rails: .csv .obj .dxf)")
        ->required();
    std::vector<CLI::Option*> shapeOptions{noRelax};
    shapeOptions.push_back(
        exporting->add_option("--colour-by", o.exporting.colourBy, "Colour bars by")
            ->capture_default_str()
            ->check(CLI::IsMember({"piece", "tension"})));
    shapeOptions.push_back(exporting
                               ->add_option("--tube-radius", o.exporting.tubeRadius,
                                            "obj/ply: bars as tubes of this radius, m")
                               ->capture_default_str()
                               ->check(numberAbove(true)));
    shapeOptions.push_back(exporting->add_option("--width", o.exporting.width, "png width, pixels")
                               ->capture_default_str()
                               ->check(CLI::Range(16, 16384)));
    shapeOptions.push_back(
        exporting->add_option("--height", o.exporting.height, "png height, pixels")
            ->capture_default_str()
            ->check(CLI::Range(16, 16384)));
    shapeOptions.push_back(
        exporting->add_option("--view", o.exporting.view, "svg/png view")
            ->capture_default_str()
            ->check(CLI::IsMember({"top", "side", "front", "perspective", "all"})));
    CLI::Option* rails = exporting->add_flag(
        "--rails", o.exporting.rails,
        "Write the rails alone (.csv, .obj or .dxf; import_rails reads them back); no relaxation");
    for (CLI::Option* option : shapeOptions)
        rails->excludes(option);
}

void addReport(CLI::App& app, Options& o) {
    CLI::App* report =
        app.add_subcommand("report", "Print the fabrication and load report (Markdown by default)");
    report->add_option("DOC", o.report.document, "A journal (.netj) or snapshot (.nets)")
        ->required();
    report->add_flag("!--no-relax", o.report.relaxFirst,
                     "Report the shape as it is; without it a shape that is not relaxed (a "
                     "journal's) is relaxed first");
    auto* json = report->add_flag("--json", o.reportJson, "Print the report as JSON");
    report->add_option("--csv", o.reportCsv, "Print a table as CSV: pieces or attachments")
        ->expected(0, 1)
        ->default_str("pieces")
        ->check(CLI::IsMember({"pieces", "attachments"}))
        ->excludes(json);
}

int dispatch(const CLI::App& app, const Options& o) {
    const Verbosity verbosity = o.quiet     ? Verbosity::Quiet
                                : o.verbose ? Verbosity::Verbose
                                            : Verbosity::Normal;
    if (app.got_subcommand("run"))
        return runScript(o.run, verbosity);
    if (app.got_subcommand("replay"))
        return replayJournal(o.journal, o.replayOut, verbosity);
    if (app.got_subcommand("to-lua"))
        return journalToLua(o.journal);
    if (app.got_subcommand("relax"))
        return relaxDocument(o.relax, verbosity);
    if (app.got_subcommand("export"))
        return exportDocument(o.exporting, verbosity);
    const CLI::App* report = app.get_subcommand("report");
    ReportArgs args = o.report;
    if (o.reportJson)
        args.format = ReportFormat::Json;
    else if (report->count("--csv") > 0)
        args.format =
            o.reportCsv == "attachments" ? ReportFormat::AttachmentsCsv : ReportFormat::PiecesCsv;
    return reportDocument(args, verbosity);
}

/// Whether argv[i], an option of `command` (or a global one), takes the next token as its value.
bool takesValue(const CLI::App& command, const std::string& token) {
    if (token.find('=') != std::string::npos)
        return false; // --out=DIR
    const CLI::Option* option = command.get_option_no_throw(token);
    if (option == nullptr && command.get_parent() != nullptr)
        option = command.get_parent()->get_option_no_throw(token);
    return option != nullptr && option->get_type_size() > 0;
}

/// Where `run`'s script arguments after `--` start in argv (argc when there are none). CLI11
/// drops them once the script's list has a value before the `--` (`run s.lua a -- --quick`), so
/// main parses the rest and appends these. Only when the command is `run` and its script comes
/// before the `--` (`run --out o -- s.lua x` is CLI11's to read).
int scriptArgumentsAfterDashes(const CLI::App& app, int argc, char** argv) {
    const CLI::App* run = app.get_subcommand("run");
    int i = 1;
    while (i < argc && std::string_view(argv[i]).starts_with("-") && argv[i] != std::string("--"))
        ++i; // the global flags (-q, -v) take no value
    if (i == argc || argv[i] != std::string("run"))
        return argc;
    bool script = false;
    for (++i; i < argc; ++i) {
        const std::string token = argv[i];
        if (token == "--")
            return script ? i : argc;
        if (!token.starts_with("-"))
            script = true;
        else if (takesValue(*run, token))
            ++i;
    }
    return argc;
}

} // namespace

int main(int argc, char** argv) {
    netsculpt::keepFreedMemoryForReuse();
    CLI::App app{"netsculpt: design knotted-rope net sculptures hung from rails", "netsculpt"};
    app.formatter(std::make_shared<HelpFormatter>()); // before the commands, which copy it
    Options o;
    app.set_version_flag("--version", "netsculpt " NETSCULPT_VERSION);
    app.add_flag("--quiet,-q", o.quiet,
                 "No progress line or notes, only errors and warnings (a command's result on "
                 "stdout, such as relax's result line, still prints)");
    app.add_flag("--verbose,-v", o.verbose, "More messages (relaxation summaries, Lua tracebacks)");
    app.require_subcommand(1);
    app.fallthrough();
    addRun(app, o);
    addJournalCommands(app, o);
    addRelax(app, o);
    addExport(app, o);
    addReport(app, o);
    const int dashes = scriptArgumentsAfterDashes(app, argc, argv);
    try {
        app.parse(dashes, argv);
        for (int i = dashes + 1; i < argc; ++i)
            o.run.args.emplace_back(argv[i]);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "netsculpt: error: " << netsculpt::cli::describeParseError(app, e)
                  << "\nRun with --help for more information.\n";
        return 2;
    }
    try {
        return dispatch(app, o);
    } catch (const netsculpt::cli::Interrupted& e) {
        std::cerr << "netsculpt: interrupted: " << e.what() << "\n";
        return netsculpt::cli::kExitInterrupted;
    } catch (const UserError& e) {
        std::cerr << "netsculpt: error: " << e.what() << "\n";
    } catch (const std::bad_alloc&) {
        std::cerr << "netsculpt: error: out of memory: the sculpture (or a file's numbers) needs "
                     "more memory than this machine gives it; nothing was written\n";
    } catch (const std::exception& e) {
        std::cerr << "netsculpt: error: " << e.what() << "\n";
    }
    return 1;
}
