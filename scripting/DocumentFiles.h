#pragma once
// Opening sculpture files for reading only. Document::open/load keep appending to a journal they
// open (and cut a torn tail off it); a script, `netsculpt replay`, `relax`, `export` and `report`
// must leave the file they read as it was. So a journal is replayed from a private copy, and
// messages name the original file.

#include "commands/Document.h"

#include <filesystem>
#include <string>
#include <vector>

namespace netsculpt::lua {

/// A journal (replayed) or a snapshot, by content; the file is never written. The document is
/// attached to no journal the caller can see (attachJournal to keep one).
Document openReadOnly(const std::filesystem::path& path,
                      std::vector<std::string>* warnings = nullptr);

} // namespace netsculpt::lua
