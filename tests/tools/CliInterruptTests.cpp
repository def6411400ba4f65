// Ctrl-C (SIGINT) during the netsculpt program's long work (tools/cli/Interrupt.h): relax saves
// the shape reached, a script stops with its journal kept, report writes nothing; each exits
// with 130. The signal is sent once the program catches it (its SigCgt mask in /proc), so the
// tests do not depend on how long anything takes.

#include "CliSupport.h"

#include <catch2/catch.hpp>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <poll.h>
#include <sstream>
#include <thread>
#include <unistd.h>
#include <vector>

using namespace netsculpt::test;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
namespace fs = std::filesystem;

namespace {

/// Starts `netsculpt <arguments>` with stdout and stderr into `output` (a file, or a terminal's
/// side that the program writes to).
pid_t spawnCli(const std::vector<std::string>& arguments, const fs::path& output) {
    const pid_t pid = fork();
    if (pid != 0)
        return pid;
    const int out = open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOCTTY, 0644);
    const int none = open("/dev/null", O_RDONLY);
    dup2(none, STDIN_FILENO);
    dup2(out, STDOUT_FILENO);
    dup2(out, STDERR_FILENO);
    signal(SIGINT, SIG_DFL); // as from a terminal: not ignored
    std::vector<std::string> words{cliPath().string()};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& w : words)
        argv.push_back(w.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
}

/// Whether process `pid` runs netsculpt (the fork has become it) and catches SIGINT now (bit
/// SIGINT - 1 of SigCgt in /proc/<pid>/status).
bool catchesInterrupt(pid_t pid) {
    const std::string proc = "/proc/" + std::to_string(pid);
    std::error_code error;
    if (!fs::equivalent(fs::read_symlink(proc + "/exe", error), cliPath(), error))
        return false;
    std::ifstream status(proc + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("SigCgt:", 0) == 0)
            return (std::stoull(line.substr(7), nullptr, 16) >> (SIGINT - 1) & 1) != 0;
    return false;
}

