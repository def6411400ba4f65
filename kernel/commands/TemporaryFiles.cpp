#include "commands/TemporaryFiles.h"

#include <atomic>
#include <cerrno>
#include <charconv>
#include <string>
#include <system_error>

#include <signal.h>
#include <unistd.h>

namespace netsculpt {

namespace {

constexpr const char* kInfix = ".tmp-";

/// Whether `name` is `target.tmp-<pid>-...` of a process that is gone.
bool staleTemporaryOf(const std::string& name, const std::string& target) {
    const std::string prefix = target + kInfix;
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0)
        return false;
    long pid = 0;
    const char* digits = name.data() + prefix.size();
    const auto [end, error] = std::from_chars(digits, name.data() + name.size(), pid);
    if (error != std::errc() || end == digits || pid <= 0 || pid == long(::getpid()))
        return false;
    return ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
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
        if (staleTemporaryOf(name, target))
            std::filesystem::remove(it->path(), error);
    }
}

} // namespace netsculpt
