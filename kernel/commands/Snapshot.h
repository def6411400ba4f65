#pragma once
// Internal to kernel/commands: the snapshot file (Document::saveSnapshot). Line 1 is the header
// "netsculpt-snapshot 5"; line 2 one JSON object:
//   {"hash": "<hashSculpture, 16 hex digits>", "model": {rails, pieces, seams, id counters,
//    gravity}, "history": [the compacted journal entries that build the model],
//    "shape": {"warm": bool, "relaxed": bool, "origin": [x, y, z],
//              "positions": [x0, y0, z0, x1, ...],
//              "wind": {"direction": [x, y, z], "pressure": q} (only when relaxed under one),
//              "residual": r (only when relaxed),
//              "tolerance": t (only when relaxed: what it converged to)}}
// The positions are measured from the origin (MassSpringSystem::origin), so that a shape relaxed
// in site coordinates is saved to the last bit. Format 1 had no origin: its positions are the
// sculpture's coordinates (origin (0, 0, 0)), and it is still read. Format 2 had no "residual";
// format 3 added it (so that an older netsculpt says the file is newer rather than refusing the
// key), format 4 "tolerance", format 5 a material's "breaking_load" (in the model and in the
// history's set_material, only where one is given); all are still read (a shape without a
// tolerance is reported against the default one, a model of format 4 or older has no breaking
// loads).
// The history lets a loaded snapshot be undone, saved as a journal and turned into Lua; the
// model and hash make the file self-describing and are checked against the history on load.

#include "commands/Journal.h"

#include "physics/Wind.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace netsculpt {

inline constexpr int kSnapshotFormat = 5;
inline constexpr std::string_view kSnapshotMagic = "netsculpt-snapshot";

/// Whether a file's text (or its first bytes) is a snapshot's rather than a journal's.
inline bool isSnapshotText(std::string_view text) { return text.starts_with(kSnapshotMagic); }

/// The shape a snapshot saves ("shape").
struct SnapshotShape {
    Vec3 origin;                 ///< m; what the positions are measured from
    std::vector<Vec3> positions; ///< m, from origin; one per knot of the compiled model
    std::optional<Wind> wind;    ///< the wind the shape was relaxed under (Document::shapeWind)
    bool warm = false;           ///< the positions come from a relaxation
    bool relaxed = false;        ///< ... that converged
    /// The relaxed shape's residual when it was saved: a loaded shape far above it was edited or
    /// damaged, and is not taken as relaxed. Absent in older files.
    std::optional<double> residual;
    /// The tolerance the relaxed shape converged to (Document::shapeTolerance): what its force
    /// balance is checked against. Absent in older files.
    std::optional<double> tolerance;
};

struct SnapshotData {
    Sculpture model;
    std::uint64_t hash = 0;
    std::vector<JournalEntry> history;
    SnapshotShape shape;
};

std::string encodeSnapshot(const Sculpture& model, const std::vector<JournalEntry>& history,
                           const SnapshotShape& shape);
/// Throws UserError naming `name` for a malformed file or a newer format.
SnapshotData decodeSnapshot(std::string_view text, const std::string& name);

} // namespace netsculpt
