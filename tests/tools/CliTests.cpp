// The netsculpt program (tools/cli): exit codes (0 success, 1 user error, 2 usage error), --help,
// --version, and each subcommand on a small sculpture.

#include "CliSupport.h"

#include "io/Import.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <sys/file.h>
#include <unistd.h>
#include <utility>
#include <vector>

using namespace netsculpt::test;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using Catch::Matchers::StartsWith;
namespace fs = std::filesystem;

namespace {

const char* const kSmallSculpture = R"(local ns = require "netsculpt"
local doc = ns.new()
local pts = {}
for i = 0, 47 do local a = 2 * math.pi * i / 48; pts[#pts + 1] = {2 * math.cos(a), 2 * math.sin(a), 5} end
local ring = doc:add_rail{name = "ring", points = pts, closed = true}
local p = doc:attach_to_rail{rail = ring, columns = 24, rows = 4, bar = 0.4}
doc:set_material{piece = p, stiffness = 100, breaking_load = 40}
local q = doc:attach_to_piece{piece = p, gear = 2, rows = 3, bar = 0.3}
doc:set_material{piece = q, stiffness = 100, breaking_load = false}
doc:set_rows{piece = q, rows = 5}
doc:undo()
doc:redo()
print("hash " .. doc:hash())
)";

/// The "hash 0123..." a script printed.
std::string printedHash(const std::string& output) {
    const auto at = output.find("hash ");
    return at == std::string::npos ? std::string() : output.substr(at + 5, 16);
}

} // namespace

TEST_CASE("Help, version and usage errors", "[cli]") {
    const Ran help = runCli("--help");
    CHECK(help.exitCode == 0);
    for (const char* sub : {"run", "replay", "to-lua", "relax", "export", "report"})
        CHECK_THAT(help.output, Contains(sub));
    for (const char* sub : {"run", "replay", "to-lua", "relax", "export", "report"}) {
        INFO(sub);
        const Ran r = runCli(std::string(sub) + " --help");
        CHECK(r.exitCode == 0);
        CHECK_THAT(r.output, Contains("Usage"));
    }
    CHECK_THAT(runCli("run --help").output, Contains("--max-memory") &&
                                                Contains("--max-instructions") &&
                                                Contains("--unsafe") && Contains("--backend"));
    const Ran version = runCli("--version");
    CHECK(version.exitCode == 0);
    CHECK_THAT(version.output, StartsWith("netsculpt "));
    for (const char* bad :
         {"", "frobnicate", "run", "run x.lua --bogus", "relax d.netj --backend warp",
          "run x.lua --max-memory -3", "report d.netj --json --csv"}) {
        INFO(bad);
        const Ran r = runCli(bad);
        CHECK(r.exitCode == 2);
        CHECK_THAT(r.output, StartsWith("netsculpt: error: "));
    }
    // A misspelt command or option is named, with the nearest option.
    CHECK_THAT(runCli("reprot x.nets").output,
               Contains("unknown command 'reprot'; the commands are run, replay, to-lua, relax, "
                        "export, report"));
    CHECK_THAT(runCli("relax d.netj --tolerence 1e-7").output,
               Contains("unknown option --tolerence (did you mean --tolerance?)\n"));
    CHECK_THAT(runCli("report d.netj --jsn").output, Contains("did you mean --json?"));
    CHECK_THAT(runCli("relax d.netj --frobnicate").output,
               Contains("unknown option --frobnicate\n"));
    // A short option is offered only for a near word: "--bogus" was "did you mean --out?".
    CHECK_THAT(runCli("relax d.netj --bogus").output, Contains("unknown option --bogus\n"));
    CHECK_THAT(runCli("relax d.netj --ot").output,
               Contains("unknown option --ot (did you mean --out?)\n"));
}

TEST_CASE("A misspelt option followed by its value is named alone, not the document after it",
          "[cli]") {
    // `relax --tolerence 1 out/x.netj` said "unexpected arguments: --tolerence out/x.netj": CLI11
    // took the 1 for the document and listed the document as unexpected.
    const std::string tolerance = "netsculpt: error: unknown option --tolerence (did you mean "
                                  "--tolerance?)\nRun with --help for more information.\n";
    for (const char* arguments :
         {"relax --tolerence 1 out/x.netj", "relax out/x.netj --tolerence 1",
          "relax --tolerence=1 out/x.netj", "-q relax --tolerence 1 out/x.netj",
          "relax --tolerence 1 out/x.netj -q"}) {
        INFO(arguments);
        const Ran r = runCli(arguments);
        CHECK(r.exitCode == 2);
        CHECK(r.output == tolerance);
    }
    for (const auto& [arguments, message] :
         {std::pair{"export --tube-radus 0.01 d.netj net.obj",
                    "unknown option --tube-radus (did you mean --tube-radius?)\n"},
          std::pair{"report --frobnicate 1 d.netj", "unknown option --frobnicate\n"},
          std::pair{"relax d.netj -x", "unknown option -x\n"},
          std::pair{"--quite relax d.netj", "unknown option --quite\n"},
          std::pair{"relax --tolerence 1 --bogus 2 d.netj",
                    "unknown options --tolerence (did you mean --tolerance?), --bogus\n"},
          std::pair{"run x.lua --bogus 2",
                    "unknown option --bogus (a script's own arguments that start with - go after "
                    "--: netsculpt run SCRIPT -- --bogus)\n"},
          // Without an unknown option, arguments left over are the user's own, listed.
          std::pair{"relax a.netj b.netj c.netj", "unexpected arguments: b.netj c.netj\n"},
          std::pair{"relax d.netj -3", "unexpected arguments: -3\n"}}) {
        INFO(arguments);
        const Ran r = runCli(arguments);
        CHECK(r.exitCode == 2);
        CHECK_THAT(r.output, StartsWith("netsculpt: error: " + std::string(message)));
    }
}

