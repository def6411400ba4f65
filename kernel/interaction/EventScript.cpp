#include "interaction/EventScript.h"

#include "model/Error.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace netsculpt {

namespace {

struct NamedKey {
    const char* name;
    int key;
};

constexpr NamedKey kNamedKeys[] = {
    {"escape", keys::Escape}, {"enter", keys::Enter}, {"tab", keys::Tab},     {"backspace", keys::Backspace},
    {"delete", keys::Delete}, {"right", keys::Right}, {"left", keys::Left},   {"down", keys::Down},
    {"up", keys::Up},         {"home", keys::Home},   {"end", keys::End},     {"space", ' '},
};

std::string lower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return out;
}

std::vector<std::string> splitWords(std::string_view line) {
    std::vector<std::string> words;
    std::istringstream in{std::string(line)};
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

std::vector<std::string> splitPlus(const std::string& text) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (;;) {
        const std::size_t plus = text.find('+', start);
        parts.push_back(text.substr(start, plus - start));
        if (plus == std::string::npos) break;
        start = plus + 1;
    }
    return parts;
}

bool parseNumber(const std::string& text, double& value) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end && std::isfinite(value);
}

MouseButton parseButton(const std::string& text) {
    const std::string b = lower(text);
    if (b == "left") return MouseButton::Left;
    if (b == "right") return MouseButton::Right;
    if (b == "middle") return MouseButton::Middle;
    throw UserError("mouse button \"" + text + "\" is unknown, expected left, right or middle");
}

Modifiers parseMods(const std::string& text) {
    Modifiers mods;
    for (const std::string& part : splitPlus(lower(text))) {
        if (part == "shift") mods.shift = true;
        else if (part == "ctrl") mods.ctrl = true;
        else if (part == "alt") mods.alt = true;
        else throw UserError("modifier \"" + part + "\" is unknown, expected shift, ctrl or alt joined by +");
    }
    return mods;
}

std::string modsPrefix(Modifiers mods) {
    return std::string(mods.ctrl ? "ctrl+" : "") + (mods.shift ? "shift+" : "") + (mods.alt ? "alt+" : "");
}

} // namespace

std::string toString(MouseButton button) {
    switch (button) {
    case MouseButton::Left: return "left";
    case MouseButton::Right: return "right";
    case MouseButton::Middle: return "middle";
    }
    return "left";
}

std::string keyName(int key, Modifiers mods) {
    std::string name;
    for (const NamedKey& k : kNamedKeys)
        if (k.key == key) name = k.name;
    char buffer[16];
    if (name.empty() && key >= keys::F1 && key < keys::F1 + 12) {
        std::snprintf(buffer, sizeof buffer, "f%d", key - keys::F1 + 1);
        name = buffer;
    }
    if (name.empty() && key > ' ' && key < 127) name = std::string(1, char(std::tolower(key)));
    if (name.empty()) {
        std::snprintf(buffer, sizeof buffer, "key%d", key);
        name = buffer;
    }
    std::string out = modsPrefix(mods);
    out += name;
    return out;
}

KeyPress parseKey(std::string_view text) {
    const std::vector<std::string> parts = splitPlus(lower(text));
    KeyPress press;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
        const std::string& part = parts[i];
        if (part == "shift") press.mods.shift = true;
        else if (part == "ctrl") press.mods.ctrl = true;
        else if (part == "alt") press.mods.alt = true;
        else throw UserError("key \"" + std::string(text) + "\": modifier \"" + part +
                             "\" is unknown, expected shift, ctrl or alt");
    }
    const std::string& name = parts.back();
    for (const NamedKey& k : kNamedKeys)
        if (name == k.name) {
            press.key = k.key;
            return press;
        }
    if (name.size() >= 2 && name[0] == 'f' && std::all_of(name.begin() + 1, name.end(), ::isdigit)) {
        const int n = std::stoi(name.substr(1));
        if (n >= 1 && n <= 12) {
            press.key = keys::F1 + n - 1;
            return press;
        }
    }
    if (name.size() == 1 && name[0] > ' ' && name[0] < 127) {
        press.key = std::toupper(static_cast<unsigned char>(name[0]));
        return press;
    }
    throw UserError("key \"" + std::string(text) +
                    "\" is unknown, expected [ctrl+][shift+][alt+] and a letter, a digit, escape, enter, "
                    "tab, backspace, delete, left, right, up, down, home, end, space or f1 .. f12");
}

