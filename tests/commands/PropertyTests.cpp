// Random command sequences (fixed seed), valid and invalid inputs mixed. After every sequence:
// undo all gives the empty sculpture, redo all the final one, and replaying the journal (and the
// compacted save) gives the final one, hash for hash. A failed command changes nothing.

#include "CommandTestSupport.h"

#include <chrono>
#include <limits>
#include <map>
#include <random>

using namespace netsculpt;
using namespace netsculpt::test;

namespace {

class RandomEditor {
  public:
    explicit RandomEditor(std::uint64_t seed) : random_(seed) {}

    int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random_); }
    double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random_); }
    bool chance(double p) { return real(0, 1) < p; }
    template <typename T> T oneOf(const std::vector<T>& values) { return values[std::size_t(pick(0, int(values.size()) - 1))]; }

    /// Mostly a live piece (one hanging from a piece when `child`), sometimes a removed,
    /// unknown or null id.
    PieceId piece(const Sculpture& s, bool child = false) {
        std::vector<PieceId> candidates;
        for (const auto& [id, p] : s.pieces)
            if (!child || !p.onRail()) candidates.push_back(id);
        if (candidates.empty() && child) return piece(s);
        if (!candidates.empty() && chance(0.93)) return oneOf(candidates);
        return PieceId(std::uint32_t(pick(0, int(s.nextPieceId) + 1)));
    }
    RailId rail(const Sculpture& s) {
        if (!s.rails.empty() && chance(0.93)) {
            auto it = s.rails.begin();
            std::advance(it, pick(0, int(s.rails.size()) - 1));
            return it->first;
        }
        return RailId(std::uint32_t(pick(0, int(s.nextRailId) + 1)));
    }
    double bar() { return oneOf<double>({0.05, 0.2, 0.3, 0.3, 0.45, 0.6, 0.6, 0.9, 1.2, -0.1, 0.0, std::nan("")}); }
    Gear gear() { return oneOf<Gear>({{1, 1}, {2, 1}, {3, 1}, {1, 2}, {1, 3}, {1, 1}, {2, 1}, {4, 1}, {2, 3}, {0, 1}}); }
    int rows() { return pick(-2, 40); }

    CurveSpec curve() {
        const int kind = pick(0, 9);
        if (kind <= 5) {
            CurveSpec spec = polygonRail(pick(5, 12), real(0.8, 1.6), kind == 0 ? 0.0 : real(2, 4));
            if (kind == 5) {
                spec.spline = true;
                spec.degree = pick(2, 3);
            }
            return spec;
        }
        if (kind == 9) { // invalid: a single point or a NaN
            CurveSpec spec = lineRail({0, 0, 3}, {chance(0.5) ? std::nan("") : 0.0, 0, 3});
            return spec;
        }
        const double half = real(0.5, 3);
        return lineRail({-half, real(-1, 1), 3}, {half, real(-1, 1), real(2.5, 3.5)});
    }

    /// The next action: a command (with a merge flag) or undo / redo / end of gesture.
    struct Action {
        enum Kind { Execute, Undo, Redo, EndGesture } kind = Execute;
        Command command;
        bool merge = false;
    };

    Action next(const Sculpture& s, std::size_t knots) {
        Action a;
        const bool big = knots > 2500;
        // a gesture: the last value-setting command again, with another value, merged
        if (gesture_ && chance(0.5)) {
            a.merge = chance(0.9);
            a.command = std::visit(
                [&](const auto& c) -> Command {
                    using T = std::decay_t<decltype(c)>;
                    if constexpr (std::is_same_v<T, SetRowsCommand>) return SetRowsCommand{c.piece, big ? pick(1, 5) : rows()};
                    else if constexpr (std::is_same_v<T, SetColumnsCommand>) return SetColumnsCommand{c.piece, pick(-1, 24)};
                    else if constexpr (std::is_same_v<T, SetGearCommand>) return SetGearCommand{c.piece, gear()};
                    else if constexpr (std::is_same_v<T, SetBarLengthCommand>) return SetBarLengthCommand{c.piece, c.column, c.row, bar()};
                    else return c;
                },
                *gesture_);
            return a;
        }
        gesture_.reset();
        const int roll = pick(0, 99);
        if (roll < 7) return {Action::Undo, {}, false};
        if (roll < 11) return {Action::Redo, {}, false};
        if (roll < 13) return {Action::EndGesture, {}, false};
        a.merge = chance(0.4);
        int what = big ? oneOf<int>({5, 12, 14, 15, 16, 17}) : pick(0, 19);
        if (what == 19) what = 4; // attach_to_piece twice as often
        if (s.rails.empty() && chance(0.7)) what = 0;
        else if (s.pieces.empty() && chance(0.6)) what = 2;
        switch (what) {
        case 0:
            a.command = AddRailCommand{s.rails.size() < 4 || chance(0.2) ? "r" : "extra", curve()};
            break;
        case 1: {
            ImportRailsCommand import{"import.csv", {}};
            for (int i = chance(0.1) ? 0 : pick(1, 2); i > 0; --i) import.rails.push_back({"imported", curve()});
            a.command = import;
            break;
        }
        case 2:
        case 3: {
            AttachToRailArgs args;
            args.rail = rail(s);
            if (chance(0.85)) args.columns = pick(-1, 20);
            else args.spacing = oneOf<double>({0.3, 0.5, -1.0, 0.0});
            args.rows = big ? pick(-1, 4) : std::min(rows(), 20);
            args.bar = bar();
            if (chance(0.2)) args.at = oneOf<double>({0.25, -0.1, std::nan("")});
            args.reverse = chance(0.3);
            a.command = AttachToRailCommand{args};
            break;
        }
        case 4: {
            AttachToPieceArgs args;
            args.parent = piece(s);
            args.gear = gear();
            args.rows = std::min(rows(), 20);
            args.bar = bar();
            a.command = AttachToPieceCommand{args};
            break;
        }
        case 5: a.command = SplitCommand{piece(s), pick(-1, 22)}; break;
        case 6:
        case 7: a.command = SetRowsCommand{piece(s), rows()}; break;
        case 8: a.command = SetColumnsCommand{piece(s), pick(-1, 24)}; break;
        case 9: a.command = SetGearCommand{piece(s, true), gear()}; break;
        case 10: {
            SetBarLengthCommand c{piece(s), std::nullopt, std::nullopt, bar()};
            const int mode = pick(0, 4);
            const auto it = s.pieces.find(c.piece);
            const int columns = it == s.pieces.end() ? 5 : it->second.columns;
            const int rowCount = it == s.pieces.end() ? 5 : it->second.rows;
            if (mode == 1) c.column = chance(0.5) ? 0 : columns - 1;
            if (mode == 2) c.column = pick(-1, columns + 1);
            if (mode == 3) c.row = chance(0.5) ? 0 : rowCount - 1;
            if (mode == 4) c.row = pick(-1, rowCount + 1);
            a.command = c;
            break;
        }
        case 11: a.command = ConnectToRailCommand{piece(s), rail(s), oneOf<double>({0, 0.1, 0.5, std::nan("")}), chance(0.5)}; break;
        case 12: a.command = DisconnectCommand{piece(s)}; break;
        case 13: {
            Material m;
            m.stiffness = oneOf<double>({2e5, 1e4, 3e5, -1});
            m.compressionRatio = oneOf<double>({0.01, 0.5, 0.0, 1.5});
            m.knotMass = oneOf<double>({0.002, 0, 0.01, -0.1});
            m.linearDensity = oneOf<double>({0.006, 0, 0.02});
            const double inf = std::numeric_limits<double>::infinity();
            if (chance(0.5))
                m.breakingLoad = oneOf<double>({3000, 450.5, 0, -2, inf});
            a.command = SetMaterialCommand{piece(s), m};
            break;
        }
        case 14: a.command = SetColourCommand{piece(s), Colour{real(0, 1), real(0, 1), real(-0.1, 1.1)}}; break;
        case 15:
            if (chance(0.5)) a.command = RenamePieceCommand{piece(s), chance(0.9) ? name("p", pick(0, 9)) : "a\nb"};
            else a.command = RenameRailCommand{rail(s), name("rail ", pick(0, 9))};
            break;
        case 16: a.command = RemovePieceCommand{piece(s)}; break;
        case 17: a.command = RemoveRailCommand{rail(s)}; break;
        default:
            a.command = SetGravityCommand{chance(0.9) ? Vec3{real(-1, 1), real(-1, 1), -9.81} : Vec3{0, 0, 0}};
            break;
        }
        const std::size_t kind = a.command.index();
        if (kind == Command(SetRowsCommand{}).index() || kind == Command(SetColumnsCommand{}).index() ||
            kind == Command(SetGearCommand{}).index() || kind == Command(SetBarLengthCommand{}).index())
            gesture_ = a.command;
        return a;
    }

  private:
    std::mt19937_64 random_;
    std::optional<Command> gesture_;

    static std::string name(const char* prefix, int n) {
        std::string out = prefix; // appended, not "literal" + std::string&& (GCC 12 -Wrestrict)
        out += std::to_string(n);
        return out;
    }
};

