#pragma once
// Internal to kernel/commands: the snapshot file (Document::saveSnapshot). Line 1 is the header
// "netsculpt-snapshot 1"; line 2 one JSON object:
//   {"hash": "<hashSculpture, 16 hex digits>", "model": {rails, pieces, seams, id counters,
//    gravity}, "history": [the compacted journal entries that build the model],
//    "shape": {"warm": bool, "relaxed": bool, "positions": [x0, y0, z0, x1, ...]}}
// The history lets a loaded snapshot be undone, saved as a journal and turned into Lua; the
// model and hash make the file self-describing and are checked against the history on load.

#include "commands/Journal.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace netsculpt {

inline constexpr int kSnapshotFormat = 1;
inline constexpr std::string_view kSnapshotMagic = "netsculpt-snapshot";

/// Whether a file's text (or its first bytes) is a snapshot's rather than a journal's.
inline bool isSnapshotText(std::string_view text) { return text.starts_with(kSnapshotMagic); }

struct SnapshotData {
    Sculpture model;
    std::uint64_t hash = 0;
    std::vector<JournalEntry> history;
    std::vector<Vec3> positions; ///< one per knot of the compiled model
    bool warm = false;           ///< the positions come from a relaxation
    bool relaxed = false;        ///< ... that converged
};

std::string encodeSnapshot(const Sculpture& model, const std::vector<JournalEntry>& history,
                           const std::vector<Vec3>& positions, bool warm, bool relaxed);
/// Throws UserError naming `name` for a malformed file or a newer format.
SnapshotData decodeSnapshot(std::string_view text, const std::string& name);

} // namespace netsculpt
