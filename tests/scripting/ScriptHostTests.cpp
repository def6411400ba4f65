// Running a script (scripting/ScriptHost.h): what a script is given, as the stock `lua`
// interpreter gives it.

#include "ScriptTestSupport.h"

#include <catch2/catch.hpp>

using namespace netsculpt;
using namespace netsculpt::test;

TEST_CASE("A script's arguments are its global arg and its main chunk's ...", "[host]") {
    const ScriptFolders f("arguments");
    lua::ScriptOptions o = f.options();
    o.args = {"14", "a b", "\xc3\xa9t\xc3\xa9"};
    const lua::ScriptResult r =
        f.run("local rows, name, season = ...\n"
              "assert(select('#', ...) == 3, 'got ' .. select('#', ...) .. ' values in ...')\n"
              "assert(rows == '14' and name == 'a b' and season == '\\u{e9}t\\u{e9}', rows)\n"
              "assert(arg[0] == 'test.lua' and arg[1] == rows and arg[3] == season and #arg == 3)",
              o);
    CHECK(r.error == "");
    CHECK(r.ok);

    SECTION("none given: ... is empty") {
        const auto none = f.run("assert(select('#', ...) == 0 and #arg == 0)");
        CHECK(none.error == "");
    }
}
