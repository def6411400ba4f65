#pragma once
// Window-free input events: what the studio's window (GLFW callbacks) and a replayed event file
// (EventScript.h) both turn into, and what the interaction layer consumes. Pixel coordinates are
// window pixels with the origin at the top-left corner, y growing downwards (GLFW's convention).

#include <string>
#include <variant>

namespace netsculpt {

enum class MouseButton { Left, Right, Middle };

struct Modifiers {
    bool shift = false;
    bool ctrl = false;
    bool alt = false;
    bool operator==(const Modifiers&) const = default;
};

/// Key codes. Printable keys are their upper-case ASCII code ('A', 'Z', '1', ' ', '-'); the
/// special keys below have the values of GLFW's GLFW_KEY_* constants, so a GLFW key code is a Key.
namespace keys {
inline constexpr int Escape = 256;
inline constexpr int Enter = 257;
inline constexpr int Tab = 258;
inline constexpr int Backspace = 259;
inline constexpr int Delete = 261;
inline constexpr int Right = 262;
inline constexpr int Left = 263;
inline constexpr int Down = 264;
inline constexpr int Up = 265;
inline constexpr int Home = 268;
inline constexpr int End = 269;
inline constexpr int F1 = 290; ///< F1 .. F12 are F1 + 0 .. F1 + 11
} // namespace keys

/// The cursor moved to (x, y) pixels.
struct MouseMove {
    double x = 0, y = 0;
    bool operator==(const MouseMove&) const = default;
};
/// A button went down at the cursor's current position (the last MouseMove).
struct MousePress {
    MouseButton button = MouseButton::Left;
    Modifiers mods;
    bool operator==(const MousePress&) const = default;
};
struct MouseRelease {
    MouseButton button = MouseButton::Left;
    Modifiers mods;
    bool operator==(const MouseRelease&) const = default;
};
/// A key went down (repeats arrive as further KeyPress events).
struct KeyPress {
    int key = 0;
    Modifiers mods;
    bool operator==(const KeyPress&) const = default;
};
/// Wheel turned: dy > 0 away from the user (zoom in), in wheel notches.
struct Scroll {
    double dy = 0;
    bool operator==(const Scroll&) const = default;
};

using InputEvent = std::variant<MouseMove, MousePress, MouseRelease, KeyPress, Scroll>;

/// "left", "right", "middle".
std::string toString(MouseButton button);
/// "ctrl+shift+z", "escape", "f5", "3" — the event-file spelling of a key with modifiers.
std::string keyName(int key, Modifiers mods = {});

} // namespace netsculpt
