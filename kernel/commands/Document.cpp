#include "commands/Document.h"

#include "commands/Journal.h"
#include "commands/Snapshot.h"
#include "model/Error.h"
#include "physics/Backends.h"
#include "physics/Forces.h"
#include "physics/WarmStart.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <unordered_map>

namespace netsculpt {

namespace {

/// Bytes of knot positions the undo history may keep (see Memo); past it the oldest go.
constexpr std::size_t kPositionMemoBudget = std::size_t(256) << 20;

/// Whether the forces of `system` at `positions` (one per knot) are finite: a damaged snapshot
/// may hold finite coordinates so large that a bar's length or force overflows.
bool forcesComputable(MassSpringSystem system, const std::vector<Vec3>& positions) {
    system.position = positions;
    return std::isfinite(residual(system));
}

/// Whether the knots the rails hold are at `positions` where the rails hold them (to a
/// micrometre: rounding of a moved origin stays far below that).
bool heldOnRails(const MassSpringSystem& system, const std::vector<Vec3>& positions) {
    for (std::size_t k = 0; k < system.knotCount(); ++k)
        if (system.fixed[k] && !(distance(positions[k], system.position[k]) <= 1e-6))
            return false;
    return true;
}

/// Whether a snapshot's relaxed shape at `positions` is still the equilibrium it was saved as:
/// its residual within twice the saved one (the same bits when the origin is the saved one) or
/// within the default tolerance, which any rounding of a moved origin stays far below.
bool stillRelaxed(MassSpringSystem system, const std::vector<Vec3>& positions,
                  const SnapshotShape& saved) {
    system.position = positions;
    return residual(system, saved.wind) <= std::max(2 * *saved.residual, RelaxOptions{}.tolerance);
}

/// The shape a state of the history had when the document left it. Only relaxed shapes need
/// their positions: an unrelaxed state's shape is its fresh compile, rebuilt bit for bit.
struct Memo {
    bool kept = false; ///< false: unknown (never left, or dropped for the memory budget)
    std::shared_ptr<const std::vector<Vec3>> positions; ///< null: the fresh compile is the shape
    bool relaxed = false;                               ///< a converged relaxation of this model
    std::size_t bytes() const { return positions ? positions->size() * sizeof(Vec3) : 0; }
};

/// One undo step: usually one command, several when a gesture merged them.
struct Step {
    std::vector<Command> commands;
    std::vector<CommandResult> results;
    std::vector<int> lines; ///< journal lines the commands were replayed from (0 = executed)
    Sculpture after;
    std::uint64_t serial = 0; ///< numbers the steps a document ever took, from 1 (never reused)
};

enum class MergeMode { Never, IfGesture, Required };

/// Capacity for n elements, growing geometrically (reserve(size + 1) would copy every time).
template <typename Vector> void makeRoom(Vector& v, std::size_t n) {
    if (v.capacity() < n) v.reserve(std::max(n, 2 * v.capacity()));
}

void report(const std::vector<std::string>& messages, std::vector<std::string>* warnings) {
    for (const std::string& m : messages) {
        if (warnings) warnings->push_back(m);
        else std::cerr << "netsculpt: warning: " << m << "\n";
    }
}

std::string readWhole(const std::filesystem::path& path) {
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) // why, as the system says it ("No such file or directory")
        throw UserError("cannot open " + path.string() +
                        (errno != 0 ? ": " + std::string(std::strerror(errno)) : std::string()));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    return buffer.str();
}

} // namespace

struct Document::State {
    Sculpture base;               ///< the state before the first step (empty)
    std::vector<Step> steps;      ///< the undo history; steps [0, index) are applied
    std::size_t index = 0;
    std::vector<Memo> memos;      ///< memos[i]: the shape of state i when it was left
    std::size_t memoBytes = 0;
    CompiledSculpture compiled;   ///< of state(index)
    bool warm = false;            ///< compiled positions come from a relaxation (carried on edits)
    bool relaxed = false;
    RelaxResult lastRelax;
    std::optional<Wind> wind; ///< the wind the shape was last relaxed under (shapeWind())
    double tolerance = 0;     ///< the tolerance it was last relaxed to (shapeTolerance())
    /// The system (law and shape) the last time the shape was relaxed: after an edit, relax()
    /// hands the fast path the tensions that shape had (physics/WarmStart.h), so that the parts
    /// the edit did not touch keep their equilibrium instead of going through a soft stage.
    std::optional<MassSpringSystem> relaxedSystem;
    /// The backend of the last relax(), kept so that it can reuse what it analysed (the fast
    /// path keeps its sparse ordering while the bars stay the same).
    std::unique_ptr<Relaxer> relaxer;
    std::ptrdiff_t cleanIndex = 0; ///< -1: no state of the history is the saved one
    bool gestureOpen = false;
    std::vector<JournalEntry> log; ///< every entry since the document began: what its journal holds
    std::unique_ptr<Journal> journal;
    std::uint64_t nextSerial = 1; ///< Step::serial of the next step
    /// The serial of the step that last created each id (birth()): an id made again after its
    /// step was undone has a new one.
    std::unordered_map<std::uint32_t, std::uint64_t> pieceBirth, railBirth;