TEST_CASE("Without a command, the error lists the commands and how to get help", "[cli]") {
    // It said "A subcommand is required", naming none.
    for (const char* arguments : {"", "-q"}) {
        INFO(arguments);
        const Ran r = runCli(arguments);
        CHECK(r.exitCode == 2);
        CHECK_THAT(r.output,
                   StartsWith("netsculpt: error: no command given; the commands are:\n"
                              "  run     Run a sculpture script (sandboxed unless --unsafe)\n"
                              "  replay  Replay a journal, check it and print the sculpture's "
                              "hash\n"));
        for (const char* command : {"\n  to-lua  ", "\n  relax   ", "\n  export  ", "\n  report  "})
            CHECK_THAT(r.output, Contains(command));
        CHECK_THAT(r.output,
                   Contains("\n'netsculpt COMMAND --help' describes a command's arguments "
                            "and options.\nRun with --help for more information.\n"));
    }
    // An option that is not a global one is named too, with the nearest one.
    const Ran misspelt = runCli("--quite");
    CHECK(misspelt.exitCode == 2);
    CHECK_THAT(
        misspelt.output,
        StartsWith("netsculpt: error: unknown option --quite (did you mean --quiet?), and no "
                   "command given; the commands are:\n  run "));
}

TEST_CASE("A missing argument is named as the usage line names it, with what it is", "[cli]") {
    // export DOC without its files said "files is required", CLI11's name for them.
    for (const auto& [arguments, message] :
         {std::pair{"export d.netj",
                    "export needs FILE..., the files to write, by extension: .csv .obj .ply .glb "
                    ".json .svg .png .dxf (with --rails: .csv .obj .dxf); usage: netsculpt export "
                    "DOC FILE...\n"},
          std::pair{"export d.netj --rails", "export needs FILE..., the files to write"},
          std::pair{"export", "export needs DOC, a journal (.netj) or snapshot (.nets); usage: "
                              "netsculpt export DOC FILE...\n"},
          std::pair{"run", "run needs SCRIPT, the Lua script; usage: netsculpt run SCRIPT "
                           "[ARGS...]\n"},
          std::pair{"-q run --out x", "run needs SCRIPT, the Lua script"},
          std::pair{"replay", "replay needs JOURNAL, the journal (.netj); usage: netsculpt "
                              "replay JOURNAL\n"},
          std::pair{"to-lua", "to-lua needs JOURNAL, the journal (.netj) or snapshot (.nets); "
                              "usage: netsculpt to-lua JOURNAL\n"},
          std::pair{"relax --max-steps 5", "relax needs DOC, a journal (.netj) or snapshot "
                                           "(.nets); usage: netsculpt relax DOC\n"},
          std::pair{"report --json", "report needs DOC, a journal (.netj) or snapshot (.nets); "
                                     "usage: netsculpt report DOC\n"},
          std::pair{"export d.netj --frobnicate",
                    "unknown option --frobnicate, and export needs FILE..., the files"}}) {
        INFO(arguments);
        const Ran r = runCli(arguments);
        CHECK(r.exitCode == 2);
        CHECK_THAT(r.output, StartsWith("netsculpt: error: " + std::string(message)));
        CHECK_THAT(r.output, EndsWith("\nRun with --help for more information.\n"));
    }
    // --help's usage line names them so too.
    CHECK_THAT(runCli("export --help").output,
               Contains("Usage: netsculpt export [OPTIONS] DOC FILE...\n"));
    CHECK_THAT(runCli("run --help").output,
               Contains("Usage: netsculpt run [OPTIONS] SCRIPT [ARGS...]\n"));
}

TEST_CASE("A command's help lists each positional by name and what it is, its options with their "
          "type, range and default",
          "[cli]") {
    // It listed "DOC TEXT REQUIRED", CLI11's type and flag, which the usage line already says.
    const std::string doc = "A journal (.netj) or snapshot (.nets)";
    const std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>>
        commands{
            {"run",
             {{"SCRIPT", "The Lua script"},
              {"ARGS...", "Arguments for the script (its global `arg`); put -- before ones "
                          "starting with -"}}},
            {"replay", {{"JOURNAL", "The journal (.netj)"}}},
            {"to-lua", {{"JOURNAL", "The journal (.netj) or snapshot (.nets)"}}},
            {"relax", {{"DOC", doc}}},
            {"export",
             {{"DOC", doc},
              {"FILE...", "The files to write, by extension: .csv .obj .ply .glb .json .svg .png "
                          ".dxf (with --rails: .csv .obj .dxf)"}}},
            {"report", {{"DOC", doc}}}};
    for (const auto& [command, positionals] : commands) {
        INFO(command);
        const Ran help = runCli(command + " --help");
        REQUIRE(help.exitCode == 0);
        const auto start = help.output.find("\nPositionals:\n");
        REQUIRE(start != std::string::npos);
        const auto end = help.output.find("\n\n", start + 1);
        REQUIRE(end != std::string::npos);
        std::istringstream section(help.output.substr(start + 14, end - start - 14));
        std::string line;
        for (const auto& [name, description] : positionals) {
            REQUIRE(std::getline(section, line));
            INFO(line);
            // "  DOC", the padding to the description's column, the description.
            CHECK_THAT(line, StartsWith("  " + name + "  "));
            const auto text = line.find_first_not_of(' ', name.size() + 2);
            REQUIRE(text != std::string::npos);
            CHECK(text == 30); // CLI11's first column, as the options' descriptions
            CHECK(line.substr(text) == description);
        }
        CHECK_FALSE(std::getline(section, line)); // no other positional
        CHECK_THAT(help.output, !Contains("REQUIRED"));
    }
    // The options keep their type, range and default.
    CHECK_THAT(runCli("relax --help").output,
               Contains("\n  --tolerance FLOAT:NUMBER in (0, 0.01]=1e-06\n") &&
                   Contains("\n  --backend TEXT:{auto,fast,rk4,bullet}=auto\n"));
    CHECK_THAT(runCli("run --help").output, Contains("\n  --lib TEXT:DIR ...  "));
}

