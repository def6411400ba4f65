// The sandbox of scripts (scripting/Sandbox.h): what is refused, where a script may read and
// write, and that --unsafe lifts it.

#include "ScriptTestSupport.h"

#include <catch2/catch.hpp>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

TEST_CASE("Dangerous functions refuse with a clear error", "[sandbox]") {
    const ScriptFolders f("refused");
    const char* const calls[] = {"os.execute('true')",
                                 "io.popen('ls')",
                                 "os.exit(3)",
                                 "os.remove('x')",
                                 "os.rename('a', 'b')",
                                 "os.tmpname()",
                                 "os.setlocale('de_DE')",
                                 "io.tmpfile()",
                                 "package.loadlib('x', 'y')",
                                 "package.searchpath('x', '')",
                                 "debug.sethook()",
                                 "debug.getregistry()",
                                 "debug.getupvalue(print, 1)",
                                 "debug.setuservalue(io.stdout, 1)"};
    for (const char* call : calls) {
        INFO(call);
        const lua::ScriptResult r = f.run(call);
        CHECK_FALSE(r.ok);
        const std::string name = std::string(call).substr(0, std::string(call).find('('));
        CHECK_THAT(r.error, Contains("test.lua:1: " + name + ": not allowed in a script") &&
                                Contains("--unsafe"));
    }
    SECTION("what stays works") {
        const auto r = f.run("assert(debug.traceback('x'):find('x')); assert(os.time() > 0);"
                             "assert(os.getenv('PATH')); assert(load('return 2')() == 2)");
        CHECK(r.error == "");
    }
}

TEST_CASE("A script writes only through doc:save/export into the output folder", "[sandbox]") {
    const ScriptFolders f("writes");
    fs::create_directories(f.root / "elsewhere");
    fs::create_symlink(f.root / "elsewhere", f.out / "link");
    const std::string prelude = "local ns = require 'netsculpt'; local doc = ns.new()\n";
    struct Case {
        std::string code, message;
        fs::path mustNotExist;
    };
    const Case cases[] = {
        {"io.open('w.txt', 'w')", "io.open: writing files is not allowed in a script (mode \"w\")",
         f.scripts / "w.txt"},
        {"io.open('a.txt', 'a+')", "io.open: writing files is not allowed", f.scripts / "a.txt"},
        {"io.output('o.txt')", "io.output: writing files is not allowed", f.scripts / "o.txt"},
        {"doc:save('../escape.netj')", "save: \"../escape.netj\" is outside the output folder",
         f.root / "escape.netj"},
        {"doc:save('sub/../../escape2.netj')", "is outside the output folder",
         f.root / "escape2.netj"},
        {"doc:save('" + (f.root / "abs.netj").string() + "')", "is an absolute path",
         f.root / "abs.netj"},
        {"doc:export('link/knots.csv')", "export: \"link/knots.csv\" is outside the output folder",
         f.root / "elsewhere" / "knots.csv"},
        {"doc:write_report('../report.md')", "write_report: \"../report.md\" is outside",
         f.root / "report.md"},
        {"doc:save('design.netj\\0x')",
         "save: the file name \"design.netj\\0x\" holds a NUL character (byte 12)",
         f.out / "design.netj"},
        {"doc:export('knots.csv\\0.png')", "export: the file name \"knots.csv\\0.png\" holds a NUL",
         f.out / "knots.csv"},
    };
    for (const Case& c : cases) {
        INFO(c.code);
        const lua::ScriptResult r = f.run(prelude + c.code);
        CHECK_FALSE(r.ok);
        CHECK_THAT(r.error, Contains("test.lua:2: ") && Contains(c.message));
        CHECK_FALSE(fs::exists(c.mustNotExist));
    }
    SECTION("relative paths land in the output folder, with their folders") {
        const auto r = f.run(prelude + "doc:save('a/b/design.netj'); doc:export('knots.csv')");
        CHECK(r.error == "");
        CHECK(fs::is_regular_file(f.out / "a" / "b" / "design.netj"));
        CHECK(fs::is_regular_file(f.out / "knots.csv"));
    }
}

