// netsculpt-studio's command line (docs/studio.md "Command line"), parsed without a window.

#include "StudioOptions.h"

#include "model/Error.h"

#include <catch2/catch.hpp>

#include <sstream>

using Catch::Matchers::Contains;
using netsculpt::UserError;
using netsculpt::studio::parseStudioOptions;
using netsculpt::studio::readCommandLine;

TEST_CASE("studio options: --help asks for the usage, not an error", "[studio]") {
    // It was thrown as the error of a bad argument: the usage on stderr, exit status 2.
    CHECK(parseStudioOptions({"--help"}).help);
    CHECK(parseStudioOptions({"-h"}).help);
    CHECK(parseStudioOptions({"--demo", "--help"}).help);
    CHECK_FALSE(parseStudioOptions({"--demo"}).help);
}

TEST_CASE("studio options: --settle takes seconds with fractions", "[studio]") {
    CHECK(parseStudioOptions({"--settle", "0.5"}).settleSeconds == 0.5);
    CHECK(parseStudioOptions({"--settle", "60"}).settleSeconds == 60);
    CHECK_THROWS_WITH(parseStudioOptions({"--settle", "-1"}),
                      Contains("--settle expects a number of seconds from 0 to 3600, got \"-1\""));
    CHECK_THROWS_WITH(parseStudioOptions({"--settle", "soon"}), Contains("got \"soon\""));
    CHECK_THROWS_AS(parseStudioOptions({"--settle", "1e9"}), UserError);
}

TEST_CASE("studio command line: a bad argument is a usage error worded as netsculpt's",
          "[studio]") {
    // It printed the bare message ("--size expects WxH, ..."), some with the whole usage after it,
    // without the program's name: netsculpt says "netsculpt: error: ..." and how to get help.
    for (const auto& [arguments, message] :
         {std::pair{std::vector<std::string>{"--size", "100"},
                    "--size expects WxH, e.g. 1280x800, got \"100\""},
          std::pair{std::vector<std::string>{"--demo", "--bogus"}, "unknown argument \"--bogus\""},
          std::pair{std::vector<std::string>{"--open"}, "--open needs a value"},
          std::pair{std::vector<std::string>{"--demo", "--open", "a.netj"},
                    "give at most one of --script, --open and --demo"}}) {
        INFO(arguments.back());
        std::ostringstream out, err;
        const auto commandLine = readCommandLine(arguments, out, err);
        CHECK(commandLine.exitStatus == 2);
        CHECK(err.str() == std::string("netsculpt-studio: error: ") + message +
                               "\nRun with --help for more information.\n");
        CHECK(out.str().empty());
    }
}

TEST_CASE("studio command line: --help prints the usage and exits 0, good options start",
          "[studio]") {
    std::ostringstream out, err;
    const auto help = readCommandLine({"--help"}, out, err);
    CHECK(help.exitStatus == 0);
    CHECK(out.str() == netsculpt::studio::studioUsage());
    CHECK(err.str().empty());
    const auto start = readCommandLine({"--demo", "--size", "640x480"}, out, err);
    CHECK_FALSE(start.exitStatus.has_value());
    CHECK(start.options.demo);
    CHECK(start.options.width == 640);
    CHECK(err.str().empty());
}
