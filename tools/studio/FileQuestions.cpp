#include "FileQuestions.h"

namespace netsculpt::studio {

namespace {

bool dropsChanges(FileAction a) {
    return a == FileAction::New || a == FileAction::Open || a == FileAction::Quit;
}
bool needsPath(FileAction a) {
    return a != FileAction::New && a != FileAction::Quit;
}

} // namespace

void FileQuestions::request(FileAction action, FileActions& files) {
    afterSave_.reset();
    if (dropsChanges(action) && !files.isClean()) {
        askUnsaved_ = action;
        openedUnsaved_ = true;
        return;
    }
    perform(action, files);
}

void FileQuestions::answerUnsaved(UnsavedAnswer answer, FileActions& files) {
    const std::optional<FileAction> then = std::exchange(askUnsaved_, std::nullopt);
    if (!then || answer == UnsavedAnswer::Cancel)
        return;
    if (answer == UnsavedAnswer::Discard)
        return perform(*then, files);
    const auto path = files.currentPath();
    if (path && files.save(*path))
        return perform(*then, files);
    perform(FileAction::SaveAs, files);
    afterSave_ = then; // once saved under the path asked for
}

void FileQuestions::answerPath(const std::string& path, FileActions& files) {
    if (path.empty() || !askPath_)
        return;
    const FileAction action = *std::exchange(askPath_, std::nullopt);
    const std::optional<FileAction> then = std::exchange(afterSave_, std::nullopt);
    if (action != FileAction::SaveAs)
        return files.act(action, path);
    if (files.save(path) && then)
        perform(*then, files);
}

void FileQuestions::cancelPath() {
    askPath_.reset();
    afterSave_.reset();
}

void FileQuestions::perform(FileAction action, FileActions& files) {
    const auto current = files.currentPath();
    if (action == FileAction::Save && current) {
        files.save(*current);
        return;
    }
    if (!needsPath(action))
        return files.act(action);
    askPath_ = action == FileAction::Save ? FileAction::SaveAs : action;
    if (action == FileAction::Screenshot)
        path_ = "netsculpt-studio.png";
    else if (current && (action == FileAction::SaveAs || action == FileAction::Open))
        path_ = current->string();
    openedPath_ = true;
}

} // namespace netsculpt::studio