    State() : memos(1), compiled(compileSculpture(base)) {}

    const Sculpture& state(std::size_t i) const { return i == 0 ? base : steps[i - 1].after; }
    const Sculpture& current() const { return state(index); }

    Memo leavingMemo() const {
        if (!warm) return Memo{true, nullptr, false};
        return Memo{true, std::make_shared<const std::vector<Vec3>>(compiled.system.position), relaxed};
    }
    void setMemo(std::size_t i, Memo memo) {
        memoBytes -= memos[i].bytes();
        memos[i] = std::move(memo);
        memoBytes += memos[i].bytes();
        for (std::size_t k = 0; k < memos.size() && memoBytes > kPositionMemoBudget; ++k) {
            if (!memos[k].positions) continue;
            memoBytes -= memos[k].bytes();
            memos[k] = {}; // forgotten: returning to it warm-starts from the shape of the moment
        }
    }
    void dropRedoBranch() {
        for (std::size_t i = index + 1; i < memos.size(); ++i) memoBytes -= memos[i].bytes();
        memos.resize(index + 1);
        steps.erase(steps.begin() + std::ptrdiff_t(index), steps.end());
        if (cleanIndex > std::ptrdiff_t(index)) cleanIndex = -1;
    }
    /// Commits a freshly compiled system for the new current state.
    void installCompiled(CompiledSculpture next, const KnotRenaming& renamed = {}) {
        if (warm)
            carryPositions(compiled, next, renamed);
        compiled = std::move(next);
        relaxed = false;
    }
    JournalEntry nextEntry(JournalEntry::Kind kind) const {
        JournalEntry e;
        e.kind = kind;
        e.seq = log.size() + 1;
        return e;
    }

    /// How `command` renamed knots it did not move: a split's right part (else none).
    KnotRenaming renamingOf(const Command& command, const CommandResult& result) const {
        const auto* split = std::get_if<SplitCommand>(&command);
        if (split == nullptr || result.pieces.size() != 2 ||
            !compiled.pieces.contains(split->piece))
            return {};
        return splitRenaming(split->piece, result.pieces[1], split->column,
                             compiled.pieces.at(split->piece).columns);
    }

    /// Validate, apply, compile (unless replaying), journal, commit (DESIGN.md "Journal").
    CommandResult execute(const Command& command, MergeMode mode, bool compile, int line = 0) {
        const bool mergeable = index > 0 && index == steps.size() &&
                               canMerge(steps[index - 1].commands.back(), command);
        if (mode == MergeMode::Required && !mergeable)
            throw UserError("it is marked as merged into the previous undo step, which it cannot join");
        const bool merging = mergeable && (mode == MergeMode::Required || (mode == MergeMode::IfGesture && gestureOpen));

        Sculpture work = current();
        CommandResult result = applyCommand(work, command);
        // A split keeps the piece's id for its first part: only ids new to the sculpture are born.
        std::vector<PieceId> bornPieces;
        std::vector<RailId> bornRails;
        for (PieceId id : result.pieces)
            if (!current().hasPiece(id)) bornPieces.push_back(id);
        for (RailId id : result.rails)
            if (!current().hasRail(id)) bornRails.push_back(id);
        refreshAndValidate(work);
        std::optional<CompiledSculpture> next;
        if (compile) next = compileSculpture(work);
        JournalEntry entry = nextEntry(JournalEntry::Kind::Command);
        entry.command = command;
        entry.created = result;
        entry.merge = merging;
        const std::string encoded = encodeJournalLine(entry);
        Memo leaving = merging ? Memo{} : leavingMemo();
        makeRoom(log, log.size() + 1);
        makeRoom(steps, index + 1);
        makeRoom(memos, index + 2);
        pieceBirth.reserve(pieceBirth.size() + bornPieces.size());
        railBirth.reserve(railBirth.size() + bornRails.size());

        if (journal) journal->append(encoded); // the last step that may fail: nothing is changed yet

        if (merging) {
            Step& top = steps[index - 1];
            top.commands.push_back(command);
            top.results.push_back(result);
            top.lines.push_back(line);
            top.after = std::move(work);
            if (cleanIndex == std::ptrdiff_t(index)) cleanIndex = -1; // the saved state is gone
        } else {
            dropRedoBranch();
            setMemo(index, std::move(leaving));
            steps.push_back(Step{{command}, {result}, {line}, std::move(work), nextSerial++});
            memos.emplace_back();
            ++index;
        }
        for (PieceId id : bornPieces) pieceBirth[id.value] = steps[index - 1].serial;
        for (RailId id : bornRails) railBirth[id.value] = steps[index - 1].serial;
        if (next)
            installCompiled(std::move(*next), renamingOf(command, result));
        log.push_back(std::move(entry));
        gestureOpen = true;
        return result;
    }

