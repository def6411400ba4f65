#include "Commands.h"
#include "FolderFiles.h"
#include "Interrupt.h"
#include "OutputLock.h"
#include "Watchdog.h"

#include "io/Export.h"
#include "io/Report.h"
#include "model/Error.h"
#include "physics/Backends.h"
#include "scripting/DocumentFiles.h"
#include "scripting/ScriptHost.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace netsculpt::cli {

namespace fs = std::filesystem;

namespace {

void createFolder(const fs::path& folder) {
    std::error_code error;
    fs::create_directories(folder, error);
    if (error || !fs::is_directory(folder))
        throw UserError("cannot create the output folder " + folder.string() +
                        (error ? ": " + error.message() : std::string()));
}

/// Refuses, before a relaxation that may take a while, a folder that createFolder could not
/// make because a part of its path is a file. Nothing is created here.
void checkFolderPath(const fs::path& folder) {
    std::error_code error;
    for (fs::path part = folder; !part.empty(); part = part.parent_path()) {
        if (fs::exists(part, error)) {
            if (!fs::is_directory(part, error))
                throw UserError("cannot create the output folder " + folder.string() + ": " +
                                part.string() + " is a file, not a folder");
            return;
        }
        if (part == part.parent_path())
            return;
    }
}

/// Opens a design, saying what it dropped (a torn last entry) even with --quiet, which keeps
/// errors and warnings: that entry is gone from every output of this command.
Document openDocument(const fs::path& path) {
    std::vector<std::string> warnings;
    Document doc = lua::openReadOnly(path, &warnings);
    for (const std::string& w : warnings)
        std::cerr << "netsculpt: warning: " << w << "\n";
    return doc;
}

std::uint64_t wholeCount(double value, const char* option) {
    if (!(value >= 0) || value != std::floor(value) || value > 1.8e19)
        throw UserError(std::string(option) + " must be a whole number >= 0, got " +
                        formatNumber(value));
    return std::uint64_t(value);
}

/// " (its wind, 0.05 N/m towards (0, 1, 0))" for a document whose shape was relaxed under wind,
/// "" for gravity alone: a document is relaxed again under the load its shape was relaxed under.
std::string windClause(const std::optional<Wind>& wind) {
    if (!wind)
        return "";
    const Vec3& d = wind->direction;
    return " (its wind, " + formatNumber(wind->pressure) + " N/m towards (" + formatNumber(d.x) +
           ", " + formatNumber(d.y) + ", " + formatNumber(d.z) + "))";
}

std::string hashText(std::uint64_t hash) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
    return text;
}

/// "1 rail", "3 rails".
std::string counted(std::size_t count, const std::string& noun) {
    return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

/// "3 rails, 5 pieces, 12000 knots, 23000 bars".
std::string summary(const Document& doc) {
    const auto& s = doc.sculpture();
    const auto& system = doc.compiled().system;
    return counted(s.rails.size(), "rail") + ", " + counted(s.pieces.size(), "piece") + ", " +
           counted(system.knotCount(), "knot") + ", " + counted(system.barCount(), "bar");
}

lua::ScriptOptions scriptOptions(const RunArgs& a, const fs::path& out, ProgressLine& progress) {
    lua::ScriptOptions o;
    o.outputDir = out;
    o.unsafe = a.unsafe;
    o.libraryDirs = a.libraries;
    if (!(a.maxMemoryMiB >= 0) || !std::isfinite(a.maxMemoryMiB))
        throw UserError("--max-memory must be a number of MiB >= 0, got " +
                        formatNumber(a.maxMemoryMiB));
    o.maxMemory = std::size_t(std::llround(a.maxMemoryMiB * double(1 << 20)));
    o.maxInstructions = wholeCount(a.maxInstructions, "--max-instructions");
    o.backend = a.backend;
    o.journal = a.journal;
    o.args = a.args;
    if (progress.enabled())
        o.relaxProgress = [&progress](const RelaxProgress& p) { progress.update(p); };
    // A script's relaxed shape gets the warning `relax` gives.
    o.relaxFinished = [&progress](const Document& doc, const RelaxResult& r) {
        progress.finish(r);
        if (r.converged || r.residual <= kSettledResidual)
            if (const std::size_t overstretched = countOverstretchedBars(doc.compiled().system))
                std::cerr << "netsculpt: warning: after doc:relax, "
                          << overstretchWarning(overstretched) << "\n";
    };
    return o;
}

} // namespace

namespace {

/// "about 12000 Lua instructions"; they are counted a thousand at a time.
std::string instructionsText(std::uint64_t instructions) {
    if (instructions == 0)
        return "fewer than 1000 Lua instructions";
    return "about " + std::to_string(instructions) + " Lua instructions";
}

/// "340 KiB", "12.5 MiB".
std::string memoryText(std::size_t bytes) {
    char text[32];
    if (bytes < (1 << 20))
        std::snprintf(text, sizeof text, "%zu KiB", (bytes + 1023) / 1024);
    else
        std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / (1 << 20));
    return text;
}

} // namespace

