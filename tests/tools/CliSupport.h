#pragma once
// Running the netsculpt program from tests: its exit code and everything it printed.

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace netsculpt::test {

struct Ran {
    int exitCode = -1;
    std::string output; ///< stdout and stderr together
};

inline std::filesystem::path cliPath() {
    return std::filesystem::path(NETSCULPT_BINARY_DIR) / "tools" / "netsculpt";
}

/// Runs `netsculpt <arguments>` through the shell (arguments are passed as written), with
/// `environment` ("NAME=value ...") set for it.
inline Ran runCli(const std::string& arguments, const std::string& environment = "") {
    const std::string command =
        environment + " '" + cliPath().string() + "' " + arguments + " 2>&1 </dev/null";
    Ran ran;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr)
        return ran;
    std::array<char, 4096> buffer{};
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
        ran.output.append(buffer.data(), n);
    const int status = pclose(pipe);
    ran.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return ran;
}

inline std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

/// A fresh folder for a test under the build tree.
inline std::filesystem::path freshFolder(const std::string& name) {
    const auto folder =
        std::filesystem::path(NETSCULPT_BINARY_DIR) / "test-output" / "tools" / name;
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    return folder;
}

/// Writes `text` to folder/name: the path.
inline std::filesystem::path writeScript(const std::filesystem::path& folder,
                                         const std::string& name, const std::string& text) {
    const std::filesystem::path file = folder / name;
    std::ofstream(file) << text;
    return file;
}

inline std::string quoted(const std::filesystem::path& path) {
    std::string out = "'"; // appended piecewise: "'" + std::string&& trips GCC 12's -Wrestrict
    out += path.string();
    return out += "'";
}

} // namespace netsculpt::test
