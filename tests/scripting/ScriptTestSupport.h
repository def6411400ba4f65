#pragma once
// Shared by the scripting tests: a fresh folder pair (scripts, out) per test under the build
// tree, and running a chunk of Lua in it.

#include "scripting/ScriptHost.h"

#include <filesystem>
#include <fstream>
#include <string>

namespace netsculpt::test {

struct ScriptFolders {
    std::filesystem::path root, scripts, out;

    explicit ScriptFolders(const std::string& name) {
        root = std::filesystem::path(NETSCULPT_BINARY_DIR) / "test-output" / "scripting" / name;
        std::filesystem::remove_all(root);
        scripts = root / "scripts";
        out = root / "out";
        std::filesystem::create_directories(scripts);
        std::filesystem::create_directories(out);
    }

    lua::ScriptOptions options() const {
        lua::ScriptOptions o;
        o.outputDir = out;
        o.journal = false;
        return o;
    }

    /// Runs `code` as the script "<chunk>" in the scripts folder.
    lua::ScriptResult run(const std::string& code, lua::ScriptOptions o,
                          const std::string& chunk = "test.lua") const {
        if (o.outputDir == ".")
            o.outputDir = out;
        return lua::runScriptString(code, chunk, scripts, o);
    }
    lua::ScriptResult run(const std::string& code) const { return run(code, options()); }

    void write(const std::filesystem::path& file, const std::string& text) const {
        std::filesystem::create_directories(file.parent_path());
        std::ofstream(file) << text;
    }
};

} // namespace netsculpt::test
