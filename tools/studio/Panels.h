#pragma once
// The studio's Dear ImGui panels: menu, mode toolbar, the piece under the mouse or selected (every
// field editable by typing, through commands), rails, the report summary, the solver's status,
// the status line, and the modal questions (file paths, unsaved changes, restoring a session).

#include "FileQuestions.h"

#include "model/Ids.h"

#include <optional>
#include <string>

namespace netsculpt::studio {

class App;

class Panels {
  public:
    /// Builds this frame's panels (between ImGui::NewFrame and ImGui::Render).
    void draw(App& app);
    /// Starts a file action (from the menu or a shortcut): asks about unsaved changes first where
    /// the action would drop them, then for a path where it needs one.
    void request(FileAction action, App& app);

    static constexpr float kLeftWidth = 300;  ///< px, the inspector on the left
    static constexpr float kRightWidth = 270; ///< px, the solver panel on the right
    /// px that framing the sculpture keeps clear at each side of the window (Camera::frameInset)
    static constexpr int kFrameInset =
        int(kLeftWidth > kRightWidth ? kLeftWidth : kRightWidth) + 16;

  private:
    void drawMenu(App& app);
    void drawToolbar(App& app);
    void drawInspector(App& app);
    void drawPiece(App& app, PieceId id);
    void drawRails(App& app);
    void drawReport(App& app);
    void drawSolver(App& app);
    void drawStatus(App& app);
    void drawTensionScale(double maxTension);
    void drawDialogs(App& app);
    void drawUnsaved(App& app);
    void drawPath(App& app);

    FileQuestions questions_;
    PieceId colourPiece_;
    float colour_[3] = {0, 0, 0};
    bool colourPending_ = false;
    float menuHeight_ = 0;
    /// px, the toolbar's right and bottom edges in the last frame: in a narrow window the solver
    /// panel goes below the toolbar instead of over its last buttons.
    float toolbarRight_ = 0, toolbarBottom_ = 0;
};

} // namespace netsculpt::studio
