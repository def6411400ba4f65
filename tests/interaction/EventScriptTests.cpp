// The studio's event files (--play): parsing, the drag shorthand, round trips and messages.

#include "interaction/EventScript.h"
#include "model/Error.h"

#include <catch2/catch.hpp>

using namespace netsculpt;
using Catch::Matchers::Contains;

TEST_CASE("event script: every verb parses to the event a window would send", "[events]") {
    const auto steps = parseEventScript("# a comment\n"
                                        "frame 10\n"
                                        "\n"
                                        "move 400 300.5   # trailing comment\n"
                                        "press left\n"
                                        "release right ctrl+shift\n"
                                        "key ctrl+shift+z\n"
                                        "key f5\n"
                                        "key escape\n"
                                        "scroll -2\n");
    REQUIRE(steps.size() == 8);
    CHECK(std::get<FrameWait>(steps[0].what).frames == 10);
    CHECK(steps[0].line == 2);
    CHECK(std::get<InputEvent>(steps[1].what) == InputEvent{MouseMove{400, 300.5}});
    CHECK(steps[1].line == 4);
    CHECK(std::get<InputEvent>(steps[2].what) == InputEvent{MousePress{MouseButton::Left, {}}});
    CHECK(std::get<InputEvent>(steps[3].what) == InputEvent{MouseRelease{MouseButton::Right, {true, true, false}}});
    CHECK(std::get<InputEvent>(steps[4].what) == InputEvent{KeyPress{'Z', {true, true, false}}});
    CHECK(std::get<InputEvent>(steps[5].what) == InputEvent{KeyPress{keys::F1 + 4, {}}});
    CHECK(std::get<InputEvent>(steps[6].what) == InputEvent{KeyPress{keys::Escape, {}}});
    CHECK(std::get<InputEvent>(steps[7].what) == InputEvent{Scroll{-2}});
}

TEST_CASE("event script: drag expands to move, press, moves with frames, release", "[events]") {
    const auto steps = parseEventScript("drag left 100 200 100 240 4");
    // move, frame, press, frame, 4 x (move, frame), release
    REQUIRE(steps.size() == 4 + 8 + 1);
    CHECK(std::get<InputEvent>(steps[0].what) == InputEvent{MouseMove{100, 200}});
    CHECK(std::get<FrameWait>(steps[1].what).frames == 1);
    CHECK(std::get<InputEvent>(steps[2].what) == InputEvent{MousePress{MouseButton::Left, {}}});
    CHECK(std::get<InputEvent>(steps[4].what) == InputEvent{MouseMove{100, 210}});
    CHECK(std::get<InputEvent>(steps[10].what) == InputEvent{MouseMove{100, 240}});
    CHECK(std::get<InputEvent>(steps.back().what) == InputEvent{MouseRelease{MouseButton::Left, {}}});
}

TEST_CASE("event script: formatEvent reads back to the same event", "[events]") {
    const InputEvent events[] = {MouseMove{0.25, 799},
                                 MousePress{MouseButton::Middle, {false, false, true}},
                                 MouseRelease{MouseButton::Left, {}},
                                 KeyPress{'Y', {false, true, false}},
                                 KeyPress{keys::Home, {true, false, false}},
                                 KeyPress{'7', {}},
                                 Scroll{1.5}};
    for (const InputEvent& e : events) {
        const std::string line = formatEvent(e);
        INFO(line);
        const auto steps = parseEventScript(line);
        REQUIRE(steps.size() == 1);
        CHECK(std::get<InputEvent>(steps[0].what) == e);
    }
    CHECK(formatEvent(KeyPress{'Z', {true, true, false}}) == "key ctrl+shift+z");
}

TEST_CASE("event script: bad lines name the file, the line and what was expected", "[events]") {
    auto message = [](const std::string& text) {
        try {
            (void)parseEventScript(text, "play.events");
        } catch (const UserError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(message("frame 1\nwiggle 3"), Contains("play.events:2") && Contains("unknown event \"wiggle\""));
    CHECK_THAT(message("move 10"), Contains("play.events:1") && Contains("Y as a number"));
    CHECK_THAT(message("move 10 abc"), Contains("got \"abc\""));
    CHECK_THAT(message("press thumb"), Contains("expected left, right or middle"));
    CHECK_THAT(message("key hyper+q"), Contains("modifier \"hyper\""));
    CHECK_THAT(message("key ctrl+banana"), Contains("unknown"));
    CHECK_THAT(message("frame -3"), Contains("whole number"));
    CHECK_THAT(message("frame 2.5"), Contains("whole number"));
    CHECK_THROWS_AS(readEventScript("/nonexistent/file.events"), UserError);
}
