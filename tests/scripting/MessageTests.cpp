// Error messages of the binding: the script's file:line, the call, the argument, the bad value and
// what is allowed; a failed call leaves the sculpture and its journal as they were.

#include "ScriptTestSupport.h"

#include <catch2/catch.hpp>

#include <fstream>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;
using Catch::Matchers::StartsWith;

namespace {

const char* const kPrelude =
    "local ns = require 'netsculpt'\n"
    "local doc = ns.new()\n"
    "local pts = {} for i = 0, 47 do local a = 2 * math.pi * i / 48\n"
    "  pts[#pts + 1] = {2 * math.cos(a), 2 * math.sin(a), 5} end\n"
    "local ring = doc:add_rail{name = 'ring', points = pts, closed = true}\n"
    "local p = doc:attach_to_rail{rail = ring, columns = 36, rows = 6, bar = 0.3}\n";

std::size_t lineCount(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::size_t n = 0;
    for (std::string line; std::getline(in, line);)
        ++n;
    return n;
}

} // namespace

TEST_CASE("A bad argument names the call, the argument, the value and the place", "[messages]") {
    const ScriptFolders f("messages");
    const std::pair<const char*, const char*> cases[] = {
        {"doc:attach_to_rail{rail = ring, columns = 36, rows = -3}",
         "sculpture.lua:7: attach_to_rail: argument 'rows' must be a whole number from 1 to "
         "100000, got -3"},
        {"doc:set_bar_length{piece = p, length = 'long'}",
         "sculpture.lua:7: set_bar_length: argument 'length' must be a finite number > 0, got "
         "\"long\""},
        {"doc:attach_to_piece{piece = ring, rows = 3}",
         "sculpture.lua:7: attach_to_piece: argument 'piece' must be a piece handle, got rail 1"},
        {"doc:add_rail{points = {{0, 0, 0}, {1, 0}}}",
         "sculpture.lua:7: add_rail: argument 'points[2]' must be a point {x, y, z} of three "
         "finite numbers, "
         "got a table of 2 values"},
        {"doc:add_rail{control = {{0, 0, 0}, {1, 0, 0}}, sampling = 'even'}",
         "sculpture.lua:7: add_rail: argument 'sampling' must be one of \"arclength\" or "
         "\"parameter\", got \"even\""},
        {"doc:remove_piece{piece = p}; p:info()", "sculpture.lua:7: info: piece 1 was removed"},
        {"doc:split{piece = p, column = 36}",
         "sculpture.lua:7: split: column must be from 1 to 35 for piece 1"},
    };
    for (const auto& [code, message] : cases) {
        INFO(code);
        const auto r = f.run(std::string(kPrelude) + code, f.options(), "sculpture.lua");
        CHECK_FALSE(r.ok);
        CHECK_THAT(r.error, StartsWith(message));
        CHECK_THAT(r.traceback, StartsWith("stack traceback:"));
    }
}

TEST_CASE("A failed call leaves the sculpture and the journal as they were", "[messages]") {
    const ScriptFolders f("unchanged");
    auto o = f.options();
    o.journal = true;
    o.journalStem = "unchanged";
    const auto r =
        f.run(std::string(kPrelude) +
                  "local before = doc:hash()\n"
                  "local bad = {{rows = 0}, {gear = 5}, {bar = 0.01}, {rows = 3, bar = -1}}\n"
                  "for _, args in ipairs(bad) do\n"
                  "  args.piece = p; args.rows = args.rows or 3\n"
                  "  assert(not pcall(doc.attach_to_piece, doc, args))\n"
                  "  assert(doc:hash() == before and #doc:pieces() == 1)\n"
                  "end\n"
                  "assert(not pcall(doc.split, doc, {piece = p, column = 99}))\n"
                  "assert(doc:hash() == before)\n",
              o);
    CHECK(r.error == "");
    REQUIRE(r.journals.size() == 1);
    CHECK(lineCount(r.journals[0]) == 1 + 2); // the header, add_rail and attach_to_rail only
}
