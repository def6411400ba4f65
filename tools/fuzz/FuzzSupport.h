#pragma once
// Shared by the libFuzzer harnesses (README "Fuzzing"): the readers take files, so each input is
// written to a file in a folder of its own, and what is not a UserError is a finding.

#include "model/Error.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <unistd.h>

namespace netsculpt::fuzz {

/// A folder for this process's inputs: in /dev/shm when there is one (the inputs are written
/// thousands of times a second), else in the temporary folder. libFuzzer ends with _Exit, so
/// the folders stay: remove netsculpt-fuzz-* after a run (-fork makes one per job).
inline const std::filesystem::path& workDir() {
    static const std::filesystem::path dir = [] {
        std::error_code error;
        const std::filesystem::path shm = "/dev/shm";
        const std::filesystem::path base = std::filesystem::is_directory(shm, error)
                                               ? shm
                                               : std::filesystem::temp_directory_path();
        std::filesystem::path d = base / ("netsculpt-fuzz-" + std::to_string(getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

inline std::filesystem::path writeInput(const std::string& name, std::string_view bytes) {
    const std::filesystem::path path = workDir() / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), std::streamsize(bytes.size()));
    return path;
}

inline std::string_view bytesOf(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

/// A reader let through an exception that is not a UserError: abort so that libFuzzer keeps
/// the input.
[[noreturn]] inline void unexpected(const char* reader, const std::exception& e) {
    std::fprintf(stderr, "%s threw an exception that is not a UserError: %s\n", reader, e.what());
    std::abort();
}

/// Runs `read`: a UserError is the reader refusing the input, as it should; any other exception
/// is a finding (unexpected).
template <class Read> void refusesOnlyWithUserErrors(const char* reader, Read&& read) {
    try {
        read();
    } catch (const UserError&) {
    } catch (const std::exception& e) {
        unexpected(reader, e);
    }
}

} // namespace netsculpt::fuzz