    void undoRedo(bool undo, bool compile) {
        if (undo && index == 0) throw UserError("nothing to undo");
        if (!undo && index == steps.size()) throw UserError("nothing to redo");
        const std::size_t target = undo ? index - 1 : index + 1;
        const Memo memo = memos[target];
        std::optional<CompiledSculpture> next;
        if (compile) {
            next = compileSculpture(state(target));
            if (memo.positions && memo.positions->size() == next->system.knotCount())
                next->system.position = *memo.positions;
        }
        const JournalEntry entry = nextEntry(undo ? JournalEntry::Kind::Undo : JournalEntry::Kind::Redo);
        const std::string encoded = encodeJournalLine(entry);
        Memo leaving = leavingMemo();
        makeRoom(log, log.size() + 1);

        if (journal) journal->append(encoded);

        setMemo(index, std::move(leaving));
        setMemo(target, {}); // it is the current state now; its memo is taken again when it is left
        if (next) {
            if (memo.kept) { // the shape it had: relaxed positions, or its initial geometry
                warm = memo.positions != nullptr;
                relaxed = warm && memo.relaxed;
                compiled = std::move(*next);
                // The next relax's hint comes from this shape's own law, or from none.
                if (relaxed) relaxedSystem = compiled.system;
                else relaxedSystem.reset();
            } else { // unknown: warm-start from the current shape when it is relaxed
                installCompiled(std::move(*next));
            }
        }
        index = target;
        gestureOpen = false;
        log.push_back(entry);
    }

    /// Replays journal entries into this (fresh) state without compiling each step, checking the
    /// ids every create command returns; then compiles the result once.
    void replay(const std::vector<JournalEntry>& entries, const std::string& name) {
        for (const JournalEntry& e : entries) {
            const std::string where = name + " " + describe(e);
            try {
                if (e.kind != JournalEntry::Kind::Command) {
                    undoRedo(e.kind == JournalEntry::Kind::Undo, false);
                    continue;
                }
                const CommandResult result =
                    execute(e.command, e.merge ? MergeMode::Required : MergeMode::Never, false, e.line);
                if (!(result == e.created))
                    throw UserError("it created " + describeIds(result) + ", the journal recorded " +
                                    describeIds(e.created));
            } catch (const UserError& error) {
                throw UserError(where + ": " + error.what());
            }
        }
        try {
            compiled = compileSculpture(current());
        } catch (const UserError& error) {
            std::string where = name;
            if (index > 0) {
                const Step& step = steps[index - 1];
                JournalEntry last;
                last.command = step.commands.back();
                last.line = step.lines.back();
                last.seq = 0;
                where += " " + describe(last);
            }
            throw UserError(where + ": " + error.what());
        }
        log = entries;
        for (JournalEntry& e : log) e.line = 0;
        cleanIndex = std::ptrdiff_t(index);
        gestureOpen = false;
    }

    static std::string describeIds(const CommandResult& r) {
        std::string out;
        for (RailId id : r.rails) out += (out.empty() ? "" : ", ") + toString(id);
        for (PieceId id : r.pieces) out += (out.empty() ? "" : ", ") + toString(id);
        return out.empty() ? "nothing" : out;
    }

    /// The commands of the applied steps, numbered from 1; merged commands keep their flag.
    std::vector<JournalEntry> compacted() const {
        std::vector<JournalEntry> out;
        for (std::size_t i = 0; i < index; ++i)
            for (std::size_t k = 0; k < steps[i].commands.size(); ++k) {
                JournalEntry e;
                e.seq = out.size() + 1;
                e.command = steps[i].commands[k];
                e.created = steps[i].results[k];
                e.merge = k > 0;
                out.push_back(std::move(e));
            }
        return out;
    }
};