TEST_CASE("export --rails writes the rails alone, unrelaxed, and import_rails reads them back",
          "[cli]") {
    const fs::path dir = freshFolder("rails");
    const fs::path script = writeScript(dir, "small.lua", kSmallSculpture);
    REQUIRE(runCli("run " + quoted(script) + " --out " + quoted(dir) + " -q").exitCode == 0);
    const fs::path journal = dir / "small.netj";
    const Ran rails = runCli("export " + quoted(journal) + " --rails " +
                             quoted(dir / "out" / "rails.dxf") + " " + quoted(dir / "rails.csv"));
    CHECK(rails.exitCode == 0);
    CHECK_THAT(rails.output, !Contains("relaxed")); // a journal's rails need no shape
    for (const fs::path& file : {dir / "out" / "rails.dxf", dir / "rails.csv"}) {
        const auto back = netsculpt::importRailsFile(file);
        REQUIRE(back.size() == 1);
        CHECK(back[0].name == "ring");
        CHECK(back[0].curve.closed);
        CHECK(back[0].curve.points.size() == 48);
        CHECK(back[0].curve.points[0] == netsculpt::Vec3{2, 0, 5}); // 2 cos 0, 2 sin 0, 5
    }
    // The whole net as DXF: its bars are left out when its rails are read back.
    const Ran net = runCli("export " + quoted(journal) + " --no-relax " + quoted(dir / "net.dxf"));
    CHECK(net.exitCode == 0);
    const auto back = netsculpt::importRailsFile(dir / "net.dxf");
    REQUIRE(back.size() == 1);
    CHECK(back[0].name == "ring");

    const Ran mixed = runCli("export " + quoted(journal) + " --rails " + quoted(dir / "r.obj") +
                             " --tube-radius 0.01");
    CHECK(mixed.exitCode == 2);
    CHECK_THAT(mixed.output, Contains("--tube-radius excludes --rails"));
    const Ran png = runCli("export " + quoted(journal) + " --rails " + quoted(dir / "r.png"));
    CHECK(png.exitCode == 1);
    CHECK_THAT(png.output, Contains("r.png: rails are exported to .csv, .obj or .dxf, not .png"));
    CHECK_FALSE(fs::exists(dir / "r.obj"));
}

TEST_CASE("Numbers out of range are usage errors that say what is allowed", "[cli]") {
    for (const auto& [bad, message] :
         {std::pair{"relax d.netj --tolerance 0",
                    "--tolerance: must be a number > 0 and at most 0.01, got 0"},
          std::pair{"relax d.netj --tolerance 2",
                    "--tolerance: must be a number > 0 and at most 0.01, got 2"},
          std::pair{"relax d.netj --max-seconds -5", "--max-seconds: must be a number > 0, got -5"},
          std::pair{"run x.lua --max-memory -3", "--max-memory: must be a number >= 0, got -3"},
          std::pair{"export d.netj x.obj --tube-radius -1",
                    "--tube-radius: must be a number >= 0, got -1"},
          std::pair{"relax d.netj --tolerance inf",
                    "--tolerance: must be a number > 0 and at most 0.01, got inf"},
          std::pair{"relax d.netj --max-seconds 1e400",
                    "--max-seconds: must be a number > 0, got 1e400"},
          std::pair{"relax d.netj --max-steps -5",
                    "--max-steps: must be a whole number from -1 to 10^15, got -5"},
          std::pair{"relax d.netj --max-steps 99999999999999999999",
                    "--max-steps: must be a whole number from -1 to 10^15, got 9999999999999"},
          std::pair{"run x.lua --max-instructions 1.5",
                    "--max-instructions: must be a whole number from 0 to 10^15, got 1.5"}}) {
        INFO(bad);
        const Ran r = runCli(bad);
        CHECK(r.exitCode == 2);
        CHECK_THAT(r.output, StartsWith(std::string("netsculpt: error: ") + message));
    }
}

