#pragma once
// A sculpture being worked on: the model, its undo history, its journal and its compiled,
// relaxed mass-spring system. Every change goes through execute(); undo()/redo() restore the
// model bit for bit. When a journal file is attached every entry is appended and synced before
// the call returns (DESIGN.md "Journal").

#include "commands/Command.h"
#include "model/Compiler.h"
#include "physics/Relaxer.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace netsculpt {

class Journal;

/// Relaxation backends: "auto" (the fastest that converges), "rk4" (the paper's overdamped RK4),
/// "fast", "bullet" (when built with Bullet).
struct DocumentRelaxOptions {
    RelaxOptions solver;
    std::string backend = "auto";
};

class Document {
  public:
    Document();
    ~Document();
    Document(Document&&) noexcept;
    Document& operator=(Document&&) noexcept;

    /// Replays a journal file and keeps appending to it. A torn or garbled last entry is dropped
    /// and reported in `warnings`; any other problem throws UserError with the line number.
    static Document open(const std::filesystem::path& journal, std::vector<std::string>* warnings = nullptr);
    /// Opens a snapshot (see saveSnapshot) or a journal, by content.
    static Document load(const std::filesystem::path& file, std::vector<std::string>* warnings = nullptr);

    /// Starts journaling to `path` (created or truncated): the header and the history so far.
    void attachJournal(const std::filesystem::path& path);
    /// Writes a compacted journal (the commands that build the current state) to `path`; if a
    /// journal is attached it stays attached. Marks the document clean.
    void save(const std::filesystem::path& path);
    /// Writes the model and the current positions as one file that opens fast; opening it
    /// gives the same hash() as replaying the journal.
    void saveSnapshot(const std::filesystem::path& path) const;

    /// Validates, applies, recompiles and journals. With merge = true the command joins the
    /// previous undo step when canMerge() allows (a continuous gesture). Throws UserError and
    /// leaves everything (model, history, journal) as it was.
    CommandResult execute(const Command& command, bool merge = false);
    bool canUndo() const;
    bool canRedo() const;
    void undo(); ///< UserError when there is nothing to undo
    void redo(); ///< UserError when there is nothing to redo
    /// The command undo() (redo()) would take back (bring back): "set_rows", or "" when none.
    std::string undoName() const;
    std::string redoName() const;
    /// Tells apart the pieces (rails) that have had an id: an id made again after the step that
    /// made it was undone has another birth, one brought back by redo() the same. A number for
    /// an id of the current sculpture; 0 for one never made.
    std::uint64_t birth(PieceId id) const;
    std::uint64_t birth(RailId id) const;
    std::size_t undoableSteps() const; ///< how many undo() calls in a row can succeed
    std::size_t redoableSteps() const; ///< how many redo() calls in a row can succeed
    /// Ends the current merge run: the next execute(…, merge = true) starts a new undo step.
    void endGesture();

    /// No changes since the last save / open (the clean index).
    bool isClean() const;
    void markClean();

    const Sculpture& sculpture() const;
    /// The compiled system of the current model; positions are relaxed ones when relax() ran
    /// (kept across edits as a warm start for knots that still exist).
    const CompiledSculpture& compiled() const;
    CompiledSculpture& compiled();
    /// The last relaxation's result (converged = false before any).
    const RelaxResult& lastRelax() const;
    bool isRelaxed() const; ///< a relaxation converged since the last change
    /// The steady wind the shape was last relaxed under (none: gravity alone, and after the
    /// studio's relaxation); its load belongs in the shape's force balance (the report). Saved in
    /// snapshots.
    const std::optional<Wind>& shapeWind() const;
    /// The tolerance the shape was last relaxed to, saved in snapshots (a relaxed one's); 0 when
    /// unknown (none ran, a snapshot from before it was saved, after the studio's relaxation).
    double shapeTolerance() const;
    /// Takes positions relaxed elsewhere (the studio's background relaxation) as the current
    /// shape, measured from compiled().system.origin as that system's are: the next edit
    /// warm-starts from them, as after relax(). `converged`: they are an
    /// equilibrium at the material's stiffness. UserError when the count is not the knot count.
    void adoptPositions(std::vector<Vec3> positions, bool converged);

    /// UserError, the document unchanged, for a tolerance outside (0, kMaxTolerance].
    RelaxResult relax(const DocumentRelaxOptions& options);
    /// With the default options (an overload, not a default argument: g++ 12 warns on the
    /// temporary's std::function when it is destroyed at the caller).
    RelaxResult relax();

    /// FNV-1a over the model in a fixed order: equal hashes = the same sculpture.
    std::uint64_t hash() const;
    /// The commands of the history (for to-lua), as journaled.
    std::string toLua() const;

  private:
    struct State;
    std::unique_ptr<State> state_;
};

/// FNV-1a hash of a sculpture (rails, pieces, seams, id counters, gravity), fixed order.
std::uint64_t hashSculpture(const Sculpture& s);

} // namespace netsculpt
