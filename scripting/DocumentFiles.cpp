#include "scripting/DocumentFiles.h"

#include "model/Error.h"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <system_error>

namespace netsculpt::lua {

namespace fs = std::filesystem;

namespace {

/// A private temporary folder, removed with everything in it when this goes.
class TemporaryFolder {
  public:
    TemporaryFolder() {
        std::string pattern = (fs::temp_directory_path() / "netsculpt-open-XXXXXX").string();
        if (mkdtemp(pattern.data()) == nullptr)
            throw UserError("cannot create a temporary folder in " +
                            fs::temp_directory_path().string());
        path_ = pattern;
    }
    ~TemporaryFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); !from.empty() && at != std::string::npos;
         at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

/// A design to read is a regular file with at least a whole header line.
void checkReadable(const fs::path& path) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (fs::is_directory(status))
        throw UserError("cannot open " + path.string() +
                        ": it is a folder; expected a journal (.netj) or snapshot (.nets) file");
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw UserError("cannot open " + path.string() + ": it is not a regular file (a device " +
                        "or pipe); expected a journal (.netj) or snapshot (.nets) file");
    if (!fs::exists(status))
        throw UserError("cannot open " + path.string() + ": no such file");
    std::ifstream in(path, std::ios::binary);
    std::string header;
    if (!std::getline(in, header) || in.eof())
        throw UserError(path.string() + " holds no sculpture: it is " +
                        (header.empty() ? "empty" : "cut off within its header line") +
                        "; a journal or snapshot starts with a whole header line");
}

} // namespace

Document openReadOnly(const fs::path& path, std::vector<std::string>* warnings) {
    std::error_code error;
    checkReadable(path);
    const TemporaryFolder folder;
    const fs::path copy = folder.path() / path.filename();
    fs::copy_file(path, copy, error);
    if (error)
        throw UserError("cannot read " + path.string() + ": " + error.message());
    std::vector<std::string> found;
    try {
        Document doc = Document::load(copy, &found);
        for (const std::string& w : found) {
            const std::string warning = replaceAll(w, copy.string(), path.string());
            if (warnings)
                warnings->push_back(warning);
            else
                std::cerr << "netsculpt: warning: " << warning << "\n";
        }
        return doc;
    } catch (const UserError& e) {
        throw UserError(replaceAll(e.what(), copy.string(), path.string()));
    }
}

} // namespace netsculpt::lua