TEST_CASE("A script reads only in its own folder and the output folder", "[sandbox]") {
    const ScriptFolders f("reads");
    f.write(f.scripts / "data.txt", "hello\n");
    f.write(f.scripts / "lib" / "helper.lua", "return {answer = 42}\n");
    f.write(f.out / "made.txt", "made\n");
    f.write(f.root / "secret.txt", "secret\n");
    f.write(f.root / "evil.lua", "return 1\n");
    SECTION("allowed") {
        const auto r2 = f.run("local ns_out = require('netsculpt').output_dir()\n"
                              "assert(io.open('data.txt'):read('l') == 'hello')\n"
                              "assert(io.open(ns_out .. '/made.txt'):read('l') == 'made')\n"
                              "for line in io.lines('data.txt') do assert(line == 'hello') end\n"
                              "assert(require('lib.helper').answer == 42)\n"
                              "assert(dofile('lib/helper.lua').answer == 42)\n");
        CHECK(r2.error == "");
        CHECK(r2.ok);
    }
    SECTION("refused") {
        const std::string secret = (f.root / "secret.txt").string();
        const std::pair<std::string, std::string> cases[] = {
            {"io.open('" + secret + "')", "io.open: reading \"" + secret + "\" is not allowed"},
            {"io.open('../secret.txt')", "io.open: reading \"../secret.txt\" is not allowed"},
            {"io.lines('../secret.txt')", "io.lines: reading"},
            {"io.input('/etc/hostname')", "io.input: reading \"/etc/hostname\" is not allowed"},
            {"dofile('../evil.lua')", "dofile: reading \"../evil.lua\" is not allowed"},
            {"loadfile('../evil.lua')", "loadfile: reading"},
            {"require('netsculpt').open('../secret.txt')", "open: reading"},
            {"require('netsculpt').new():import_rails('../secret.txt')", "import_rails: reading"},
            {"require('evil')", "module 'evil' not found"},
            {"require('lpeg')", "C modules other than netsculpt are not allowed"},
            {"error(select(2, load(string.dump(function() end))))",
             "attempt to load a binary chunk"},
            {"load(string.dump(function() end), 'x', 'b')", "load: binary chunks are not allowed"},
        };
        for (const auto& [code, message] : cases) {
            INFO(code);
            const auto r = f.run(code);
            CHECK_FALSE(r.ok);
            CHECK_THAT(r.error, Contains(message));
        }
    }
}

TEST_CASE("A studio's shared modules load from a library folder given to the run", "[sandbox]") {
    const ScriptFolders f("library");
    const std::filesystem::path shared = f.root / "studio-lib";
    f.write(
        shared / "studio" / "rails.lua",
        "local M = {}\nfunction M.name() return io.open(M.folder .. '/names.txt'):read('l') end\n"
        "return M\n");
    f.write(shared / "studio" / "names.txt", "crown\n");
    const std::string code = "local rails = require('studio.rails')\n"
                             "rails.folder = '" +
                             (shared / "studio").string() +
                             "'\n"
                             "assert(rails.name() == 'crown')\n";
    const auto without = f.run(code);
    CHECK_FALSE(without.ok);
    CHECK_THAT(without.error, Contains("module 'studio.rails' not found") &&
                                  Contains("the folders given with --lib"));
    lua::ScriptOptions options = f.options();
    options.libraryDirs = {shared};
    const auto with = f.run(code, options);
    CHECK(with.error == "");
    CHECK(with.ok);
}

TEST_CASE("The unsafe option lifts the sandbox", "[sandbox]") {
    const ScriptFolders f("unsafe");
    auto o = f.options();
    o.unsafe = true;
    const fs::path file = f.root / "written.txt";
    const auto r = f.run("local f = assert(io.open('" + file.string() +
                             "', 'w')); f:write('x'); f:close()\n"
                             "assert(os.tmpname()); assert(debug.getregistry())\n"
                             "require('netsculpt').new():save('" +
                             (f.root / "abs.netj").string() + "')\n",
                         o);
    CHECK(r.error == "");
    CHECK(fs::is_regular_file(file));
    CHECK(fs::is_regular_file(f.root / "abs.netj"));
}

TEST_CASE("Lifted, the sandbox's module folders stay where require looks", "[sandbox]") {
    // --unsafe once left only package.path's own places: a module beside the script, or in a
    // --lib folder, loaded in the sandbox and was not found with the sandbox lifted.
    const ScriptFolders f("unsafe-modules");
    const fs::path shared = f.root / "studio-lib";
    f.write(f.scripts / "beside.lua", "return {name = 'beside'}\n");
    f.write(shared / "studio" / "rails.lua", "return {name = 'crown'}\n");
    const std::string code = "assert(require('beside').name == 'beside')\n"
                             "assert(require('studio.rails').name == 'crown')\n";
    for (const bool unsafe : {false, true}) {
        INFO("unsafe: " << unsafe);
        lua::ScriptOptions options = f.options();
        options.libraryDirs = {shared};
        options.unsafe = unsafe;
        const auto r = f.run(code, options);
        CHECK(r.error == "");
        CHECK(r.ok);
    }
}
