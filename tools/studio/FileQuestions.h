#pragma once
// The questions the studio asks before a file action, without a window: whether to save
// unsaved changes first (before New, Open and Quit), and for a path. The panels draw them and
// pass the answers on; tests answer them directly.

#include <filesystem>
#include <optional>
#include <string>
#include <utility>

namespace netsculpt::studio {

enum class FileAction { New, Open, Save, SaveAs, ImportRails, Export, RunScript, Screenshot, Quit };
enum class UnsavedAnswer { Save, Discard, Cancel };

/// What the questions act on (the App in the studio).
class FileActions {
  public:
    virtual ~FileActions() = default;
    virtual bool isClean() const = 0;
    /// The journal the design was opened from or saved to, if any.
    virtual std::optional<std::filesystem::path> currentPath() const = 0;
    /// Saves the journal to `path`; false (and a notice) when it failed.
    virtual bool save(const std::filesystem::path& path) = 0;
    /// New or Quit.
    virtual void act(FileAction action) = 0;
    /// Open, ImportRails, Export, RunScript or Screenshot with the path given.
    virtual void act(FileAction action, const std::string& path) = 0;
};

class FileQuestions {
  public:
    /// Starts `action`: asks about unsaved changes first where the action would drop them, then
    /// for a path where it needs one.
    void request(FileAction action, FileActions& files);
    /// The answer to "unsaved changes": Save saves (asking for a path when the design has none)
    /// and then goes on with the action asked for; Discard goes on; Cancel drops it.
    void answerUnsaved(UnsavedAnswer answer, FileActions& files);
    /// OK in the path question, with the path typed (ignored when empty).
    void answerPath(const std::string& path, FileActions& files);
    void cancelPath();

    /// The action the unsaved-changes question is open for.
    const std::optional<FileAction>& askingUnsaved() const { return askUnsaved_; }
    /// The action the path question is open for (Save asks as SaveAs).
    const std::optional<FileAction>& askingPath() const { return askPath_; }
    /// The path field's text: a suggestion when the question opens.
    std::string& path() { return path_; }
    /// True once after a question was opened (ImGui::OpenPopup is due).
    bool takeOpenedUnsaved() { return std::exchange(openedUnsaved_, false); }
    bool takeOpenedPath() { return std::exchange(openedPath_, false); }

  private:
    void perform(FileAction action, FileActions& files);

    std::optional<FileAction> askPath_, askUnsaved_;
    /// An action that waits for the design to be saved under a new path (Save in the
    /// unsaved-changes question of an untitled design).
    std::optional<FileAction> afterSave_;
    bool openedPath_ = false, openedUnsaved_ = false;
    std::string path_;
};

} // namespace netsculpt::studio