TEST_CASE("run: exit code 0 with outputs and a journal, 1 with a one-line message", "[cli]") {
    const fs::path dir = freshFolder("run");
    const fs::path script = writeScript(dir, "small.lua", kSmallSculpture);
    const Ran ok = runCli("run " + quoted(script) + " --out " + quoted(dir / "out") + " --quiet");
    CHECK(ok.exitCode == 0);
    CHECK(printedHash(ok.output).size() == 16);
    CHECK(fs::is_regular_file(dir / "out" / "small.netj"));

    const fs::path bad = writeScript(
        dir, "bad.lua", "local ns = require 'netsculpt'\nns.new():set_rows{rows = 0}\n");
    const Ran failed = runCli("run " + quoted(bad) + " --out " + quoted(dir / "out"));
    CHECK(failed.exitCode == 1);
    CHECK_THAT(failed.output, StartsWith("netsculpt: error: ") &&
                                  Contains("bad.lua:2: set_rows: argument 'piece' is missing"));

    const Ran missing = runCli("run " + quoted(dir / "none.lua"));
    CHECK(missing.exitCode == 1);
    CHECK_THAT(missing.output, StartsWith("netsculpt: error: there is no script at"));

    const fs::path loop = writeScript(dir, "loop.lua", "while true do end\n");
    const Ran stopped =
        runCli("run " + quoted(loop) + " --out " + quoted(dir / "out") + " --max-instructions 1e6");
    CHECK(stopped.exitCode == 1);
    CHECK_THAT(stopped.output,
               Contains("loop.lua:1: script exceeded its budget of 10^6 instructions"));

    // Stuck inside a library call, out of the instruction budget's reach: the time limit ends it.
    const fs::path stuck = writeScript(
        dir, "stuck.lua", "string.find(string.rep('a', 60), string.rep('a*', 8) .. 'b')\n");
    const auto started = std::chrono::steady_clock::now();
    const Ran late = runCli("run " + quoted(stuck) + " --out " + quoted(dir / "out") +
                            " --max-seconds 0.5");
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    CHECK(late.exitCode == 1);
    CHECK_THAT(late.output, Contains("stuck.lua ran past its time limit of 0.5 s (--max-seconds)"));
    CHECK(took < 20);
    // A limit beyond a century is none (the wait would overflow and end the run at once).
    const Ran unlimited = runCli("run " + quoted(script) + " --out " + quoted(dir / "out") +
                                 " --max-seconds 1e10 --quiet");
    CHECK(unlimited.exitCode == 0);
    CHECK(printedHash(unlimited.output).size() == 16);

    const fs::path hungry =
        writeScript(dir, "hungry.lua", "local t = {} for i = 1, 1e9 do t[i] = i end\n");
    const Ran full =
        runCli("run " + quoted(hungry) + " --out " + quoted(dir / "out") + " --max-memory 16");
    CHECK(full.exitCode == 1);
    CHECK_THAT(full.output, Contains("netsculpt: error: script exceeded 16 MiB of memory"));

    const Ran args =
        runCli("run " + quoted(writeScript(dir, "args.lua", "print(arg[1], arg[2], #arg)")) +
               " --out " + quoted(dir / "out") + " -q -- --no-relax two");
    CHECK(args.exitCode == 0);
    CHECK_THAT(args.output, Contains("--no-relax\ttwo\t2"));
    // Plain arguments before --, dashed ones after it: all of them, in order.
    const Ran mixed = runCli("run " + quoted(dir / "args.lua") + " --out " + quoted(dir / "out") +
                             " -q one -- --quick");
    CHECK(mixed.exitCode == 0);
    CHECK_THAT(mixed.output, Contains("one\t--quick\t2"));
    // -- before the script, as usual, still ends the options; another command's -- is its own.
    const Ran before = runCli("run --out " + quoted(dir / "out") + " -q -- " +
                              quoted(dir / "args.lua") + " x");
    CHECK(before.exitCode == 0);
    CHECK_THAT(before.output, Contains("x\tnil\t1"));
    CHECK(runCli("replay --out run d.netj -- extra").exitCode == 2);
    // A dashed argument without -- is a usage error that says where it goes.
    const Ran dashed = runCli("run " + quoted(dir / "args.lua") + " --quick");
    CHECK(dashed.exitCode == 2);
    CHECK_THAT(dashed.output, Contains("go after --: netsculpt run SCRIPT -- --quick"));

    const Ran backend = runCli(
        "run " +
        quoted(writeScript(
            dir, "backend.lua",
            std::string(kSmallSculpture) +
                "print('backend ' .. doc:relax{backend = 'fast', max_seconds = 0.5}.backend)")) +
        " --out " + quoted(dir / "out") + " -q --backend rk4");
    CHECK(backend.exitCode == 0);
    CHECK_THAT(backend.output, Contains("backend rk4")); // --backend overrides the script's choice

    const Ran unsafe = runCli(
        "run " +
        quoted(writeScript(dir, "unsafe.lua", "assert(io.popen('echo hi'):read('l') == 'hi')")) +
        " --out " + quoted(dir / "out") + " --unsafe");
    CHECK(unsafe.exitCode == 0);
    CHECK_THAT(unsafe.output, Contains("--unsafe: the sandbox is off"));
}

TEST_CASE("run: a rail kilometres long from a file without units gets a warning naming units",
          "[cli]") {
    // A square of 2000 x 2000 in a CSV: 8 km as metres, likely millimetres. With units = "mm"
    // it is 8 m and nothing is said.
    const fs::path dir = freshFolder("units");
    writeScript(dir, "square.csv",
                "x,y,z\n0,0,5000\n2000,0,5000\n2000,2000,5000\n0,2000,5000\n0,0,5000\n");
    const fs::path script = writeScript(
        dir, "import.lua",
        "local doc = require('netsculpt').new()\n"
        "print(doc:import_rails('square.csv')[1]:info().length)\n"
        "print(doc:import_rails('square.csv', {units = 'mm'})[1]:info().length)\n");
    const Ran ran = runCli("run " + quoted(script) + " --out " + quoted(dir / "out"));
    CHECK(ran.exitCode == 0);
    CHECK_THAT(ran.output, Contains("8000.0\n8.0\n"));
    CHECK_THAT(ran.output, Contains("rail 'square' of square.csv is 8000 m long, read as metres") &&
                               Contains("{units = \"mm\"}"));
    const std::size_t first = ran.output.find("warning");
    CHECK(ran.output.find("warning", first + 1) == std::string::npos); // the mm import is quiet
}

