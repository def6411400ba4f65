// The limits that stop runaway scripts (scripting/Limits.h): an instruction budget and a memory
// limit; the host survives and reports, and a script cannot catch the limit's error.

#include "ScriptTestSupport.h"

#include "scripting/Limits.h"

#include <catch2/catch.hpp>

#include <atomic>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;

namespace {

lua::ScriptOptions limited(const ScriptFolders& f, std::uint64_t instructions, std::size_t mib) {
    lua::ScriptOptions o = f.options();
    o.maxInstructions = instructions;
    o.maxMemory = mib << 20;
    return o;
}

} // namespace

TEST_CASE("Budget and limit texts", "[limits]") {
    CHECK(lua::instructionBudgetText(1'000'000'000) == "10^9");
    CHECK(lua::instructionBudgetText(1000) == "10^3");
    CHECK(lua::instructionBudgetText(100) == "100");
    CHECK(lua::instructionBudgetText(2'500'000) == "2500000");
    CHECK(lua::memoryLimitText(std::size_t(512) << 20) == "512 MiB");
    CHECK(lua::memoryExceededMessage(std::size_t(512) << 20) ==
          "script exceeded 512 MiB of memory");
    CHECK(lua::instructionsExceededMessage(1'000'000'000) ==
          "script exceeded its budget of 10^9 instructions");
}

TEST_CASE("An endless loop is stopped by the instruction budget", "[limits]") {
    const ScriptFolders f("loop");
    const auto o = limited(f, 10'000'000, 64);
    SECTION("plain") {
        const auto r = f.run("local x = 0\nwhile true do x = x + 1 end", o, "loop.lua");
        CHECK_FALSE(r.ok);
        CHECK(r.stop == lua::Stop::Instructions);
        CHECK_THAT(r.error, Equals("loop.lua:2: script exceeded its budget of 10^7 instructions"));
        CHECK(r.instructions > 10'000'000);
        CHECK(r.instructions <= 10'001'000);
    }
    SECTION("inside pcall, xpcall and coroutines: the error cannot be caught") {
        for (const char* code :
             {"while true do pcall(function() while true do end end) end",
              "while true do xpcall(function() while true do end end, print) end",
              "while true do coroutine.resume(coroutine.create(function() while true do end end)) "
              "end",
              "local ok = pcall(function() while true do end end); print('survived')"}) {
            INFO(code);
            const auto r = f.run(code, o);
            CHECK(r.stop == lua::Stop::Instructions);
            CHECK_THAT(r.error, Contains("script exceeded its budget of 10^7 instructions"));
        }
    }
    SECTION("the host goes on") {
        CHECK_FALSE(f.run("while true do end", o).ok);
        const auto r = f.run("local s = 0 for i = 1, 1000 do s = s + i end assert(s == 500500)", o);
        CHECK(r.ok);
        CHECK(r.stop == lua::Stop::None);
    }
}

TEST_CASE("A finalizer cannot run past the instruction budget", "[limits]") {
    // Lua runs __gc finalizers with its hooks off: a finalizer's loop ran unseen by the budget
    // (an endless one hung `netsculpt run`, during the run or while the state closed).
    const ScriptFolders f("finalizer");
    const auto o = limited(f, 10'000'000, 64);
    for (const char* code :
         {"setmetatable({}, {__gc = function() for i = 1, 1e8 do end end})\n"
          "collectgarbage()",
          "local mt = {__gc = true}\nsetmetatable({}, mt)\n"
          "mt.__gc = function() for i = 1, 1e8 do end end"}) {
        INFO(code);
        const auto r = f.run(code, o, "gc.lua");
        CHECK_FALSE(r.ok);
        CHECK_THAT(r.error, Contains("gc.lua:") &&
                                Contains("setmetatable: a metatable with a __gc field is not "
                                         "allowed while the script has an instruction budget "
                                         "(10^7)"));
        CHECK(r.instructions < 1'000'000);
    }
    SECTION("other metatables work as before, and without a budget so does __gc") {
        CHECK(f.run("local t = setmetatable({}, {__index = function() return 7 end})\n"
                    "assert(t.x == 7)",
                    o)
                  .ok);
        const auto r = f.run("local n = 0\nsetmetatable({}, {__gc = function() n = 1 end})\n"
                             "collectgarbage()\nassert(n == 1)",
                             limited(f, 0, 64));
        CHECK(r.error == "");
        CHECK(r.ok);
    }
}

TEST_CASE("Finalizers that edit the sculpture run between calls, never inside one", "[limits]") {
    // Without a budget __gc is allowed. A finalizer ran by an allocation inside doc:knots and
    // rebuilt the piece it was reading (an AddressSanitizer heap-use-after-free).
    const ScriptFolders f("finalizer-edits");
    const auto r = f.run(
        "local ns = require 'netsculpt'\n"
        "local doc = ns.new()\n"
        "local pts = {} for i = 0, 47 do local a = 2 * math.pi * i / 48\n"
        "  pts[#pts + 1] = {1.5 * math.cos(a), 1.5 * math.sin(a), 5} end\n"
        "local top = doc:add_rail{points = pts, closed = true}\n"
        "local p = doc:attach_to_rail{rail = top, columns = 40, rows = 30, bar = 0.2}\n"
        "local n = 0\n"
        "for i = 1, 100 do\n"
        "  for k = 1, 20 do setmetatable({}, {__gc = function()\n"
        "    n = n + 1\n"
        "    doc:set_rows{piece = p, rows = 5 + n % 20}\n"
        "    if n % 3 == 0 then doc:undo() end end}) end\n"
        "  local rows = p:info().rows\n"
        "  assert(#doc:knots(p) == rows, 'knots of a piece edited during the call')\n"
        "  assert(#doc:piece_info(p).bar_lengths > 0 and #doc:report().pieces == 1)\n"
        "end\n"
        "assert(n > 100, n)",
        limited(f, 0, 256));
    CHECK(r.error == "");
    CHECK(r.ok);
}

TEST_CASE("A huge table is stopped by the memory limit", "[limits]") {
    const ScriptFolders f("memory");
    const auto o = limited(f, 0, 32);
    for (const char* code :
         {"local t = {} for i = 1, 1e9 do t[i] = i end",
          "local t = {} for i = 1, 1e9 do t[i] = {i} end", "local s = string.rep('x', 2^30)",
          "while true do pcall(function() local t = {} for i = 1, 1e9 do t[i] = i end end) end",
          "local t = {} while true do t[#t + 1] = tostring(#t) .. 'abcdefgh' end"}) {
        INFO(code);
        const auto r = f.run(code, o);
        CHECK_FALSE(r.ok);
        CHECK(r.stop == lua::Stop::Memory);
        CHECK(r.error == "script exceeded 32 MiB of memory");
        CHECK(r.peakMemory <= (std::size_t(32) << 20));
    }
    SECTION("the host goes on, and the limit does not get in the way of normal work") {
        const auto r =
            f.run("local ns = require 'netsculpt'\n"
                  "local doc = ns.new()\n"
                  "local pts = {} for i = 0, 63 do local a = 2 * math.pi * i / 64\n"
                  "  pts[#pts + 1] = {2 * math.cos(a), 2 * math.sin(a), 5} end\n"
                  "local r = doc:add_rail{points = pts, closed = true}\n"
                  "local p = doc:attach_to_rail{rail = r, columns = 200, rows = 200, bar = 0.1}\n"
                  "assert(#doc:knots(p) == 200)",
                  o);
        CHECK(r.error == "");
        CHECK(r.ok);
    }
}

TEST_CASE("An interrupt stops the script, also with no instruction budget", "[limits]") {
    const ScriptFolders f("interrupt");
    std::atomic<bool> interrupt{true}; // Ctrl-C was pressed
    auto o = limited(f, 0, 64);        // no budget: the hook runs for the interrupt alone
    o.interrupt = &interrupt;
    SECTION("an endless loop, inside pcall too, stops at the hook's first turn") {
        const auto r = f.run("local n = 0\nwhile true do pcall(function()\n"
                             "  while true do n = n + 1 end end) end",
                             o, "loop.lua");
        CHECK(r.stop == lua::Stop::Interrupted);
        CHECK_THAT(r.error, Equals("loop.lua:3: script interrupted (Ctrl-C)"));
        CHECK(r.instructions == 1000);
    }
    SECTION("a script that ends before the hook's first turn is not taken as done") {
        const auto r = f.run("local x = 1", o);
        CHECK_FALSE(r.ok);
        CHECK(r.stop == lua::Stop::Interrupted);
        CHECK_THAT(r.error, Equals("script interrupted (Ctrl-C)"));
    }
    SECTION("without the interrupt the same script runs") {
        interrupt = false;
        CHECK(f.run("local x = 1", o).ok);
    }
}

TEST_CASE("An interrupt during doc:relax stops the relaxation, then the script", "[limits]") {
    const ScriptFolders f("interrupt-relax");
    std::atomic<bool> interrupt{false};
    auto o = limited(f, 0, 64);
    o.interrupt = &interrupt;
    long long progressCalls = 0;
    o.relaxProgress = [&](const RelaxProgress&) { interrupt = ++progressCalls >= 2; };
    RelaxResult relaxed;
    o.relaxFinished = [&](const Document&, const RelaxResult& r) { relaxed = r; };
    const auto r = f.run(R"(local ns = require "netsculpt"
local doc = ns.new()
local ring = doc:add_rail{points = ns.circle{radius = 2, points = 48}, closed = true}
local p = doc:attach_to_rail{rail = ring, columns = 24, rows = 20, bar = 0.4}
local ok, e = pcall(doc.relax, doc, {backend = "rk4", max_seconds = 60})
print("went on"))",
                         o, "relaxing.lua");
    CHECK(r.stop == lua::Stop::Interrupted);
    CHECK_THAT(r.error, Equals("relax: script interrupted (Ctrl-C)"));
    CHECK(relaxed.stopReason == "cancelled");
    CHECK_FALSE(relaxed.converged);
    CHECK(relaxed.steps >= 1);
}
