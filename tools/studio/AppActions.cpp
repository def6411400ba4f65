// The studio's document-level actions: the starting document, the session journal, files,
// scripts, the report, and the live relaxation switches.

#include "App.h"

#include "Notices.h"
#include "Screenshot.h"

#include "commands/Journal.h"
#include "commands/Snapshot.h"
#include "interaction/DemoScenes.h"
#include "io/Export.h"
#include "io/Import.h"
#include "io/Report.h"
#include "model/Error.h"

#include <cstdio>
#include <fstream>

namespace netsculpt::studio {

namespace {

/// Runs `action`; a UserError or any other failure becomes a notice. Returns whether it worked.
template <typename F> bool attempt(App& app, const std::string& what, F&& action) {
    try {
        action();
        return true;
    } catch (const std::exception& e) {
        app.notify(what + ": " + e.what(), true);
        return false;
    }
}

/// Whether `file` is a snapshot (a relaxed shape saved by `netsculpt relax` or saveSnapshot)
/// rather than a journal: its first bytes say so.
bool isSnapshot(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::string start(kSnapshotMagic.size(), '\0');
    in.read(start.data(), std::streamsize(start.size()));
    return in && isSnapshotText(start);
}

bool hasEntries(const std::filesystem::path& journal) {
    try {
        return std::filesystem::exists(journal) && !readJournal(journal).entries.empty();
    } catch (const std::exception&) {
        return std::filesystem::exists(journal); // unreadable: still worth offering (open will say why)
    }
}

} // namespace

void App::notify(const std::string& message, bool error) {
    notice_ = message;
    noticeIsError_ = error;
    std::fprintf(error ? stderr : stdout, "netsculpt-studio: %s\n", message.c_str());
}

void App::buildInitialDocument() {
    sessionPath_ = options_.journal.value_or(defaultSessionJournal());
    if (options_.open) {
        std::vector<std::string> warnings;
        *doc_ = Document::load(*options_.open, &warnings);
        if (!warnings.empty()) {
            const Notice notice = openNotice("opened " + options_.open->string(), warnings);
            notify(notice.text, notice.error);
        }
        if (!isSnapshot(*options_.open)) // a snapshot is not overwritten by a journal on save
            currentPath_ = *options_.open;
    } else if (options_.demoKnots > 0) {
        buildLargeDemoSculpture(*doc_, options_.demoKnots);
        doc_->markClean();
    } else if (options_.demo) {
        buildDemoSculpture(*doc_);
        doc_->markClean();
    } else if (options_.script) {
        if (!scriptRunner_)
            throw UserError("--script: this studio was built without the Lua binding; use --demo or --open");
        scriptRunner_->run(*doc_, *options_.script);
        doc_->markClean();
    }
    const bool startsEmpty = !options_.open && !options_.demo && options_.demoKnots == 0 && !options_.script;
    if (startsEmpty && hasEntries(sessionPath_)) restorePending_ = true;
    else attachSession();
    interaction_->setDocument(*doc_);
}

void App::attachSession() {
    keepSessionWork();
    doc_->attachJournal(sessionPath_);
}

void App::keepSessionWork() {
    std::filesystem::create_directories(sessionPath_.parent_path().empty() ? "." : sessionPath_.parent_path());
    if (hasEntries(sessionPath_)) {
        // Work in the session journal (the default one or --journal's) is kept once more before
        // the journal starts afresh: in case the restore question was answered wrongly, or
        // --journal named a design's own journal.
        std::filesystem::path previous = sessionPath_;
        previous.replace_extension(".previous.netj");
        std::error_code failed;
        std::filesystem::copy_file(sessionPath_, previous,
                                   std::filesystem::copy_options::overwrite_existing, failed);
        if (failed)
            throw UserError("cannot keep " + sessionPath_.string() + " as " + previous.string() +
                            " (" + failed.message() + "), so it is not journaled over; give " +
                            "--journal a path of its own");
        if (options_.journal)
            notify(sessionPath_.string() + " held work: it is kept as " + previous.string() +
                       ", and the session is journaled afresh",
                   false);
    }
}

void App::answerRestore(bool restore) {
    restorePending_ = false;
    if (restore && attempt(*this, "restore " + sessionPath_.string(), [&] {
            std::vector<std::string> warnings;
            Document restored = Document::open(sessionPath_, &warnings); // keeps appending to the session
            replaceDocument(std::move(restored));
            const std::string done = "restored the last session (" + sessionPath_.string() + ")";
            const Notice notice = openNotice(done, warnings);
            notify(notice.text, notice.error);
        }))
        return;
    attempt(*this, "session journal", [&] { attachSession(); });
}

void App::replaceDocument(Document next) {
    live_->cancel();
    *doc_ = std::move(next);
    interaction_->setDocument(*doc_);
    interaction_->frameAll();
}

void App::newDocument() {
    attempt(*this, "new", [&] {
        keepSessionWork(); // before the document goes: if the copy fails, nothing changes
        replaceDocument(Document{});
        doc_->attachJournal(sessionPath_);
        currentPath_.reset();
    });
}

bool App::openJournal(const std::filesystem::path& path) {
    return attempt(*this, "open " + path.string(), [&] {
        std::vector<std::string> warnings;
        Document opened = Document::load(path, &warnings);
        keepSessionWork(); // before the document goes: if the copy fails, nothing changes
        replaceDocument(std::move(opened));
        doc_->attachJournal(sessionPath_); // the session goes on; the file changes only on save
        doc_->markClean();
        currentPath_.reset();
        if (!isSnapshot(path)) // a snapshot is not overwritten by a journal on save
            currentPath_ = path;
        const Notice notice = openNotice("opened " + path.string(), warnings);
        notify(notice.text, notice.error);
    });
}

bool App::saveJournal(const std::filesystem::path& path) {
    return attempt(*this, "save " + path.string(), [&] {
        doc_->save(path);
        currentPath_ = path;
        notify("saved " + path.string(), false);
    });
}

bool App::importRails(const std::filesystem::path& path) {
    return attempt(*this, "import " + path.string(), [&] {
        std::vector<NamedCurve> rails = importRailsFile(path);
        const std::size_t count = rails.size();
        if (interaction_->execute(ImportRailsCommand{path.string(), std::move(rails)}))
            notify("imported " + std::to_string(count) + " rail(s) from " + path.string(), false);
    });
}

bool App::exportTo(const std::filesystem::path& path) {
    return attempt(*this, "export " + path.string(), [&] {
        ExportOptions o;
        o.colourBy = colourBy_ == ColourBy::Tension ? "tension" : "piece";
        exportFile(*doc_, path, o);
        const Notice notice = exportNotice(path.string(), doc_->isRelaxed(), previewScaleShown());
        notify(notice.text, notice.error);
    });
}

bool App::runScript(const std::filesystem::path& path) {
    if (!scriptRunner_) {
        notify("run script: this studio was built without the Lua binding", true);
        return false;
    }
    return attempt(*this, "script " + path.string(), [&] {
        scriptRunner_->run(*doc_, path);
        interaction_->setDocument(*doc_);
        interaction_->frameAll();
        notify("ran " + path.string(), false);
    });
}

bool App::takeScreenshot(const std::filesystem::path& path) {
    pendingScreenshot_ = path;
    return true;
}

void App::writePendingScreenshot() {
    const std::filesystem::path path = *pendingScreenshot_;
    pendingScreenshot_.reset();
    attempt(*this, "screenshot", [&] {
        writeFramebufferPng(path, camera_.width(), camera_.height());
        notify("screenshot " + path.string(), false);
    });
}

void App::refine() {
    live_->refine(doc_->compiled().system, shownVersion_);
    residualHistory_.clear();
}

void App::setLiveEnabled(bool on) {
    liveEnabled_ = on;
    if (on) live_->preview(doc_->compiled().system, shownVersion_);
    else live_->cancel();
}

void App::setColourBy(ColourBy c) {
    colourBy_ = c;
    positionsDirty_ = true;
}

double App::previewScaleShown() const {
    const bool shown = liveState_ && liveState_->generation == interaction_->version() &&
                       liveState_->positions.size() == doc_->compiled().system.knotCount();
    return shown ? liveState_->stiffnessScale : 1.0;
}

/// The report of a preview shape with the preview's stiffness: the forces that hold that shape
/// (at the material's stiffness its stretch would read as forces about 1/scale too large).
nlohmann::json App::previewReport() const {
    CompiledSculpture soft = doc_->compiled();
    scaleStiffness(soft.system, previewScaleShown());
    return buildReport(doc_->sculpture(), soft, relaxStatus(*doc_));
}

const nlohmann::json* App::report() {
    const auto now = std::chrono::steady_clock::now();
    const bool current = liveState_ && liveState_->generation == interaction_->version();
    // The run for the shape shown has ended: its last shape's report is due now.
    const bool settled = current && !liveState_->running;
    // An edit's counts and lengths are due at once, unless a drag goes on (then twice a second).
    const bool edited = reportVersion_ != interaction_->version() && !interaction_->gestureActive();
    if ((reportDirty_ || edited) &&
        (settled || edited || now - reportTime_ > std::chrono::milliseconds(500))) {
        reportDirty_ = false;
        reportTime_ = now;
        reportVersion_ = interaction_->version();
        try {
            const double preview = previewScaleShown();
            report_ = preview < 1 ? previewReport() : buildReport(*doc_);
            reportValid_ = true;
            const bool relaxed = doc_->isRelaxed() ||
                                 (current && liveState_->converged && liveState_->stiffnessScale == 1);
            reportBasis_ = relaxed ? ReportBasis::Relaxed : preview < 1 ? ReportBasis::Preview : ReportBasis::NotRelaxed;
            reportPreviewScale_ = preview;
        } catch (const std::exception& e) {
            reportValid_ = false;
            notify(std::string("report: ") + e.what(), true);
        }
    }
    return reportValid_ ? &report_ : nullptr;
}

} // namespace netsculpt::studio
