// A sculpture script run as `netsculpt run` runs it (sandboxed, with its limits) from arbitrary
// bytes. The instruction budget is 10^7 instead of 10^9 and the memory limit 256 MiB, so that a
// runaway Lua loop ends well within libFuzzer's -timeout and -rss_limit_mb.

#include "FuzzSupport.h"

#include "scripting/ScriptHost.h"

#include <utility>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace netsculpt;
    static const auto folders = [] {
        const auto scripts = fuzz::workDir() / "scripts";
        const auto out = fuzz::workDir() / "out";
        std::filesystem::create_directories(scripts);
        std::filesystem::create_directories(out);
        return std::pair{scripts, out};
    }();
    lua::ScriptOptions options;
    options.outputDir = folders.second;
    options.journal = false;
    options.maxInstructions = 10'000'000;
    options.maxMemory = std::size_t(256) << 20;
    try {
        (void)lua::runScriptString(fuzz::bytesOf(data, size), "fuzz.lua", folders.first, options);
    } catch (const std::exception& e) {
        fuzz::unexpected("runScriptString", e);
    }
    return 0;
}