TEST_CASE("run: without --out a script reads and writes in out/<script name>, not where the "
          "artist stands", "[cli]") {
    const fs::path home = freshFolder("run-home");
    std::ofstream(home / "secret.txt") << "private\n";
    fs::create_directories(home / "shared");
    const fs::path script = writeScript(home / "shared", "peek.lua", R"(
local ns = require "netsculpt"
local f = io.open(ns.output_dir() .. "/secret.txt")
print("read: " .. tostring(f and f:read("l")))
local doc = ns.new()
local ring = doc:add_rail{points = ns.circle{radius = 2, points = 24}, closed = true}
doc:attach_to_rail{rail = ring, columns = 12, rows = 3, bar = 0.8}
doc:export("secret.txt.csv")
)");
    const Ran ran = runCli("run " + quoted(script), "cd " + quoted(home) + " &&");
    INFO(ran.output);
    CHECK(ran.exitCode == 0);
    CHECK_THAT(ran.output, Contains("read: nil") && Contains("outputs in out/peek"));
    CHECK(fs::is_regular_file(home / "out" / "peek" / "secret.txt.csv"));
    CHECK(fs::is_regular_file(home / "out" / "peek" / "peek.netj"));
    CHECK_FALSE(fs::exists(home / "secret.txt.csv"));
}

TEST_CASE("run: a run into an output folder another run holds is refused and writes nothing",
          "[cli]") {
    // Two runs of one script into one folder used to append to one session journal: entries of
    // both interleaved, and the journal then failed to open ("sequence number 1, expected 2").
    const fs::path dir = freshFolder("run-lock");
    const fs::path script = writeScript(dir, "small.lua", kSmallSculpture);
    const fs::path out = dir / "shared out";
    fs::create_directories(out);
    std::ofstream(out / "small.netj") << "netsculpt-journal 1\n";
    const int held = ::open((out / ".netsculpt-run.lock").c_str(), O_RDWR | O_CREAT, 0644);
    REQUIRE(held >= 0);
    REQUIRE(::flock(held, LOCK_EX | LOCK_NB) == 0); // as the other run holds it

    const Ran refused = runCli("run " + quoted(script) + " --out " + quoted(out));
    CHECK(refused.exitCode == 1);
    CHECK_THAT(refused.output, StartsWith("netsculpt: error: the output folder " + out.string() +
                                          " is in use by another netsculpt run") &&
                                   Contains("give this run another --out"));
    CHECK(printedHash(refused.output).empty()); // the script did not run
    CHECK(readFile(out / "small.netj") == "netsculpt-journal 1\n");

    ::close(held); // the other run ends: the folder is free again
    const Ran ran = runCli("run " + quoted(script) + " --out " + quoted(out) + " -q");
    CHECK(ran.exitCode == 0);
    CHECK(printedHash(ran.output).size() == 16);
    CHECK(readFile(out / "small.netj").size() > 100);
}

TEST_CASE("run: files an earlier run left in the output folder are named, not taken as this "
          "run's",
          "[cli]") {
    // A script that stops half way leaves its new journal beside the exports of the run before.
    const fs::path dir = freshFolder("run-leftovers");
    const fs::path out = dir / "out";
    const fs::path script = writeScript(dir, "half.lua", R"(
local ns = require "netsculpt"
local doc = ns.new()
local ring = doc:add_rail{points = ns.circle{radius = 2, points = 24}, closed = true}
doc:attach_to_rail{rail = ring, columns = 12, rows = 3, bar = 0.8}
doc:export("new.csv")
if arg[1] == "stop" then error("stopped half way") end
)");
    REQUIRE(runCli("run " + quoted(script) + " --out " + quoted(out)).exitCode == 0);
    fs::create_directories(out / "views");
    std::ofstream(out / "report.md") << "# an earlier report\n";
    std::ofstream(out / "views" / "top.png") << "png";

    const Ran stopped = runCli("run " + quoted(script) + " --out " + quoted(out) + " stop");
    CHECK(stopped.exitCode == 1);
    CHECK_THAT(stopped.output, Contains("half.lua:7: stopped half way") &&
                                   Contains("netsculpt: note: 2 files in " + out.string() +
                                            " are from before this run, which did not write "
                                            "them: report.md, views/top.png"));
    CHECK(stopped.output.find("new.csv") == std::string::npos); // rewritten by this run
    CHECK(stopped.output.find("half.netj") == std::string::npos);

    const Ran whole = runCli("run " + quoted(script) + " --out " + quoted(out));
    CHECK(whole.exitCode == 0);
    CHECK_THAT(whole.output, Contains("2 files in " + out.string() + " are from before"));
    fs::remove(out / "report.md");
    fs::remove(out / "views" / "top.png");
    const Ran clean = runCli("run " + quoted(script) + " --out " + quoted(out));
    CHECK(clean.exitCode == 0);
    CHECK(clean.output.find("note:") == std::string::npos);
}

