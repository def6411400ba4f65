#include "ScriptRunner.h"

#include "commands/Journal.h"
#include "model/Error.h"
#include "scripting/ScriptHost.h"

#include <chrono>

namespace netsculpt::studio {

namespace {

/// Runs the script in the sandbox with its own journal in a scratch folder, then replays that
/// journal into the studio's document, so the script's commands are the studio's: journaled in
/// the session and undoable step by step. The ids a script's commands name are those of a new
/// sculpture, so the studio's document must be new.
class LuaScriptRunner final : public ScriptRunner {
  public:
    void run(Document& doc, const std::filesystem::path& script) override {
        const Sculpture& s = doc.sculpture();
        if (s.nextRailId != 1 || s.nextPieceId != 1)
            throw UserError("run script: a script builds a new sculpture; start a new one (File > New) first");
        const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
        const auto scratch = std::filesystem::temp_directory_path() / ("netsculpt-studio-" + std::to_string(stamp));
        std::filesystem::create_directories(scratch);
        lua::ScriptOptions options;
        options.outputDir = scratch;
        const lua::ScriptResult result = lua::runScriptFile(script, options);
        std::error_code ignored;
        if (!result.ok) {
            std::filesystem::remove_all(scratch, ignored);
            throw UserError(result.error);
        }
        if (result.journals.empty()) {
            std::filesystem::remove_all(scratch, ignored);
            throw UserError("run script: " + script.string() + " made no sculpture (no ns.new())");
        }
        const JournalContents journal = readJournal(result.journals.front());
        std::filesystem::remove_all(scratch, ignored);
        for (const JournalEntry& entry : journal.entries) {
            if (entry.kind == JournalEntry::Kind::Undo) doc.undo();
            else if (entry.kind == JournalEntry::Kind::Redo) doc.redo();
            else doc.execute(entry.command, entry.merge);
        }
    }
};

} // namespace

std::unique_ptr<ScriptRunner> makeScriptRunner() { return std::make_unique<LuaScriptRunner>(); }

} // namespace netsculpt::studio
