#include "interaction/Interaction.h"

#include "model/Edits.h"
#include "model/Error.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

namespace netsculpt {

namespace {

/// Gears ordered by the columns they give (what a drag up steps through), the allowed ones only.
std::vector<Gear> gearLadder(const Sculpture& s, const Piece& p) {
    const ParentEdge& edge = p.parentTop();
    const int n = int(sourceRow(s, edge).size());
    std::vector<Gear> ladder;
    for (Gear g : {Gear{1, 3}, Gear{1, 2}, Gear{1, 1}, Gear{2, 1}, Gear{3, 1}}) {
        try {
            (void)gearedColumns(n, edge.ringClosed, g);
            ladder.push_back(g);
        } catch (const UserError&) {
        }
    }
    return ladder;
}

/// The bar length of `p`'s last row at `column`: a piece graded by row has its last row's
/// everywhere in that row (BarProfile::at takes a row index then, not a column).
double lastRowBar(const Piece& p, int column) {
    return p.bar.at(p.bar.axis == BarAxis::Row ? p.rows - 1 : column);
}

/// A piece whose top row hangs from `rail`, or none.
PieceId pieceOnRail(const Sculpture& s, RailId rail) {
    for (const auto& [id, piece] : s.pieces)
        if (piece.onRail() && piece.railTop().rail == rail)
            return id;
    return PieceId{};
}

/// Handles that execute a command when clicked (the value handles act by dragging).
bool actsOnClick(HandleKind kind) {
    return kind == HandleKind::RailPoint || kind == HandleKind::LastRow ||
           kind == HandleKind::TopKnot;
}

/// Whole pixels of drag turned into whole steps, towards zero (a 7 px drag at 8 px/row is 0 rows).
/// (The small allowance keeps an exact multiple that arrives as 71.99999... px a whole step.)
int steps(double pixels, double pixelsPerStep) {
    const int n = int(std::floor(std::abs(pixels) / pixelsPerStep + 1e-6));
    return pixels < 0 ? -n : n;
}

} // namespace

int defaultColumns(double railLength, bool closedRail, double spacing, int maxColumns) {
    const double n = std::round(railLength / spacing) + (closedRail ? 0 : 1);
    return int(std::clamp(n, closedRail ? 3.0 : 2.0, double(std::max(maxColumns, 3))));
}

Interaction::Interaction(Document& doc, Camera& camera, InteractionSettings settings)
    : doc_(&doc), camera_(&camera), settings_(settings) {
    refresh();
}

void Interaction::setDocument(Document& doc) {
    doc_ = &doc;
    drag_ = Drag::None;
    dragHandle_.reset();
    hoveredPiece_ = selected_ = PieceId{};
    changed();
}

void Interaction::setMode(Mode mode) {
    if (drag_ == Drag::Handle) return; // finish the gesture first
    if (mode != mode_)
        say({}, false); // the message was about the old mode's work
    mode_ = mode;
    refresh();
}

void Interaction::changed() {
    ++version_;
    if (selected_ && !doc_->sculpture().hasPiece(selected_)) selected_ = PieceId{};
    refresh();
}

void Interaction::refresh() {
    const Sculpture& s = doc_->sculpture();
    if (drag_ == Drag::Handle && dragHandle_ && dragHandle_->kind == HandleKind::ConnectSource)
        handles_ = connectTargets(s, doc_->compiled(), dragHandle_->piece, settings_.handles);
    else
        handles_ = handlesForMode(mode_, s, doc_->compiled(), settings_.handles);
    updateHover();
}

void Interaction::frameAll() {
    const auto [lo, hi] = sceneBounds(doc_->sculpture(), doc_->compiled());
    camera_->frame(lo, hi);
}

void Interaction::updateHover() {
    hovered_ = drag_ == Drag::Orbit || drag_ == Drag::Pan || pointerOverPanel_
                   ? -1
                   : pickHandle(handles_, *camera_, cursorX_, cursorY_, settings_.pickRadiusPixels);
    updatePointerNote();
}

/// Divide mode offers no sphere on a piece that split refuses; while the cursor is on such a
/// piece (and on no sphere of another), the message gives split's reason, naming the piece and
/// what to do first. Split asks a piece graded by row for its bar length by column or one
/// length; the studio sets a graded piece's bars by row, so one length is its way there.
void Interaction::updatePointerNote() {
    const Sculpture& s = doc_->sculpture();
    const bool onPiece = mode_ == Mode::Divide && drag_ == Drag::None && hovered_ < 0 &&
                         hoveredPiece_ && s.hasPiece(hoveredPiece_);
    std::string refusal = onPiece ? splitRefusal(s, hoveredPiece_) : std::string();
    if (!refusal.empty() && s.piece(hoveredPiece_).bar.gradedByRow())
        refusal += " (here: give its bar top and bar last row one length in the inspector)";
    if (!refusal.empty()) {
        say(std::move(refusal), true);
        messageIsPointerNote_ = true;
    } else if (messageIsPointerNote_) {
        say({}, false); // the cursor left the piece: the mode's hint again
    }
}

void Interaction::say(std::string message, bool error) {
    message_ = std::move(message);
    messageIsError_ = error;
    messageIsPointerNote_ = false;
}

bool Interaction::execute(const Command& command, bool merge) {
    try {
        lastCreated_ = doc_->execute(command, merge);
    } catch (const UserError& e) {
        say(e.what(), true);
        return false;
    }
    say(commandName(command), false);
    changed();
    return true;
}

bool Interaction::undo() {
    if (drag_ == Drag::Handle || !doc_->canUndo()) return false;
    say("undo " + doc_->undoName(), false);
    doc_->undo();
    changed();
    return true;
}

bool Interaction::redo() {
    if (drag_ == Drag::Handle || !doc_->canRedo()) return false;
    say("redo " + doc_->redoName(), false);
    doc_->redo();
    changed();
    return true;
}

void Interaction::handle(const InputEvent& event) {
    if (const auto* move = std::get_if<MouseMove>(&event)) onMove(move->x, move->y);
    else if (const auto* press = std::get_if<MousePress>(&event)) onPress(press->button, press->mods);
    else if (const auto* release = std::get_if<MouseRelease>(&event)) onRelease(release->button);
    else if (const auto* key = std::get_if<KeyPress>(&event)) onKey(*key);
    else if (const auto* scroll = std::get_if<Scroll>(&event)) {
        camera_->zoom(scroll->dy);
        updateHover();
    }
}

void Interaction::onMove(double x, double y) {
    cursorX_ = x;
    cursorY_ = y;
    const double dx = x - lastX_, dy = y - lastY_;
    lastX_ = x;
    lastY_ = y;
    switch (drag_) {
    case Drag::Orbit: camera_->orbit(dx, dy, settings_.orbitRadiansPerPixel); break;
    case Drag::Pan: camera_->pan(dx, dy); break;
    case Drag::Handle: dragHandleTo(y); break;
    case Drag::None:
        hoveredPiece_ = pointerOverPanel_ ? PieceId{} : pieceAt(x, y);
        break;
    }
    updateHover();
}

void Interaction::onPress(MouseButton button, Modifiers mods) {
    if (drag_ != Drag::None) return; // a second button during a gesture is ignored
    pressX_ = lastX_ = cursorX_;
    pressY_ = lastY_ = cursorY_;
    dragButton_ = button;
    updateHover();
    if (button == MouseButton::Left && !mods.shift && hovered_ >= 0) {
        const Handle h = handles_[std::size_t(hovered_)];
        const Sculpture& s = doc_->sculpture();
        drag_ = Drag::Handle;
        dragHandle_ = h;
        if (h.piece) selected_ = h.piece;
        doc_->endGesture(); // this gesture never merges into an earlier one
        if (h.piece && s.hasPiece(h.piece)) {
            const Piece& p = s.piece(h.piece);
            switch (h.kind) {
            case HandleKind::RowsEnd: dragStartValue_ = p.rows; break;
            case HandleKind::ColumnsEdge:
                if (p.onRail()) dragStartValue_ = p.columns;
                else {
                    const auto ladder = gearLadder(s, p);
                    const auto at = std::find(ladder.begin(), ladder.end(), p.parentTop().gear);
                    dragStartValue_ = double(at - ladder.begin());
                }
                break;
            case HandleKind::BarEnd:
                dragStartValue_ = p.bar.at(h.barRow ? *h.barRow : h.barColumn.value_or(0));
                break;
            default: break;
            }
        }
        lastApplied_ = dragStartValue_;
        if (h.kind == HandleKind::ConnectSource) refresh(); // show the rails it may join
        return;
    }
    drag_ = (button == MouseButton::Left && !mods.shift) ? Drag::Orbit : Drag::Pan;
    hovered_ = -1;
}

void Interaction::onRelease(MouseButton button) {
    if (drag_ == Drag::None || button != dragButton_) return;
    const bool click = std::hypot(cursorX_ - pressX_, cursorY_ - pressY_) <= settings_.clickSlopPixels;
    const Drag was = drag_;
    drag_ = Drag::None;
    if (was == Drag::Handle && dragHandle_) {
        const Handle h = *std::exchange(dragHandle_, std::nullopt);
        if (pointerOverPanel_)
            releaseOverPanel(h, click);
        else if (h.kind == HandleKind::ConnectSource)
            dropOnRail(h);
        else if (click)
            clickHandle(h);
        doc_->endGesture();
        refresh();
        return;
    }
    if (was == Drag::Orbit && click && !pointerOverPanel_)
        selected_ = pieceAt(cursorX_, cursorY_);
    updateHover();
}

/// Drop on a rail sphere ("on top of" = projections within the pick radius); elsewhere nothing
/// happens and nothing is journaled.
void Interaction::dropOnRail(const Handle& source) {
    const int target =
        pickHandle(handles_, *camera_, cursorX_, cursorY_, settings_.pickRadiusPixels);
    if (target >= 0) {
        const Handle& t = handles_[std::size_t(target)];
        execute(ConnectToRailCommand{source.piece, t.rail, t.t, t.reverse});
    } else {
        say("connect: dropped away from the rails; nothing changed", false);
    }
}

/// A panel hides what a drop or a click released over it would act on (a rail sphere, a net
/// behind it), so neither acts. A value drag made its change as it moved; its release adds
/// nothing there or elsewhere.
void Interaction::releaseOverPanel(const Handle& h, bool click) {
    if (h.kind == HandleKind::ConnectSource)
        say("connect: dropped over a panel; nothing changed (drop the row on a rail sphere in "
            "the view)",
            false);
    else if (click && actsOnClick(h.kind))
        say(std::string(modeName(mode_)) + ": released over a panel; nothing changed", false);
}

void Interaction::clickHandle(const Handle& h) {
    const Sculpture& s = doc_->sculpture();
    switch (h.kind) {
    case HandleKind::RailPoint: {
        if (!s.hasRail(h.rail)) return;
        const Curve& curve = s.rail(h.rail).curve();
        AttachToRailArgs args;
        args.rail = h.rail;
        args.rows = settings_.newPieceRows;
        args.bar = settings_.newPieceBar;
        args.columns = defaultColumns(curve.length(), curve.closed(), settings_.newPieceSpacingRatio * args.bar,
                                      settings_.newPieceMaxColumns);
        args.at = curve.closed() ? h.t : 0; // a piece on an open rail spans it from its start
        const PieceId already = pieceOnRail(s, h.rail);
        if (!execute(AttachToRailCommand{args}))
            break;
        selected_ = lastCreated_.pieces.front();
        if (already)
            say("attach_to_rail: " + toString(h.rail) + " already holds " + toString(already) +
                    "; the new piece hangs over it (Ctrl+Z takes it back)",
                false);
        break;
    }
    case HandleKind::LastRow: {
        AttachToPieceArgs args;
        args.parent = h.piece;
        args.gear = Gear{1, 1};
        args.rows = settings_.newPieceRows;
        args.bar = s.hasPiece(h.piece) ? lastRowBar(s.piece(h.piece), h.column)
                                       : settings_.newPieceBar;
        if (s.hasPiece(h.piece))
            args.material = s.piece(h.piece).material; // knotted from its parent's rope
        if (execute(AttachToPieceCommand{args})) selected_ = lastCreated_.pieces.front();
        break;
    }
    case HandleKind::TopKnot: execute(SplitCommand{h.piece, h.column}); break;
    default: break; // value handles do nothing on a click
    }
}

void Interaction::dragHandleTo(double y) {
    const Handle& h = *dragHandle_;
    const double down = y - pressY_; // pixels dragged downwards
    const Sculpture& s = doc_->sculpture();
    if (!h.piece || !s.hasPiece(h.piece)) return;
    const Piece& p = s.piece(h.piece);
    const PieceId id = h.piece;
    std::function<Command(double)> commandFor;
    double value = lastApplied_;
    int perUnit = 1; // values are whole multiples of 1 / perUnit
    switch (h.kind) {
    case HandleKind::RowsEnd:
        value = std::max(1, int(dragStartValue_) + steps(down, settings_.pixelsPerRow));
        commandFor = [id](double v) { return SetRowsCommand{id, int(v)}; };
        break;
    case HandleKind::ColumnsEdge:
        if (p.onRail()) { // up = smaller spacing = more columns
            value = std::max(p.closed ? 3 : 2, int(dragStartValue_) + steps(-down, settings_.pixelsPerColumn));
            commandFor = [id](double v) { return SetColumnsCommand{id, int(v)}; };
        } else { // below a piece: step through the gears that divide the parent's row
            const auto ladder = gearLadder(s, p);
            if (ladder.empty()) return;
            value = std::clamp(int(dragStartValue_) + steps(-down, settings_.pixelsPerGear), 0, int(ladder.size()) - 1);
            commandFor = [id, ladder](double v) {
                return SetGearCommand{id, ladder[std::size_t(v)]};
            };
        }
        break;
    case HandleKind::BarEnd: { // up = shorter, down = longer; whole millimetres
        const double length = std::round((dragStartValue_ + down * settings_.barMetresPerPixel) * 1000) / 1000;
        value = std::max(0.001, length);
        perUnit = 1000;
        const std::optional<int> column = h.barColumn, row = h.barRow;
        commandFor = [id, column, row](double v) {
            return SetBarLengthCommand{id, column, row, v};
        };
        break;
    }
    default:
        return; // a connect drag changes only what is hovered
    }
    if (value == lastApplied_) return;
    if (execute(commandFor(value), /*merge=*/true)) {
        lastApplied_ = value;
        return;
    }
    clampDragTowards(value, perUnit, commandFor);
}

/// A drag past what the design allows stops at the last allowed value on the way (found by
/// halving, in whole units: values are whole multiples of 1 / perUnit), and the message names
/// the limit: the refusal of the value one unit past it.
void Interaction::clampDragTowards(double wanted, int perUnit,
                                   const std::function<Command(double)>& commandFor) {
    const std::string refusal = message_; // of `wanted`, which was just refused
    const auto valueOf = [perUnit](long long units) { return double(units) / perUnit; };
    const long long target = std::llround(wanted * perUnit);
    long long allowed = std::llround(lastApplied_ * perUnit), refused = target;
    while (std::llabs(refused - allowed) > 1) {
        const long long middle = allowed + (refused - allowed) / 2;
        if (execute(commandFor(valueOf(middle)), /*merge=*/true)) {
            allowed = middle;
            lastApplied_ = valueOf(middle);
        } else {
            refused = middle;
        }
    }
    const long long next = allowed + (target > allowed ? 1 : -1);
    if (next == target) { // its refusal is the one to show
        say(refusal, true);
    } else if (execute(commandFor(valueOf(next)), /*merge=*/true)) { // refused: its message stays
        lastApplied_ = valueOf(next);
    }
}

void Interaction::onKey(const KeyPress& key) {
    const Modifiers m = key.mods;
    if (drag_ == Drag::Handle) return;
    if (m.ctrl && !m.alt) {
        if (key.key == 'Z' && !m.shift) undo();
        else if ((key.key == 'Z' && m.shift) || (key.key == 'Y' && !m.shift)) redo();
        return;
    }
    if (m.alt) return;
    static constexpr std::pair<int, Mode> modeKeys[] = {
        {'V', Mode::View},    {'N', Mode::NewNet},    {'D', Mode::Divide}, {'R', Mode::Rows},
        {'C', Mode::Columns}, {'B', Mode::BarLength}, {'J', Mode::Connect}};
    for (const auto& [k, mode] : modeKeys)
        if (key.key == k) return setMode(mode);
    if (key.key >= '1' && key.key < '1' + int(std::size(kAllModes))) return setMode(kAllModes[key.key - '1']);
    switch (key.key) {
    case 'T': camera_->setPreset(ViewPreset::Top); break;
    case 'F': camera_->setPreset(ViewPreset::Front); break;
    case 'S': camera_->setPreset(ViewPreset::Side); break;
    case 'P': camera_->setPreset(ViewPreset::Perspective); break;
    case keys::Home: frameAll(); break;
    case keys::Escape: setMode(Mode::View); break;
    default: return;
    }
    updateHover();
}

PieceId Interaction::pieceAt(double x, double y) const {
    const MassSpringSystem& sys = doc_->compiled().system;
    double best = settings_.pickRadiusPixels, bestDepth = std::numeric_limits<double>::infinity();
    PieceId found;
    for (std::size_t j = 0; j < sys.knotCount(); ++j) {
        if (sys.refStart.size() <= j + 1 || sys.refStart[j] == sys.refStart[j + 1]) continue;
        const ScreenPoint sp = camera_->project(sys.worldPosition(j));
        if (!sp.visible) continue;
        const double d = std::hypot(sp.x - x, sp.y - y);
        if (d < best - 0.5 || (d < best + 0.5 && sp.depth < bestDepth)) {
            best = d;
            bestDepth = sp.depth;
            found = sys.refs[sys.refStart[j]].piece;
        }
    }
    return found;
}

} // namespace netsculpt