TEST_CASE("replay, to-lua, relax, export and report on a journal", "[cli]") {
    const fs::path dir = freshFolder("journal");
    const fs::path script = writeScript(dir, "small.lua", kSmallSculpture);
    const Ran ran = runCli("run " + quoted(script) + " --out " + quoted(dir) + " -q");
    REQUIRE(ran.exitCode == 0);
    const std::string hash = printedHash(ran.output);
    const fs::path journal = dir / "small.netj";
    const auto journalBytes = fs::file_size(journal);

    const Ran replay = runCli("replay " + quoted(journal) + " --out " + quoted(dir / "replayed"));
    CHECK(replay.exitCode == 0);
    CHECK_THAT(replay.output, Contains("1 rail, 2 pieces") && Contains("hash " + hash));
    CHECK(fs::is_regular_file(dir / "replayed" / "small.netj"));
    CHECK(fs::file_size(journal) == journalBytes); // read, never written

    const Ran lua = runCli("to-lua " + quoted(journal));
    CHECK(lua.exitCode == 0);
    std::string generated = lua.output;
    const auto end = generated.rfind("return doc");
    REQUIRE(end != std::string::npos);
    generated.insert(end, "print('hash ' .. doc:hash())\n");
    const fs::path again = writeScript(dir, "again.lua", generated);
    const Ran rerun =
        runCli("run " + quoted(again) + " --out " + quoted(dir / "again") + " -q --no-journal");
    CHECK(rerun.exitCode == 0);
    CHECK(printedHash(rerun.output) == hash); // the generated script builds the same sculpture

    const Ran relax = runCli("relax " + quoted(journal) +
                             " --tolerance 1e-2 --max-seconds 20 --out " + quoted(dir / "relaxed"));
    CHECK(relax.exitCode == 0);
    CHECK_THAT(relax.output, Contains("converged"));
    // With -v the result line is still said once (it is the command's output).
    const Ran verbose = runCli("-v relax " + quoted(journal) +
                               " --tolerance 1e-2 --max-seconds 20 --out " + quoted(dir / "v"));
    const std::string::size_type first = verbose.output.find("converged after");
    CHECK(first != std::string::npos);
    CHECK(verbose.output.find("converged after", first + 1) == std::string::npos);
    const fs::path snapshot = dir / "relaxed" / "small.nets";
    CHECK(fs::is_regular_file(snapshot));
    // Stopped short of the tolerance: exit 3, the shape written all the same.
    const Ran capped = runCli("relax " + quoted(journal) + " --max-steps 1 --out " +
                              quoted(dir / "capped"));
    CHECK(capped.exitCode == 3);
    CHECK_THAT(capped.output, Contains("stopped (step limit) after 1 steps"));
    CHECK(fs::is_regular_file(dir / "capped" / "small.nets"));
    // Its input is only read: an output that would be the input itself is refused, unwritten.
    const std::string snapshotBytes = readFile(snapshot);
    const Ran over = runCli("relax " + quoted(snapshot) + " --max-steps 1 --out " +
                            quoted(dir / "relaxed" / "."));
    CHECK(over.exitCode == 1);
    CHECK_THAT(over.output, Contains("over its input") && Contains("give --out another folder"));
    CHECK(readFile(snapshot) == snapshotBytes);
    const Ran replayOver = runCli("replay " + quoted(journal) + " --out " + quoted(dir));
    CHECK(replayOver.exitCode == 1);
    CHECK(fs::file_size(journal) == journalBytes);

    const Ran exported =
        runCli("export " + quoted(snapshot) + " " + quoted(dir / "x" / "knots.csv") + " " +
               quoted(dir / "x" / "view.svg") + " --view top");
    CHECK(exported.exitCode == 0);
    CHECK(fs::is_regular_file(dir / "x" / "knots.csv"));
    CHECK(fs::is_regular_file(dir / "x" / "view.svg"));
    CHECK(runCli("export " + quoted(snapshot) + " " + quoted(dir / "x" / "knots.docx")).exitCode ==
          1);
    // A journal holds no shape: export relaxes it first, to the shape `relax` gives ...
    const Ran exportedJournal = runCli("export " + quoted(journal) + " " + quoted(dir / "j.csv"));
    CHECK(exportedJournal.exitCode == 0);
    CHECK_THAT(exportedJournal.output, Contains("relaxed it for export: converged"));
    const Ran badName = runCli("export " + quoted(journal) + " " + quoted(dir / "k.docx"));
    CHECK(badName.exitCode == 1); // refused before relaxing, which can take a while
    CHECK_THAT(badName.output, Contains("cannot export to .docx") && !Contains("relaxed it"));
    // So is a file where a folder of the path should be (it was refused after relaxing).
    std::ofstream(dir / "a-file") << "x";
    const Ran badFolder = runCli("export " + quoted(journal) + " " + quoted(dir / "j2.csv") + " " +
                                 quoted(dir / "a-file" / "k.csv"));
    CHECK(badFolder.exitCode == 1);
    CHECK_THAT(badFolder.output, Contains("cannot create the output folder") &&
                                     Contains("is a file, not a folder") &&
                                     !Contains("relaxed it"));
    CHECK_FALSE(fs::exists(dir / "j2.csv"));
    REQUIRE(runCli("relax " + quoted(journal) + " -q --out " + quoted(dir / "r")).exitCode == 0);
    REQUIRE(runCli("export " + quoted(dir / "r" / "small.nets") + " -q " + quoted(dir / "r.csv"))
                .exitCode == 0);
    const auto text = [](const fs::path& file) {
        std::ifstream in(file);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    CHECK(text(dir / "j.csv") == text(dir / "r.csv"));
    // ... or, asked not to, writes the start's shape with a warning.
    const Ran startShape =
        runCli("export " + quoted(journal) + " --no-relax " + quoted(dir / "start.csv"));
    CHECK(startShape.exitCode == 0);
    CHECK_THAT(startShape.output, Contains("warning: the shape is not relaxed"));
    CHECK(text(dir / "start.csv") != text(dir / "r.csv"));

    const Ran markdown = runCli("report " + quoted(snapshot));
    CHECK(markdown.exitCode == 0);
    CHECK_THAT(markdown.output, Contains("#"));
    const Ran json = runCli("report " + quoted(snapshot) + " --json");
    CHECK(json.exitCode == 0);
    CHECK_THAT(json.output, StartsWith("{") && Contains("\"total_mass\""));
    const Ran csv = runCli("report " + quoted(snapshot) + " --csv");
    CHECK(csv.exitCode == 0);
    const Ran attachments = runCli("report " + quoted(snapshot) + " --csv attachments");
    CHECK(attachments.exitCode == 0);
    CHECK(csv.output != attachments.output);

    // A journal holds no shape: the report relaxes it first, so its loads are the hanging net's.
    const Ran fromJournal = runCli("report " + quoted(journal));
    CHECK(fromJournal.exitCode == 0);
    CHECK_THAT(fromJournal.output, Contains("holds no relaxed shape; relaxed it for the report: "
                                            "converged") &&
                                       Contains("Shape: **relaxed**"));
    const Ran quietJson = runCli("report " + quoted(journal) + " --json -q");
    REQUIRE(quietJson.exitCode == 0);
    const nlohmann::json relaxedReport = nlohmann::json::parse(quietJson.output);
    CHECK(relaxedReport["relaxed"] == true);
    CHECK(relaxedReport["force_balance"]["within_tolerance"] == true);
    const Ran asItIs = runCli("report " + quoted(journal) + " --no-relax --csv attachments");
    CHECK(asItIs.exitCode == 0);
    CHECK_THAT(asItIs.output, Contains("warning: the shape is not relaxed"));
    CHECK(fs::file_size(journal) == journalBytes);

    const Ran broken = runCli("report " + quoted(dir / "none.netj"));
    CHECK(broken.exitCode == 1);
    CHECK_THAT(broken.output, StartsWith("netsculpt: error: "));
}

TEST_CASE("a folder, a device, an empty or cut-off file as a design or script is an error that "
          "says which", "[cli]") {
    const fs::path dir = freshFolder("not-a-design");
    fs::create_directories(dir / "folder.netj");
    std::ofstream(dir / "empty.nets").flush();
    std::ofstream(dir / "torn.netj") << "netscul";
    for (const auto& [arguments, message] :
         {std::pair{"report " + quoted(dir / "folder.netj"), "it is a folder; expected a journal"},
          std::pair{std::string("report /dev/null"), "it is not a regular file"},
          std::pair{"relax " + quoted(dir / "empty.nets") + " --out " + quoted(dir / "out"),
                    "empty.nets holds no sculpture: it is empty"},
          std::pair{"export " + quoted(dir / "torn.netj") + " " + quoted(dir / "k.csv"),
                    "torn.netj holds no sculpture: it is cut off within its header line"},
          std::pair{"run " + quoted(dir / "folder.netj"),
                    "folder.netj is a folder; expected a Lua"}}) {
        INFO(arguments);
        const Ran r = runCli(arguments);
        CHECK(r.exitCode == 1);
        CHECK_THAT(r.output, StartsWith("netsculpt: error: ") && Contains(message));
    }
    CHECK_FALSE(fs::exists(dir / "out" / "empty.nets"));
    CHECK_FALSE(fs::exists(dir / "k.csv"));
}

TEST_CASE("With --quiet, a torn last entry dropped is still warned of", "[cli]") {
    const fs::path dir = freshFolder("cli-quiet-torn");
    const fs::path script = writeScript(dir, "small.lua", kSmallSculpture);
    REQUIRE(runCli("run " + quoted(script) + " --out " + quoted(dir) + " -q").exitCode == 0);
    std::string text = readFile(dir / "small.netj");
    REQUIRE(text.size() > 20);
    text.resize(text.size() - 10); // the last entry cut off in the middle, as by a crash
    std::ofstream(dir / "torn.netj", std::ios::binary) << text;
    for (const char* name : {"replay", "to-lua", "report", "relax", "export"}) {
        const std::string command = name;
        std::string arguments = command + " -q " + quoted(dir / "torn.netj");
        if (command == "relax")
            arguments += " --out " + quoted(dir / "relaxed");
        if (command == "export")
            arguments += " " + quoted(dir / "k.csv");
        INFO(arguments);
        const Ran ran = runCli(arguments);
        CHECK(ran.exitCode == 0);
        CHECK_THAT(ran.output,
                   Contains("netsculpt: warning: ") && Contains("dropped a torn last entry"));
    }
}

TEST_CASE("relax warns when the relaxed net stretches bars beyond what rope can do", "[cli]") {
    // Three rows of 0.25 m bars tied between rails 2.8 m apart: only a 50 % stretch reaches.
    const fs::path dir = freshFolder("cli-overstretch");
    const fs::path script = writeScript(dir, "over.lua", R"(local ns = require "netsculpt"
local doc = ns.new()
local upper = doc:add_rail{points = {{0, 0, 5}, {4, 0, 5}}}
local lower = doc:add_rail{points = {{0, 2, 3}, {4, 2, 3}}}
local p = doc:attach_to_rail{rail = upper, columns = 11, rows = 3, bar = 0.25}
doc:connect_to_rail{piece = p, rail = lower}
)");
    REQUIRE(runCli("run " + quoted(script) + " --out " + quoted(dir) + " -q").exitCode == 0);
    const Ran relax = runCli("relax " + quoted(dir / "over.netj") + " --out " + quoted(dir));
    INFO(relax.output);
    CHECK(relax.exitCode == 0); // it is the model's equilibrium, so it converges ...
    CHECK_THAT(relax.output, Contains("converged after"));
    // ... but no rope hangs so: each of its 2 x (2 x 11 - 1) bars is stretched far beyond 2 %.
    CHECK_THAT(relax.output,
               Contains("netsculpt: warning: 42 bars are stretched by more than 2 %"));

    // The same design relaxed by its script: `run` warns too, and relax{} returns the count.
    const fs::path relaxing = writeScript(
        dir, "over-relaxed.lua",
        R"(local ns = require "netsculpt"
local doc = ns.new()
local upper = doc:add_rail{points = {{0, 0, 5}, {4, 0, 5}}}
local lower = doc:add_rail{points = {{0, 2, 3}, {4, 2, 3}}}
local p = doc:attach_to_rail{rail = upper, columns = 11, rows = 3, bar = 0.25}
doc:connect_to_rail{piece = p, rail = lower}
print("overstretched", doc:relax{}.overstretched_bars)
)");
    const Ran ran = runCli("run " + quoted(relaxing) + " --out " + quoted(dir));
    INFO(ran.output);
    CHECK(ran.exitCode == 0);
    CHECK_THAT(ran.output, Contains("overstretched\t42") &&
                               Contains("netsculpt: warning: after doc:relax, 42 bars are "
                                        "stretched by more than 2 %"));
}

TEST_CASE("report: each piece's breaking load, utilisation and safety factor in Markdown, JSON "
          "and CSV, and the pieces without one named",
          "[cli]") {
    // kSmallSculpture: piece 1 (the tube) has a breaking load of 40 N, piece 2 (below) none.
    const fs::path dir = freshFolder("cli-strength");
    const fs::path script = writeScript(dir, "small.lua", kSmallSculpture);
    REQUIRE(runCli("run " + quoted(script) + " --out " + quoted(dir) + " -q").exitCode == 0);
    REQUIRE(
        runCli("relax " + quoted(dir / "small.netj") + " -q --out " + quoted(dir / "r")).exitCode ==
        0);
    const fs::path snapshot = dir / "r" / "small.nets";

    const Ran json = runCli("report " + quoted(snapshot) + " --json");
    REQUIRE(json.exitCode == 0);
    const nlohmann::json r = nlohmann::json::parse(json.output);
    const nlohmann::json& tube = r["pieces"][0];
    const nlohmann::json& skirt = r["pieces"][1];
    const double tension = tube["max_tension"].get<double>();
    CHECK(tension > 0);
    CHECK(tube["breaking_load"].get<double>() == 40);
    CHECK(tube["utilisation"].get<double>() == tension / 40);
    CHECK(tube["safety_factor"].get<double>() == 40 / tension);
    CHECK(tube["max_tension_at"]["piece"] == 1);
    CHECK(skirt["breaking_load"].is_null());
    CHECK(skirt["utilisation"].is_null());
    CHECK(skirt["safety_factor"].is_null());
    CHECK(r["min_safety_factor"] == tube["safety_factor"]);
    CHECK(r["min_safety_factor_at"] == tube["max_tension_at"]);
    CHECK(r["pieces_without_breaking_load"] == nlohmann::json::array({2}));

    const Ran markdown = runCli("report " + quoted(snapshot));
    REQUIRE(markdown.exitCode == 0);
    char factor[32];
    std::snprintf(factor, sizeof factor, "%.6g", 40 / tension);
    CHECK_THAT(markdown.output,
               Contains("| least safety factor | " + std::string(factor) + " (piece 1, row ") &&
                   Contains("| pieces without a breaking load | 2 (piece 2): "
                            "not checked |") &&
                   Contains("\n## Strength\n") && Contains("\n| 2 | piece 2 | none | "));

    // The pieces table's strength columns, each read back to the JSON's number, then its seams
    // (none) and load case.
    const Ran csv = runCli("report " + quoted(snapshot) + " --csv");
    REQUIRE(csv.exitCode == 0);
    std::istringstream lines(csv.output);
    std::string header, first, second;
    std::getline(lines, header);
    std::getline(lines, first);
    std::getline(lines, second);
    CHECK_THAT(header, Contains(",knots_tied,breaking_load,utilisation,safety_factor,"
                                "max_tension_at,seams,load_case") &&
                           !Contains("load_case,"));
    const auto lastFields = [](const std::string& line) {
        std::vector<std::string> fields;
        std::string::size_type end = line.size();
        for (int i = 0; i < 6; ++i) {
            const std::string::size_type comma = line.rfind(',', end - 1);
            fields.insert(fields.begin(), line.substr(comma + 1, end - comma - 1));
            end = comma;
        }
        CHECK(fields.back() == "weight alone");
        CHECK(fields[4].empty()); // no seam
        fields.resize(4);
        return fields; // breaking_load, utilisation, safety_factor, max_tension_at
    };
    const std::vector<std::string> tubeFields = lastFields(first);
    CHECK(std::stod(tubeFields[0]) == 40);
    CHECK(std::stod(tubeFields[1]) == tube["utilisation"].get<double>());
    CHECK(std::stod(tubeFields[2]) == tube["safety_factor"].get<double>());
    CHECK_THAT(tubeFields[3], StartsWith("row "));
    const std::vector<std::string> skirtFields = lastFields(second);
    CHECK(skirtFields[0].empty());
    CHECK(skirtFields[1].empty());
    CHECK(skirtFields[2].empty());
    CHECK_THAT(skirtFields[3], StartsWith("row "));
}