Document::Document() : state_(std::make_unique<State>()) {}
Document::~Document() = default;
Document::Document(Document&&) noexcept = default;
Document& Document::operator=(Document&&) noexcept = default;

Document Document::open(const std::filesystem::path& journal, std::vector<std::string>* warnings) {
    const JournalContents contents = readJournal(journal);
    Document doc;
    doc.state_->replay(contents.entries, journal.string());
    doc.state_->journal = Journal::reopen(journal, contents.validBytes);
    report(contents.warnings, warnings);
    return doc;
}

Document Document::load(const std::filesystem::path& file, std::vector<std::string>* warnings) {
    const std::string text = readWhole(file);
    if (!isSnapshotText(text)) return open(file, warnings);
    SnapshotData data = decodeSnapshot(text, file.string());
    Document doc;
    State& st = *doc.state_;
    st.replay(data.history, file.string());
    const std::uint64_t built = hashSculpture(st.current());
    if (built != data.hash || hashSculpture(data.model) != data.hash)
        throw UserError(file.string() + " is inconsistent: its history builds a sculpture different from its model "
                                        "(the file was edited or damaged)");
    std::vector<Vec3> positions = std::move(data.shape.positions);
    const Vec3 shift = data.shape.origin - st.compiled.system.origin; // format 1: from (0, 0, 0)
    if (shift != Vec3{})
        for (Vec3& p : positions) p += shift;
    const bool fits = positions.size() == st.compiled.system.knotCount();
    if (fits && !forcesComputable(st.compiled.system, positions)) {
        report({file.string() + ": the saved shape's knots are too far apart for the forces "
                                "between them to be computed (a coordinate beyond about 1e150 m); "
                                "starting from the initial geometry"},
               warnings);
    } else if (fits && !heldOnRails(st.compiled.system, positions)) {
        report({file.string() + ": the saved shape's knots held by rails are not where the rails "
                                "hold them (the file was edited or damaged); starting from the "
                                "initial geometry"},
               warnings);
    } else if (fits && data.shape.relaxed && data.shape.residual &&
               !stillRelaxed(st.compiled.system, positions, data.shape)) {
        report({file.string() + ": the saved shape is not the equilibrium it was saved as (the "
                                "file was edited or damaged); starting from the initial geometry"},
               warnings);
    } else if (fits) {
        st.compiled.system.position = std::move(positions);
        st.wind = data.shape.wind;
        st.tolerance = data.shape.tolerance.value_or(0.0);
        st.warm = data.shape.warm;
        st.relaxed = data.shape.relaxed;
        if (st.relaxed) st.relaxedSystem = st.compiled.system;
    } else if (!positions.empty()) {
        report({file.string() + ": the saved shape has " + std::to_string(positions.size()) +
                " knots, the model " + std::to_string(st.compiled.system.knotCount()) +
                "; starting from the initial geometry"},
               warnings);
    }
    return doc;
}

void Document::attachJournal(const std::filesystem::path& path) {
    state_->journal = Journal::create(path, state_->log);
}

void Document::save(const std::filesystem::path& path) {
    State& st = *state_;
    std::vector<JournalEntry> entries = st.compacted();
    std::error_code ec;
    const bool attached = st.journal && std::filesystem::equivalent(path, st.journal->path(), ec);
    if (attached) {
        // Replacing the attached journal: it continues from the compacted history, so the redo
        // branch (which it no longer records) goes too.
        st.journal = Journal::create(path, entries);
        st.dropRedoBranch();
        st.log = std::move(entries);
        st.gestureOpen = false;
    } else {
        writeJournalFile(path, entries);
    }
    markClean();
}

void Document::saveSnapshot(const std::filesystem::path& path) const {
    const State& st = *state_;
    const MassSpringSystem& system = st.compiled.system;
    const std::optional<double> saved =
        st.relaxed ? std::optional(residual(system, st.wind)) : std::nullopt;
    writeFileDurably(
        path, encodeSnapshot(
                  st.current(), st.compacted(),
                  {system.origin, system.position, st.wind, st.warm, st.relaxed, saved,
                   st.relaxed && st.tolerance > 0 ? std::optional(st.tolerance) : std::nullopt}));
}

CommandResult Document::execute(const Command& command, bool merge) {
    return state_->execute(command, merge ? MergeMode::IfGesture : MergeMode::Never, true);
}

