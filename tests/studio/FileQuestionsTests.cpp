// The questions before a file action: unsaved changes are saved, discarded or kept, and the
// action asked for goes on once they are saved, under a path asked for when the design has none.

#include "FileQuestions.h"

#include <catch2/catch.hpp>

#include <vector>

using namespace netsculpt::studio;

namespace {

/// Records what the questions did.
struct FakeFiles : FileActions {
    bool clean = false;
    std::optional<std::filesystem::path> path;
    bool saveWorks = true;
    std::vector<std::string> done;

    bool isClean() const override { return clean; }
    std::optional<std::filesystem::path> currentPath() const override { return path; }
    bool save(const std::filesystem::path& to) override {
        done.push_back("save " + to.string());
        if (!saveWorks)
            return false;
        path = to;
        clean = true;
        return true;
    }
    void act(FileAction action) override {
        done.push_back(action == FileAction::Quit ? "quit" : "new");
    }
    void act(FileAction action, const std::string& to) override {
        done.push_back((action == FileAction::Open ? "open " : "other ") + to);
    }
};

using Done = std::vector<std::string>;

} // namespace

TEST_CASE("file questions: Save before Quit of an untitled design asks for a path, saves, then "
          "quits",
          "[studio]") {
    FakeFiles files;
    FileQuestions questions;
    questions.request(FileAction::Quit, files);
    CHECK(questions.askingUnsaved() == FileAction::Quit);
    CHECK(files.done.empty());
    questions.answerUnsaved(UnsavedAnswer::Save, files);
    CHECK(questions.askingPath() == FileAction::SaveAs);
    CHECK(files.done.empty());
    questions.answerPath("design.netj", files);
    CHECK(files.done == Done{"save design.netj", "quit"});
    CHECK_FALSE(questions.askingPath());
}

TEST_CASE("file questions: Save before Open of an untitled design saves, then asks which file to "
          "open",
          "[studio]") {
    FakeFiles files;
    FileQuestions questions;
    questions.request(FileAction::Open, files);
    questions.answerUnsaved(UnsavedAnswer::Save, files);
    questions.answerPath("mine.netj", files);
    CHECK(files.done == Done{"save mine.netj"});
    CHECK(questions.askingPath() == FileAction::Open);
    CHECK(questions.path() == "mine.netj"); // suggested: the design's own file
    questions.answerPath("other.netj", files);
    CHECK(files.done == Done{"save mine.netj", "open other.netj"});
}

TEST_CASE("file questions: a save that fails or a path question cancelled does not go on",
          "[studio]") {
    FakeFiles files;
    FileQuestions questions;
    questions.request(FileAction::New, files);
    questions.answerUnsaved(UnsavedAnswer::Save, files);
    questions.cancelPath();
    CHECK(files.done.empty());
    CHECK_FALSE(questions.askingPath());

    files.saveWorks = false;
    questions.request(FileAction::New, files);
    questions.answerUnsaved(UnsavedAnswer::Save, files);
    questions.answerPath("/nowhere/x.netj", files);
    CHECK(files.done == Done{"save /nowhere/x.netj"}); // no "new": the work is not saved
}

TEST_CASE("file questions: a titled design is saved in place, Discard and Cancel, a clean design "
          "is not asked about",
          "[studio]") {
    FakeFiles files;
    files.path = "a.netj";
    FileQuestions questions;
    questions.request(FileAction::Quit, files);
    questions.answerUnsaved(UnsavedAnswer::Save, files);
    CHECK(files.done == Done{"save a.netj", "quit"});

    files.done.clear();
    files.clean = false;
    questions.request(FileAction::New, files);
    questions.answerUnsaved(UnsavedAnswer::Cancel, files);
    CHECK(files.done.empty());
    questions.request(FileAction::New, files);
    questions.answerUnsaved(UnsavedAnswer::Discard, files);
    CHECK(files.done == Done{"new"});

    files.done.clear();
    files.clean = true;
    questions.request(FileAction::Quit, files);
    CHECK_FALSE(questions.askingUnsaved());
    CHECK(files.done == Done{"quit"});
}
