#pragma once
// The studio's interaction layer, without a window (STYLE.md, the Polyscope habit): plain input
// events and a camera in, commands out through the Document. Tests drive it with scripted events
// against a fixed camera; the studio feeds it GLFW's events through the same handle() call.
//
// Gestures: a press on a handle starts a handle gesture (the mode decides what it does); a press
// elsewhere orbits (left) or pans (right, middle, shift+left); the wheel zooms. A drag that
// changes a value executes its command with merge = true on every change and endGesture() on
// release, so the whole drag is one undo step. A click (press and release within a few pixels)
// on a NewNet or Divide handle executes one command. A click on the net selects a piece. A
// release over one of the window's panels (setPointerOverPanel) drops nothing and clicks
// nothing: the panel hides what it would act on.
//
// Keys: ctrl+z undo; ctrl+shift+z or ctrl+y redo; 1..7 or V N D R C B J choose the mode (view,
// new net, divide, rows, columns, bar length, connect); T, F, S, P top/front/side/perspective
// view; Home frames everything; Escape goes back to the view mode.

#include "commands/Document.h"
#include "interaction/Camera.h"
#include "interaction/Handles.h"
#include "interaction/InputEvent.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace netsculpt {

struct InteractionSettings {
    HandleSettings handles;
    double pickRadiusPixels = 12;   ///< a handle within this many pixels of the cursor is under it
    double clickSlopPixels = 6;     ///< a press and release closer than this is a click
    double pixelsPerRow = 8;        ///< Rows: drag distance per row
    double pixelsPerColumn = 4;     ///< Columns on a rail: drag distance per column
    double pixelsPerGear = 24;      ///< Columns below a piece: drag distance per gear step
    double barMetresPerPixel = 0.002; ///< BarLength: m per pixel of drag (rounded to whole mm)
    int newPieceRows = 10;          ///< rows of a piece made by a NewNet click
    double newPieceBar = 0.25;      ///< m, bar length of a piece made by a NewNet click
    double newPieceSpacingRatio = 1.0; ///< knot spacing along a rail = ratio * bar
    int newPieceMaxColumns = 400;
    double orbitRadiansPerPixel = 0.007;
};

/// Columns of a new piece on a rail of `railLength` m: round(length / spacing), + 1 on an open
/// rail, at least 3 (closed) or 2 (open), at most maxColumns.
int defaultColumns(double railLength, bool closedRail, double spacing, int maxColumns = 400);

class Interaction {
  public:
    Interaction(Document& doc, Camera& camera, InteractionSettings settings = {});

    /// Switches to another document (after open / restore); ends any gesture.
    void setDocument(Document& doc);
    Document& document() { return *doc_; }
    const Document& document() const { return *doc_; }
    Camera& camera() { return *camera_; }
    const InteractionSettings& settings() const { return settings_; }
    InteractionSettings& settings() { return settings_; }

    Mode mode() const { return mode_; }
    /// Switches the mode (not during a handle drag); a switch clears the message, which was
    /// about the old mode's work.
    void setMode(Mode mode);

    /// Whether the window's panels cover the view at the cursor (the window says so before each
    /// move and release it feeds): nothing behind a panel is hovered, and a release there acts on
    /// nothing the panel hides: a connect drop or a click on a sphere is cancelled (the message
    /// says so), a click selects no piece. A value drag keeps what its moves have changed.
    void setPointerOverPanel(bool over) { pointerOverPanel_ = over; }

    /// Feeds one event. Never throws for user errors: a refused command leaves the document as it
    /// was and its message in message().
    void handle(const InputEvent& event);

    /// Re-reads handle positions and hover (call when knots moved or the document changed from
    /// outside this class).
    void refresh();
    void frameAll();

    const std::vector<Handle>& handles() const { return handles_; }
    int hovered() const { return hovered_; } ///< index into handles(), -1 = none
    /// The handle being dragged (in Connect, the last row being carried to a rail).
    const std::optional<Handle>& dragged() const { return dragHandle_; }
    double cursorX() const { return cursorX_; }
    double cursorY() const { return cursorY_; }
    bool gestureActive() const { return drag_ != Drag::None; }

    PieceId hoveredPiece() const { return hoveredPiece_; } ///< the piece of the knot under the cursor
    PieceId selectedPiece() const { return selected_; }
    void select(PieceId piece) { selected_ = piece; }

    /// Runs a command (panels use this too). false + message() when it was refused.
    bool execute(const Command& command, bool merge = false);
    /// The ids the last successful execute() created.
    const CommandResult& lastCreated() const { return lastCreated_; }
    bool undo();
    bool redo();

    /// Increases on every change of the document through this class (and on setDocument).
    std::uint64_t version() const { return version_; }
    /// What the status line says for this layer: the last command's name or refusal, a
    /// cancelled drop, or in divide mode why split refuses the piece under the cursor (while it
    /// is there). Empty after a mode switch (the new mode's hint is due).
    const std::string& message() const { return message_; }
    bool messageIsError() const { return messageIsError_; }

  private:
    enum class Drag { None, Orbit, Pan, Handle };

    void onMove(double x, double y);
    void onPress(MouseButton button, Modifiers mods);
    void onRelease(MouseButton button);
    void onKey(const KeyPress& key);
    void dragHandleTo(double y);
    void clampDragTowards(double wanted, int perUnit,
                          const std::function<Command(double)>& commandFor);
    void clickHandle(const Handle& h);
    void dropOnRail(const Handle& source);
    void releaseOverPanel(const Handle& h, bool click);
    void updateHover();
    void updatePointerNote();
    void say(std::string message, bool error);
    PieceId pieceAt(double x, double y) const;
    void changed();

    Document* doc_;
    Camera* camera_;
    InteractionSettings settings_;
    Mode mode_ = Mode::View;
    std::vector<Handle> handles_;
    int hovered_ = -1;
    PieceId hoveredPiece_, selected_;
    bool pointerOverPanel_ = false;

    Drag drag_ = Drag::None;
    MouseButton dragButton_ = MouseButton::Left;
    double cursorX_ = 0, cursorY_ = 0;
    double pressX_ = 0, pressY_ = 0, lastX_ = 0, lastY_ = 0;
    std::optional<Handle> dragHandle_;
    double dragStartValue_ = 0; ///< rows, columns, gear index or bar length when the drag began
    double lastApplied_ = 0;    ///< the value last executed during this drag

    CommandResult lastCreated_;
    std::uint64_t version_ = 1;
    std::string message_;
    bool messageIsError_ = false;
    bool messageIsPointerNote_ = false; ///< message_ is about the piece under the cursor
};

} // namespace netsculpt