/// Presses Ctrl-C once the program catches it (within a minute), then waits for its end: its
/// exit code, or -1 when a signal ended it or it never caught the signal.
int interruptWhenCaught(pid_t pid) {
    bool caught = false;
    for (int i = 0; i < 30000 && !caught; ++i) {
        caught = catchesInterrupt(pid);
        if (!caught)
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    kill(pid, caught ? SIGINT : SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    return caught && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// A tube of 24 x 20 knots on a ring, then `rest`.
std::string tubeScript(const std::string& rest) {
    return R"(local ns = require "netsculpt"
local doc = ns.new()
local ring = doc:add_rail{points = ns.circle{radius = 2, points = 48, centre = {0, 0, 5}},
                          closed = true}
local p = doc:attach_to_rail{rail = ring, columns = 24, rows = 20, bar = 0.4}
)" + rest;
}

} // namespace

TEST_CASE("Ctrl-C stops relax, which saves the shape reached and exits 130", "[cli]") {
    const fs::path dir = freshFolder("cli-interrupt-relax");
    const fs::path script = writeScript(dir, "tube.lua", tubeScript(""));
    REQUIRE(runCli("run " + quoted(script) + " --out " + quoted(dir)).exitCode == 0);
    // RK4 at the rope's stiffness takes far longer than a minute on this net.
    const pid_t pid = spawnCli({"relax", (dir / "tube.netj").string(), "--backend", "rk4",
                                "--max-seconds", "60", "--out", (dir / "relaxed").string()},
                               dir / "relax.txt");
    CHECK(interruptWhenCaught(pid) == 130);
    const std::string output = readFile(dir / "relax.txt");
    CHECK_THAT(output, Contains("netsculpt: Ctrl-C: stopping (Ctrl-C again to quit at once)"));
    CHECK_THAT(output, Contains("tube.netj: stopped (Ctrl-C) after"));
    // The shape reached is a snapshot like any other: it opens, and is not called relaxed.
    const Ran report =
        runCli("report " + quoted(dir / "relaxed" / "tube.nets") + " --json --no-relax");
    CHECK(report.exitCode == 0);
    CHECK_THAT(report.output, Contains("the shape is not relaxed"));
}

TEST_CASE("Ctrl-C stops a script between instructions, and its journal keeps what it ran",
          "[cli]") {
    const fs::path dir = freshFolder("cli-interrupt-script");
    const fs::path script = writeScript(dir, "loop.lua", tubeScript("while true do end\n"));
    const pid_t pid = spawnCli({"run", script.string(), "--out", dir.string()}, dir / "run.txt");
    CHECK(interruptWhenCaught(pid) == 130);
    const std::string output = readFile(dir / "run.txt");
    CHECK_THAT(output, Contains("loop.lua:6: script interrupted (Ctrl-C)"));
    CHECK_THAT(output, Contains("loop.netj (the commands run before Ctrl-C)"));
    const Ran replay = runCli("replay " + quoted(dir / "loop.netj"));
    CHECK(replay.exitCode == 0);
    CHECK_THAT(replay.output, Contains("1 rail, 1 piece, 480 knots"));
}

TEST_CASE("With --quiet, Ctrl-C is not acknowledged, only its error said", "[cli]") {
    const fs::path dir = freshFolder("cli-interrupt-quiet");
    const fs::path script = writeScript(dir, "loop.lua", tubeScript("while true do end\n"));
    const pid_t pid =
        spawnCli({"-q", "run", script.string(), "--out", dir.string()}, dir / "run.txt");
    CHECK(interruptWhenCaught(pid) == 130);
    const std::string output = readFile(dir / "run.txt");
    CHECK_THAT(output, Contains("loop.lua:6: script interrupted (Ctrl-C)"));
    CHECK_THAT(output, !Contains("Ctrl-C again"));
}

TEST_CASE("Ctrl-C's acknowledgement starts with an empty line on a terminal only", "[cli]") {
    // It began with "\n" (ending a terminal's progress line) in a log file too.
    const fs::path dir = freshFolder("cli-interrupt-acknowledge");
    const fs::path script = writeScript(dir, "loop.lua", tubeScript("while true do end\n"));
    const pid_t toFile = spawnCli({"run", script.string(), "--out", dir.string()}, dir / "run.txt");
    CHECK(interruptWhenCaught(toFile) == 130);
    CHECK_THAT(readFile(dir / "run.txt"),
               StartsWith("netsculpt: Ctrl-C: stopping (Ctrl-C again to quit at once)\n"));

    // On a (pseudo-)terminal, whose output side writes "\r\n" for "\n". What the program wrote
    // is a few lines, within what the terminal holds until it is read.
    const int terminal = posix_openpt(O_RDWR | O_NOCTTY);
    REQUIRE(terminal >= 0);
    REQUIRE(grantpt(terminal) == 0);
    REQUIRE(unlockpt(terminal) == 0);
    const pid_t toTerminal =
        spawnCli({"run", script.string(), "--out", dir.string()}, ptsname(terminal));
    CHECK(interruptWhenCaught(toTerminal) == 130);
    std::string output;
    std::array<char, 256> buffer{};
    pollfd ready{terminal, POLLIN, 0};
    while (poll(&ready, 1, 1000) > 0) { // read fails (EIO) once all is read: the program is gone
        const ssize_t n = read(terminal, buffer.data(), buffer.size());
        if (n <= 0)
            break;
        output.append(buffer.data(), static_cast<std::size_t>(n));
    }
    close(terminal);
    CHECK_THAT(output, StartsWith("\r\nnetsculpt: Ctrl-C: stopping (Ctrl-C again to quit at once)"
                                  "\r\n"));
}

TEST_CASE("Ctrl-C stops a script's relax, and pcall does not catch it", "[cli]") {
    const fs::path dir = freshFolder("cli-interrupt-script-relax");
    const fs::path script =
        writeScript(dir, "relaxing.lua",
                    tubeScript("print(pcall(doc.relax, doc, {backend = 'rk4', max_seconds = 60}))\n"
                               "print('went on')\n"));
    const pid_t pid = spawnCli({"run", script.string(), "--out", dir.string()}, dir / "run.txt");
    CHECK(interruptWhenCaught(pid) == 130);
    const std::string output = readFile(dir / "run.txt");
    CHECK_THAT(output, Contains("netsculpt: error: relax: script interrupted (Ctrl-C)"));
    CHECK_THAT(output, !Contains("went on"));
}

TEST_CASE("Ctrl-C during the relaxation report runs first writes no report", "[cli]") {
    // A sheet hanging slack between two rails: thousands of knots, many Newton iterations.
    const fs::path dir = freshFolder("cli-interrupt-report");
    const fs::path script = writeScript(dir, "sheet.lua", R"(local ns = require "netsculpt"
local doc = ns.new()
local upper = doc:add_rail{points = {{0, 0, 10}, {10, 0, 10}}}
local lower = doc:add_rail{points = {{0, 3, 9}, {10, 3, 9}}}
local p = doc:attach_to_rail{rail = upper, columns = 100, rows = 60, bar = 0.1}
doc:connect_to_rail{piece = p, rail = lower}
)");
    REQUIRE(runCli("run " + quoted(script) + " --out " + quoted(dir)).exitCode == 0);
    const pid_t pid = spawnCli({"report", (dir / "sheet.netj").string()}, dir / "report.txt");
    CHECK(interruptWhenCaught(pid) == 130);
    const std::string output = readFile(dir / "report.txt");
    CHECK_THAT(output, Contains("netsculpt: interrupted: the relaxation for the report stopped "
                                "after"));
    CHECK_THAT(output, Contains("steps; nothing was written"));
    CHECK_THAT(output, !Contains("# ")); // no report's heading
}