std::size_t knotsOf(const Sculpture& s) {
    std::size_t n = 0;
    for (const auto& [id, p] : s.pieces) n += std::size_t(p.rows) * std::size_t(p.columns);
    return n;
}

} // namespace

TEST_CASE("random command sequences undo, redo and replay bit for bit", "[property]") {
    const int sequences = 2000;
    const std::uint64_t emptyHash = hashSculpture(Sculpture{});
    RandomEditor editor(20240611);
    TempDir dir;
    std::map<std::string, std::pair<int, int>> outcomes; // command name -> (succeeded, refused)
    int undos = 0, merges = 0, longest = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int seq = 0; seq < sequences; ++seq) {
        INFO("sequence " << seq);
        const auto path = dir.path() / "s.netj";
        const bool journalFromStart = seq % 8 == 0;
        Document doc;
        if (journalFromStart) doc.attachJournal(path);
        const int length = editor.pick(8, 40);
        for (int i = 0; i < length; ++i) {
            const auto action = editor.next(doc.sculpture(), knotsOf(doc.sculpture()));
            const std::uint64_t before = doc.hash();
            try {
                switch (action.kind) {
                case RandomEditor::Action::Undo:
                    if (doc.canUndo()) ++undos;
                    doc.undo();
                    break;
                case RandomEditor::Action::Redo: doc.redo(); break;
                case RandomEditor::Action::EndGesture: doc.endGesture(); break;
                case RandomEditor::Action::Execute:
                    doc.execute(action.command, action.merge);
                    ++outcomes[commandName(action.command)].first;
                    break;
                }
            } catch (const UserError&) {
                if (action.kind == RandomEditor::Action::Execute) ++outcomes[commandName(action.command)].second;
                REQUIRE(doc.hash() == before);
            }
        }
        const std::uint64_t finalHash = doc.hash();
        const CompiledSculpture finalSystem = doc.compiled();

        // replay of the journal: appended entry by entry, or written whole by attachJournal
        if (!journalFromStart) doc.attachJournal(path);
        {
            Document replayed = Document::open(path);
            REQUIRE(replayed.hash() == finalHash);
            if (seq % 16 == 1) requireSameSystem(replayed.compiled(), finalSystem);
            for (const JournalEntry& e : entriesOf(path)) merges += e.merge;
        }
        if (seq % 10 == 3) {
            doc.save(dir / "compact.netj");
            REQUIRE(Document::open(dir / "compact.netj").hash() == finalHash);
        }
        (void)doc.toLua();

        // undo all, then redo as many
        int depth = 0;
        while (doc.canUndo()) {
            doc.undo();
            ++depth;
        }
        longest = std::max(longest, depth);
        REQUIRE(doc.hash() == emptyHash);
        for (int i = 0; i < depth; ++i) doc.redo();
        REQUIRE(doc.hash() == finalHash);
        // the journal now holds those undos and redos too, and still replays to the same model
        if (seq % 4 == 0) REQUIRE(Document::open(path).hash() == finalHash);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    int succeeded = 0, refused = 0;
    for (const auto& [name, counts] : outcomes) {
        INFO(name << ": " << counts.first << " applied, " << counts.second << " refused");
        CHECK(counts.first > 0);
        if (name != "rename_rail") CHECK(counts.second > 0); // rename_rail fails only for a bad id
        succeeded += counts.first;
        refused += counts.second;
    }
    WARN(sequences << " sequences: " << succeeded << " commands applied, " << refused << " refused, " << undos
                   << " undos, " << merges << " merged entries, longest history " << longest << "; " << seconds
                   << " s");
    CHECK(outcomes.size() == std::variant_size_v<Command>);
    CHECK(merges > 0);
}
