#include "commands/TemporaryFiles.h"

#include <atomic>
#include <chrono>
#include <cerrno>
#include <charconv>
#include <string>
#include <optional>
#include <system_error>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace netsculpt {

namespace {

constexpr const char* kInfix = ".tmp-";
constexpr long kMaxPid = 4194304; // Linux's largest pid_max (2^22)
/// A temporary younger than this may belong to a writer this process cannot see (another host
/// or container sharing the folder): it is left alone.
constexpr auto kStaleAge = std::chrono::minutes(10);

/// The writer's pid when `name` is exactly `target.tmp-<pid>-<n>` or `target.tmp-<pid>`.
std::optional<long> writerOf(const std::string& name, const std::string& target) {
    const std::string prefix = target + kInfix;
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0)
        return std::nullopt;
    const char* const last = name.data() + name.size();
    long pid = 0, count = 0;
    const char* digits = name.data() + prefix.size();
    const auto read = std::from_chars(digits, last, pid);
    if (read.ec != std::errc() || read.ptr == digits || pid < 2 || pid > kMaxPid)
        return std::nullopt;
    if (read.ptr == last)
        return pid;
    if (*read.ptr != '-') // "-<n>" must follow
        return std::nullopt;
    const char* counter = read.ptr + 1;
    const auto counted = std::from_chars(counter, last, count);
    if (counted.ec != std::errc() || counted.ptr == counter || counted.ptr != last)
        return std::nullopt;
    return pid;
}

/// Whether the file at `path`, named `name`, is a temporary of `target` that its writer, a
/// process of this user that no longer runs, left at least kStaleAge ago.
bool staleTemporary(const std::filesystem::path& path, const std::string& name,
                    const std::string& target) {
    const std::optional<long> pid = writerOf(name, target);
    if (!pid || *pid == long(::getpid()))
        return false;
    struct stat status {};
    if (::lstat(path.c_str(), &status) != 0 || !S_ISREG(status.st_mode) ||
        status.st_uid != ::geteuid())
        return false;
    const auto written = std::chrono::system_clock::from_time_t(status.st_mtime);
    if (std::chrono::system_clock::now() - written < kStaleAge)
        return false;
    return ::kill(pid_t(*pid), 0) != 0 && errno == ESRCH;
}

} // namespace

std::filesystem::path temporaryBeside(const std::filesystem::path& path) {
    static std::atomic<unsigned> counter{0};
    std::filesystem::path tmp = path;
    tmp += kInfix + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    return tmp;
}

void removeStaleTemporaries(const std::filesystem::path& path) {
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
    const std::string target = path.filename().string();
    std::error_code error;
    for (std::filesystem::directory_iterator it(folder, error), end; !error && it != end;
         it.increment(error)) {
        const std::string name = it->path().filename().string();
        if (staleTemporary(it->path(), name, target))
            std::filesystem::remove(it->path(), error);
    }
}

} // namespace netsculpt
