// Document::load on arbitrary bytes: a journal or a snapshot, by content. What loads must save
// and load again as the same sculpture, as a journal and as a snapshot.

#include "FuzzSupport.h"

#include "commands/Document.h"
#include "commands/Journal.h"

#include <cstdio>
#include <vector>

namespace {

/// A mutation almost never keeps a journal line's CRC-32 right: every line after the header of
/// the form "<8 characters> <JSON>" gets its CRC recomputed, so that the JSON and the replay
/// behind the check get fuzzed.
std::string withGoodCrcs(std::string_view text) {
    std::string out;
    std::size_t start = 0;
    for (bool header = true; start <= text.size(); header = false) {
        std::size_t end = text.find('\n', start);
        const bool last = end == std::string_view::npos;
        if (last)
            end = text.size();
        std::string line(text.substr(start, end - start));
        if (!header && line.size() > 9 && line[8] == ' ') {
            char crc[9];
            std::snprintf(crc, sizeof crc, "%08x",
                          unsigned(netsculpt::crc32(std::string_view(line).substr(9))));
            line.replace(0, 8, crc);
        }
        out += line;
        if (last)
            break;
        out += '\n';
        start = end + 1;
    }
    return out;
}

[[noreturn]] void differs(const char* how) {
    std::fprintf(stderr, "the document read back from its %s is another sculpture\n", how);
    std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace netsculpt;
    const std::string_view bytes = fuzz::bytesOf(data, size);
    const auto file = fuzz::writeInput("design.netj", bytes.starts_with("netsculpt-journal")
                                                          ? withGoodCrcs(bytes)
                                                          : std::string(bytes));
    fuzz::refusesOnlyWithUserErrors("Document::load", [&] {
        std::vector<std::string> warnings;
        Document doc = Document::load(file, &warnings);
        const std::uint64_t hash = doc.hash();
        (void)doc.toLua();
        const auto journal = fuzz::workDir() / "again.netj";
        doc.save(journal);
        if (Document::load(journal).hash() != hash)
            differs("journal");
        const auto snapshot = fuzz::workDir() / "again.nets";
        doc.saveSnapshot(snapshot);
        if (Document::load(snapshot).hash() != hash)
            differs("snapshot");
    });
    return 0;
}
