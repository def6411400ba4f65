#pragma once
// Recorded window events as text (the studio's --play file). One event per line; `#` starts a
// comment; blank lines are ignored. Pixel coordinates as in InputEvent.h (window pixels, origin
// top-left, y down).
//
//     frame N              render N frames before the next event (N >= 0)
//     move X Y             the cursor moves to (X, Y)
//     press BUTTON [MODS]  BUTTON = left | right | middle; MODS e.g. shift, ctrl+shift
//     release BUTTON [MODS]
//     key KEY              KEY = [ctrl+][shift+][alt+]NAME; NAME = a letter, a digit, escape,
//                          enter, tab, backspace, delete, left, right, up, down, home, end,
//                          space, f1 .. f12 (e.g. key ctrl+z, key ctrl+shift+z, key r)
//     scroll DY            DY wheel notches, > 0 = away from the user (zoom in)
//     drag BUTTON X0 Y0 X1 Y1 [STEPS]
//                          shorthand: move X0 Y0, frame 1, press, frame 1, STEPS moves (default
//                          8) on the line to (X1, Y1) with one frame after each, release
//
// Like a real pointer, give the cursor a frame to arrive before a press ("move", "frame 1",
// "press"): the panels decide whether a press is theirs from where the cursor was last frame.

#include "interaction/InputEvent.h"

#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace netsculpt {

/// Render this many frames before going on.
struct FrameWait {
    int frames = 1;
    bool operator==(const FrameWait&) const = default;
};

struct ScriptStep {
    std::variant<InputEvent, FrameWait> what;
    int line = 0; ///< 1-based line in the text it was read from
};

/// Parses an event file's text. Throws UserError "<name>:<line>: <what was wrong>, expected ...".
std::vector<ScriptStep> parseEventScript(std::string_view text, const std::string& name = "events");
/// Reads and parses a file (UserError when it cannot be read).
std::vector<ScriptStep> readEventScript(const std::string& path);

/// The line that parseEventScript reads back to `event` ("move 400 300", "key ctrl+z").
std::string formatEvent(const InputEvent& event);

/// Parses a key spelling ("ctrl+shift+z"); UserError naming the text and the valid names.
KeyPress parseKey(std::string_view text);

} // namespace netsculpt