std::vector<ScriptStep> parseEventScript(std::string_view text, const std::string& name) {
    std::vector<ScriptStep> steps;
    std::istringstream in{std::string(text)};
    int lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        const std::vector<std::string> w = splitWords(line);
        if (w.empty()) continue;
        auto fail = [&](const std::string& why) -> UserError {
            return UserError(name + ":" + std::to_string(lineNumber) + ": " + why);
        };
        auto number = [&](std::size_t i, const char* what) {
            double v = 0;
            if (i >= w.size() || !parseNumber(w[i], v))
                throw fail(std::string("\"") + w[0] + "\" needs " + what + " as a number" +
                           (i < w.size() ? ", got \"" + w[i] + "\"" : ""));
            return v;
        };
        auto push = [&](auto what) { steps.push_back(ScriptStep{what, lineNumber}); };
        const std::string verb = lower(w[0]);
        try {
            if (verb == "frame") {
                const double n = number(1, "a frame count");
                if (n < 0 || n != std::floor(n) || n > 1e7)
                    throw fail("frame count must be a whole number from 0 to 10^7, got " + w[1]);
                push(FrameWait{int(n)});
            } else if (verb == "move") {
                push(InputEvent{MouseMove{number(1, "X"), number(2, "Y")}});
            } else if (verb == "press" || verb == "release") {
                if (w.size() < 2 || w.size() > 3) throw fail(verb + " takes a button and optional modifiers");
                const MouseButton button = parseButton(w[1]);
                const Modifiers mods = w.size() == 3 ? parseMods(w[2]) : Modifiers{};
                if (verb == "press") push(InputEvent{MousePress{button, mods}});
                else push(InputEvent{MouseRelease{button, mods}});
            } else if (verb == "key") {
                if (w.size() != 2) throw fail("key takes one key, e.g. \"key ctrl+z\"");
                push(InputEvent{parseKey(w[1])});
            } else if (verb == "scroll") {
                push(InputEvent{Scroll{number(1, "DY")}});
            } else if (verb == "drag") {
                if (w.size() < 6 || w.size() > 7) throw fail("drag takes BUTTON X0 Y0 X1 Y1 [STEPS]");
                const MouseButton button = parseButton(w[1]);
                const double x0 = number(2, "X0"), y0 = number(3, "Y0"), x1 = number(4, "X1"), y1 = number(5, "Y1");
                const double n = w.size() == 7 ? number(6, "STEPS") : 8;
                if (n < 1 || n != std::floor(n) || n > 1e5)
                    throw fail("drag steps must be a whole number from 1 to 10^5, got " + w[6]);
                push(InputEvent{MouseMove{x0, y0}});
                push(FrameWait{1}); // the pointer arrives (and the UI sees where it is) before the press
                push(InputEvent{MousePress{button, {}}});
                push(FrameWait{1});
                for (int i = 1; i <= int(n); ++i) {
                    const double f = double(i) / n;
                    push(InputEvent{MouseMove{x0 + (x1 - x0) * f, y0 + (y1 - y0) * f}});
                    push(FrameWait{1});
                }
                push(InputEvent{MouseRelease{button, {}}});
            } else {
                throw fail("unknown event \"" + w[0] + "\", expected frame, move, press, release, key, scroll or drag");
            }
        } catch (const UserError& e) {
            const std::string what = e.what();
            if (what.rfind(name + ":", 0) == 0) throw;
            throw fail(what);
        }
    }
    return steps;
}

std::vector<ScriptStep> readEventScript(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw UserError("cannot read event file \"" + path + "\"");
    std::ostringstream text;
    text << in.rdbuf();
    return parseEventScript(text.str(), path);
}

std::string formatEvent(const InputEvent& event) {
    auto number = [](double v) { return formatNumber(v); };
    return std::visit(
        [&](const auto& e) -> std::string {
            using T = std::decay_t<decltype(e)>;
            if constexpr (std::is_same_v<T, MouseMove>) return "move " + number(e.x) + " " + number(e.y);
            else if constexpr (std::is_same_v<T, MousePress> || std::is_same_v<T, MouseRelease>) {
                std::string out = std::is_same_v<T, MousePress> ? "press " : "release ";
                out += toString(e.button);
                if (const std::string mods = modsPrefix(e.mods); !mods.empty()) {
                    out += ' ';
                    out.append(mods, 0, mods.size() - 1);
                }
                return out;
            } else if constexpr (std::is_same_v<T, KeyPress>) return "key " + keyName(e.key, e.mods);
            else return "scroll " + number(e.dy);
        },
        event);
}

} // namespace netsculpt