int runScript(const RunArgs& a, Verbosity verbosity) {
    std::error_code error;
    if (fs::is_directory(a.script, error))
        throw UserError(a.script.string() + " is a folder; expected a Lua script file");
    if (!fs::is_regular_file(a.script, error))
        throw UserError("there is no script at " + a.script.string());
    // A folder of the run's own by default: a shared script reads and writes in its output
    // folder, which must not be wherever the artist happens to stand (their home, say).
    const fs::path out = a.out.empty() ? fs::path("out") / a.script.stem() : a.out;
    createFolder(out);
    const OutputLock lock(out);
    const FolderFiles before(out);
    if (a.unsafe)
        std::fprintf(
            stderr,
            "netsculpt: --unsafe: the sandbox is off: %s may run programs, load C modules and "
            "read and write any file\n",
            a.script.string().c_str());
    ProgressLine progress(verbosity);
    lua::ScriptOptions options = scriptOptions(a, out, progress);
    const InterruptRequest interrupt(verbosity == Verbosity::Quiet);
    options.interrupt = interrupt.flag();
    const auto start = std::chrono::steady_clock::now();
    const Watchdog watchdog(a.maxSeconds, a.script.string() + " ran past its time limit of " +
                                              formatNumber(a.maxSeconds) + " s (--max-seconds)");
    const lua::ScriptResult result = lua::runScriptFile(a.script, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string leftovers = leftoverNote(out, before.unchanged());
    if (!result.ok) {
        std::cerr << "netsculpt: error: " << result.error << "\n";
        if (verbosity == Verbosity::Verbose && !result.traceback.empty())
            std::cerr << result.traceback << "\n";
        if (result.stop == lua::Stop::Interrupted)
            for (const fs::path& journal : result.journals)
                std::cerr << "netsculpt: journal " << journal.string()
                          << " (the commands run before Ctrl-C)\n";
        if (verbosity != Verbosity::Quiet && !leftovers.empty())
            std::cerr << "netsculpt: note: " << leftovers << "\n";
        return result.stop == lua::Stop::Interrupted ? kExitInterrupted : 1;
    }
    if (verbosity != Verbosity::Quiet && !leftovers.empty())
        std::cerr << "netsculpt: note: " << leftovers << "\n";
    if (verbosity != Verbosity::Quiet) {
        std::fprintf(stderr, "netsculpt: ran %s in %.1f s; outputs in %s\n",
                     a.script.string().c_str(), seconds, out.string().c_str());
        for (const fs::path& journal : result.journals)
            std::fprintf(stderr, "netsculpt: journal %s\n", journal.string().c_str());
    }
    if (verbosity == Verbosity::Verbose)
        std::fprintf(stderr, "netsculpt: %s, peak Lua memory %s\n",
                     instructionsText(result.instructions).c_str(),
                     memoryText(result.peakMemory).c_str());
    return 0;
}

/// Refuses an output that is the input itself: DOC is only read, never written.
void checkNotInput(const fs::path& output, const fs::path& input, const char* command) {
    std::error_code error;
    if (fs::equivalent(output, input, error))
        throw UserError(std::string(command) + " would write " + output.string() +
                        " over its input " + input.string() +
                        ", which is only read; give --out another folder");
}

int replayJournal(const fs::path& journal, const fs::path& out, Verbosity verbosity) {
    if (!out.empty())
        checkNotInput(out / (journal.stem().string() + ".netj"), journal, "replay");
    Document doc = openDocument(journal);
    std::cout << journal.string() << ": " << summary(doc) << "; hash " << hashText(doc.hash())
              << "\n";
    if (!out.empty()) {
        createFolder(out);
        const fs::path copy = out / (journal.stem().string() + ".netj");
        doc.attachJournal(copy);
        if (verbosity != Verbosity::Quiet)
            std::cerr << "netsculpt: wrote " << copy.string() << "\n";
    }
    return 0;
}

int journalToLua(const fs::path& journal) {
    const Document doc = openDocument(journal);
    std::cout << doc.toLua();
    return 0;
}

int relaxDocument(const RelaxArgs& a, Verbosity verbosity) {
    const fs::path snapshot = a.out / (a.document.stem().string() + ".nets");
    checkNotInput(snapshot, a.document, "relax");
    Document doc = openDocument(a.document);
    createFolder(a.out);
    DocumentRelaxOptions options;
    options.backend = a.backend;
    options.solver.tolerance = a.tolerance;
    options.solver.maxSeconds = a.maxSeconds;
    options.solver.maxSteps = a.maxSteps;
    options.solver.wind = doc.shapeWind();
    ProgressLine progress(verbosity);
    if (progress.enabled())
        options.solver.progress = [&progress](const RelaxProgress& p) { progress.update(p); };
    // Ctrl-C stops the relaxation; its shape is saved.
    const InterruptRequest interrupt(verbosity == Verbosity::Quiet);
    options.solver.cancel = interrupt.flag();
    const RelaxResult result = doc.relax(options);
    progress.clear(); // the result is this command's output, below: not also a message
    doc.saveSnapshot(snapshot);
    std::cout << a.document.string() << windClause(options.solver.wind) << ": "
              << describeRelaxResult(result) << "\n";
    if (verbosity != Verbosity::Quiet)
        std::cerr << "netsculpt: wrote " << snapshot.string() << "\n";
    if (interrupt.requested())
        return kExitInterrupted;
    if (!result.converged)
        return kExitNotConverged;
    if (const std::size_t overstretched = countOverstretchedBars(doc.compiled().system))
        std::cerr << "netsculpt: warning: " << overstretchWarning(overstretched) << "\n";
    return 0;
}

namespace {

/// Relaxes `doc` for `purpose` ("the report", "export") when its shape is not an equilibrium
/// (a journal holds no shape), or warns when asked not to: kExitNotConverged when that
/// relaxation stopped short, else 0.
int relaxUnlessRelaxed(Document& doc, const fs::path& document, bool relaxFirst,
                       const std::string& purpose, Verbosity verbosity) {
    if (doc.isRelaxed() || doc.compiled().system.knotCount() == 0)
        return 0;
    if (!relaxFirst) {
        std::cerr << "netsculpt: warning: the shape is not relaxed: it is not the hanging net's "
                     "(without --no-relax it is relaxed first)\n";
        return 0;
    }
    DocumentRelaxOptions options;
    options.solver.wind = doc.shapeWind(); // a wind load case stays one
    ProgressLine progress(verbosity);
    if (progress.enabled())
        options.solver.progress = [&progress](const RelaxProgress& p) { progress.update(p); };
    const InterruptRequest interrupt(verbosity == Verbosity::Quiet);
    options.solver.cancel = interrupt.flag();
    const RelaxResult result = doc.relax(options);
    progress.clear(); // said once, below
    if (interrupt.requested())
        throw Interrupted("the relaxation for " + purpose + " stopped after " +
                          std::to_string(result.steps) + " steps; nothing was written");
    if (verbosity != Verbosity::Quiet || !result.converged)
        std::cerr << "netsculpt: " << document.string()
                  << " holds no relaxed shape; relaxed it for " << purpose
                  << windClause(options.solver.wind) << ": " << describeRelaxResult(result) << "\n";
    return result.converged ? 0 : kExitNotConverged;
}

} // namespace

namespace {

/// `netsculpt export DOC FILE... --rails`: the rails need no relaxation.
int exportRails(const ExportArgs& a, Verbosity verbosity) {
    for (const fs::path& file : a.files)
        checkRailsExport(file);
    const Document doc = openDocument(a.document);
    for (const fs::path& file : a.files) {
        if (file.has_parent_path())
            createFolder(file.parent_path());
        exportRailsFile(doc.sculpture(), file);
        if (verbosity != Verbosity::Quiet)
            std::cerr << "netsculpt: wrote " << file.string() << "\n";
    }
    return 0;
}

} // namespace

int exportDocument(const ExportArgs& a, Verbosity verbosity) {
    if (a.rails)
        return exportRails(a, verbosity);
    ExportOptions options;
    options.colourBy = a.colourBy;
    options.tubeRadius = a.tubeRadius;
    options.width = a.width;
    options.height = a.height;
    options.view = a.view;
    for (const fs::path& file : a.files) { // before a relaxation that may take a while
        checkExport(file, options);
        checkFolderPath(file.parent_path());
    }
    Document doc = openDocument(a.document);
    const int exitCode = relaxUnlessRelaxed(doc, a.document, a.relaxFirst, "export", verbosity);
    for (const fs::path& file : a.files) {
        if (file.has_parent_path())
            createFolder(file.parent_path());
        exportFile(doc, file, options);
        if (verbosity != Verbosity::Quiet)
            std::cerr << "netsculpt: wrote " << file.string() << "\n";
    }
    return exitCode;
}

int reportDocument(const ReportArgs& a, Verbosity verbosity) {
    Document doc = openDocument(a.document);
    const int exitCode =
        relaxUnlessRelaxed(doc, a.document, a.relaxFirst, "the report", verbosity);
    const nlohmann::json report = buildReport(doc);
    switch (a.format) {
    case ReportFormat::Markdown:
        std::cout << reportMarkdown(report);
        break;
    case ReportFormat::Json:
        std::cout << report.dump(2) << "\n";
        break;
    case ReportFormat::PiecesCsv:
        std::cout << reportPiecesCsv(report);
        break;
    case ReportFormat::AttachmentsCsv:
        std::cout << reportAttachmentsCsv(report);
        break;
    }
    return exitCode;
}

} // namespace netsculpt::cli
