#include "FolderFiles.h"

#include "OutputLock.h"

#include <sys/stat.h>
#include <system_error>

namespace netsculpt::cli {

namespace fs = std::filesystem;

bool FolderFiles::stamp(const fs::path& file, Stamp& out) {
    struct stat info {};
    if (::lstat(file.c_str(), &info) != 0 || !S_ISREG(info.st_mode))
        return false;
    out = {static_cast<unsigned long long>(info.st_ino),
           static_cast<long long>(info.st_mtim.tv_sec),
           static_cast<long long>(info.st_mtim.tv_nsec)};
    return true;
}

FolderFiles::FolderFiles(const fs::path& folder, std::size_t limit) : folder_(folder) {
    std::error_code error;
    fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied,
                                        error);
    for (; !error && it != fs::recursive_directory_iterator() && files_.size() < limit;
         it.increment(error)) {
        Stamp s;
        const std::string name = it->path().lexically_relative(folder).string();
        if (name != kRunLockName && stamp(it->path(), s))
            files_.emplace(name, s);
    }
}

std::vector<std::string> FolderFiles::unchanged() const {
    std::vector<std::string> out;
    for (const auto& [name, before] : files_) {
        Stamp now;
        if (stamp(folder_ / name, now) && now == before)
            out.push_back(name);
    }
    return out;
}

std::string leftoverNote(const fs::path& folder, const std::vector<std::string>& files,
                         std::size_t shown) {
    if (files.empty())
        return {};
    std::string note = std::to_string(files.size()) + (files.size() == 1 ? " file" : " files") +
                       " in " + folder.string() + (files.size() == 1 ? " is" : " are") +
                       " from before this run, which did not write " +
                       (files.size() == 1 ? "it: " : "them: ");
    for (std::size_t i = 0; i < files.size() && i < shown; ++i)
        note += (i == 0 ? "" : ", ") + files[i];
    if (files.size() > shown)
        note += " and " + std::to_string(files.size() - shown) + " more";
    return note;
}

} // namespace netsculpt::cli