bool Document::canUndo() const { return state_->index > 0; }
bool Document::canRedo() const { return state_->index < state_->steps.size(); }
std::string Document::undoName() const {
    return canUndo() ? commandName(state_->steps[state_->index - 1].commands.front()) : "";
}
std::string Document::redoName() const {
    return canRedo() ? commandName(state_->steps[state_->index].commands.front()) : "";
}
std::uint64_t Document::birth(PieceId id) const {
    const auto it = state_->pieceBirth.find(id.value);
    return it == state_->pieceBirth.end() ? 0 : it->second;
}
std::uint64_t Document::birth(RailId id) const {
    const auto it = state_->railBirth.find(id.value);
    return it == state_->railBirth.end() ? 0 : it->second;
}
std::size_t Document::undoableSteps() const { return state_->index; }
std::size_t Document::redoableSteps() const { return state_->steps.size() - state_->index; }
void Document::undo() { state_->undoRedo(true, true); }
void Document::redo() { state_->undoRedo(false, true); }
void Document::endGesture() { state_->gestureOpen = false; }

bool Document::isClean() const { return state_->cleanIndex == std::ptrdiff_t(state_->index); }
void Document::markClean() { state_->cleanIndex = std::ptrdiff_t(state_->index); }

const Sculpture& Document::sculpture() const { return state_->current(); }
const CompiledSculpture& Document::compiled() const { return state_->compiled; }
CompiledSculpture& Document::compiled() { return state_->compiled; }
const RelaxResult& Document::lastRelax() const { return state_->lastRelax; }
const std::optional<Wind>& Document::shapeWind() const { return state_->wind; }
double Document::shapeTolerance() const {
    return state_->tolerance;
}
bool Document::isRelaxed() const { return state_->relaxed; }

void Document::adoptPositions(std::vector<Vec3> positions, bool converged) {
    State& st = *state_;
    if (positions.size() != st.compiled.system.knotCount())
        throw UserError("adopt positions: " + std::to_string(positions.size()) +
                        " positions given, the sculpture has " +
                        std::to_string(st.compiled.system.knotCount()) + " knots");
    st.compiled.system.position = std::move(positions);
    st.wind.reset(); // the studio relaxes under gravity alone
    st.tolerance = 0; // ... to a tolerance of its own
    st.relaxed = converged;
    st.warm = true;
    if (converged) st.relaxedSystem = st.compiled.system;
}

namespace {
/// The name a backend reports for a requested backend ("auto" runs the fast path).
std::string_view relaxerKey(std::string_view requested) { return requested == "auto" ? "fast" : requested; }
} // namespace

RelaxResult Document::relax() {
    const DocumentRelaxOptions defaults;
    return relax(defaults);
}

RelaxResult Document::relax(const DocumentRelaxOptions& options) {
    if (!(options.solver.tolerance > 0 && options.solver.tolerance <= kMaxTolerance))
        throw UserError("relax: tolerance = " + formatNumber(options.solver.tolerance) +
                        "; expected a number > 0 and at most " + formatNumber(kMaxTolerance) +
                        " (the largest residual, in knot weights, that counts as relaxed)");
    State& st = *state_;
    if (!st.relaxer || relaxerKey(options.backend) != st.relaxer->name()) st.relaxer = makeRelaxer(options.backend);
    RelaxOptions solver = options.solver;
    // An edit of a relaxed shape: the tensions it had before the edit (a predictor step).
    const bool hinted = relaxerKey(options.backend) == "fast" && !st.relaxed && st.relaxedSystem &&
                        solver.startTensions.empty();
    const std::vector<double> hint =
        hinted ? startTensions(*st.relaxedSystem, st.compiled.system) : std::vector<double>{};
    if (!hint.empty()) solver.startTensions = hint;
    RelaxResult result = st.relaxer->relax(st.compiled.system, solver);
    result.tolerance = options.solver.tolerance;
    const MassSpringSystem& system = st.compiled.system;
    if (const std::int64_t worst = result.converged ? -1 : knotWithLargestResidual(system, options.solver.wind);
        worst >= 0)
        result.unsettledAt = system.refs[system.refStart[static_cast<std::size_t>(worst)]];
    st.lastRelax = result;
    st.wind = options.solver.wind;
    st.tolerance = options.solver.tolerance;
    st.relaxed = result.converged;
    st.warm = true;
    if (result.converged) st.relaxedSystem = system;
    return result;
}

std::uint64_t Document::hash() const { return hashSculpture(state_->current()); }

std::string Document::toLua() const { return journalToLua(state_->log); }

} // namespace netsculpt
