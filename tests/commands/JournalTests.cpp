// The journal file: its format, replay (bit for bit, ids checked), torn and garbled entries,
// versions, compaction on save, snapshots, and the Lua export.

#include "CommandTestSupport.h"
#include "commands/JsonCodec.h"
#include "physics/Forces.h"

#include <random>

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

std::vector<std::string> linesOf(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t pos = 0;
    while (pos < text.size()) {
        const std::size_t end = text.find('\n', pos);
        lines.push_back(text.substr(pos, end - pos));
        if (end == std::string::npos) break;
        pos = end + 1;
    }
    return lines;
}

/// Re-signs a hand-edited entry line ("<crc> <json>") so that only its content is wrong.
std::string resign(const std::string& line) {
    const std::string json = line.substr(9);
    char crc[9];
    std::snprintf(crc, sizeof crc, "%08x", crc32(json));
    return std::string(crc) + " " + json;
}

std::string joinLines(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines) out += l + "\n";
    return out;
}

/// A document with a journal of 12 entries: rails, pieces, a split, a merged gesture, undo, redo.
Document journaledDocument(const std::filesystem::path& path) {
    Document doc;
    doc.attachJournal(path);
    doc.execute(AddRailCommand{"top", polygonRail(12, 1.0, 3.0)});
    doc.execute(AddRailCommand{"bottom", polygonRail(12, 1.0, 0.0)});
    doc.execute(attach(1, 12, 6, 0.4));
    doc.execute(hang(1, Gear{2, 1}, 3, 0.3));
    doc.execute(SetRowsCommand{PieceId(2), 4}, true);
    doc.execute(SetRowsCommand{PieceId(2), 5}, true);
    doc.undo();
    doc.redo();
    doc.execute(SplitCommand{PieceId(1), 4});
    doc.execute(SetGravityCommand{Vec3{0.1, -0.2, -9.80665}});
    doc.execute(RenamePieceCommand{PieceId(3), "left \"half\" \\ é"});
    doc.execute(SetBarLengthCommand{PieceId(1), 4, std::nullopt, 0.45});
    return doc;
}

} // namespace

TEST_CASE("the journal is a header and one checksummed JSON line per entry") {
    TempDir dir;
    const auto path = dir / "j.netj";
    Document doc = journaledDocument(path);
    const std::vector<std::string> lines = linesOf(readBytes(path));
    REQUIRE(lines.size() == 13);
    CHECK(lines[0] == "netsculpt-journal 1");
    for (std::size_t i = 1; i < lines.size(); ++i) {
        INFO(lines[i]);
        REQUIRE(lines[i].size() > 10);
        CHECK(lines[i][8] == ' ');
        CHECK(resign(lines[i]) == lines[i]);
        CHECK_THAT(lines[i], Contains("{\"seq\":" + std::to_string(i) + ","));
    }
    CHECK_THAT(lines[3], Contains("\"cmd\":\"attach_to_rail\",\"args\":{\"rail\":1,\"columns\":12,\"rows\":6,"
                                  "\"bar\":0.4,\"at\":0.0,\"reverse\":false},\"created\":{\"pieces\":[1]}}"));
    CHECK_THAT(lines[5], Contains("\"cmd\":\"set_rows\",\"args\":{\"piece\":2,\"rows\":4}}"));
    CHECK_THAT(lines[6], Contains("\"args\":{\"piece\":2,\"rows\":5},\"merge\":true}"));
    CHECK_THAT(lines[7], Contains("{\"seq\":7,\"cmd\":\"undo\"}"));
    CHECK_THAT(lines[8], Contains("{\"seq\":8,\"cmd\":\"redo\"}"));
    CHECK_THAT(lines[9], Contains("\"created\":{\"pieces\":[1,3]}"));
    CHECK_THAT(lines[10], Contains("\"gravity\":[0.1,-0.2,-9.80665]"));
    CHECK_THAT(lines[11], Contains("\"name\":\"left \\\"half\\\" \\\\ \\u00e9\""));
    CHECK_THAT(lines[12], Contains("\"column\":4,\"length\":0.45"));

    SECTION("replay rebuilds the same model and the same undo history") {
        std::vector<std::string> warnings;
        Document replayed = Document::open(path, &warnings);
        CHECK(warnings.empty());
        CHECK(replayed.hash() == doc.hash());
        CHECK(replayed.isClean());
        requireSameSystem(replayed.compiled(), doc.compiled());
        while (doc.canUndo()) {
            REQUIRE(replayed.canUndo());
            doc.undo();
            replayed.undo();
            CHECK(replayed.hash() == doc.hash());
        }
        CHECK_FALSE(replayed.canUndo());
        CHECK(replayed.hash() == hashSculpture(Sculpture{}));
    }
    SECTION("the reopened journal keeps appending") {
        {
            Document replayed = Document::open(path);
            replayed.execute(SetRowsCommand{PieceId(1), 7});
            replayed.undo();
        }
        const auto entries = entriesOf(path);
        REQUIRE(entries.size() == 14);
        CHECK(entries[12].seq == 13);
        CHECK(entries[13].kind == JournalEntry::Kind::Undo);
        CHECK(Document::open(path).hash() == doc.hash());
    }
}

TEST_CASE("numbers in the journal read back bit for bit") {
    // Gravity carries numbers of every exponent down to the smallest subnormal in components
    // that leave its magnitude in range; rail points carry large ones (up to 1e150, so that a
    // polyline's length stays finite).
    TempDir dir;
    const auto path = dir / "numbers.netj";
    std::mt19937_64 random(12345);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-300, 300);
    Document doc;
    doc.attachJournal(path);
    std::vector<Vec3> written;
    for (int i = 0; i < 300; ++i) {
        Vec3 g{uniform(random) * std::ldexp(1.0, exponent(random) / 4 - 75), uniform(random),
               -(1.5 + uniform(random)) * std::pow(10.0, exponent(random) / 150)};
        if (i == 0) g = {-0.0, 0.0, -9.81};
        if (i == 1) g = {5e-324, -2.2250738585072014e-308, -999.9999999999999};
        if (i == 2) g = {0.1 + 0.2, 1.0 / 3.0, -2.0 / 3.0};
        doc.execute(SetGravityCommand{g});
        written.push_back(g);
    }
    std::vector<Vec3> far;
    for (int i = 0; i < 30; ++i) {
        const double scale = std::pow(10.0, exponent(random) / 2);
        far.push_back({uniform(random) * scale, uniform(random) * scale, uniform(random)});
        if (i == 0) far.back() = {1e150, -1.2345678901234567e149, 1.7976931348623157e-150};
        CurveSpec line;
        line.points = {{0, 0, 0}, far.back()};
        doc.execute(AddRailCommand{"far " + std::to_string(i), line});
    }
    const auto entries = entriesOf(path);
    REQUIRE(entries.size() == written.size() + far.size());
    for (std::size_t i = 0; i < written.size(); ++i)
        CHECK(sameBits(std::get<SetGravityCommand>(entries[i].command).gravity, written[i]));
    for (std::size_t i = 0; i < far.size(); ++i) {
        const auto& rail = std::get<AddRailCommand>(entries[written.size() + i].command);
        CHECK(sameBits(rail.curve.points.back(), far[i]));
    }
    CHECK(Document::open(path).hash() == doc.hash());
}

TEST_CASE("a torn last entry is dropped with a warning at every byte, and appending continues") {
    TempDir dir;
    const auto path = dir / "j.netj";
    const std::uint64_t fullHash = journaledDocument(path).hash();
    const std::string full = readBytes(path);
    const std::size_t lastStart = full.rfind('\n', full.size() - 2) + 1;
    // the expected document without its last entry
    std::string withoutLast = full.substr(0, lastStart);
    writeBytes(dir / "ref.netj", withoutLast);
    const std::uint64_t shortHash = Document::open(dir / "ref.netj").hash();
    REQUIRE(shortHash != fullHash);

    for (std::size_t cut = lastStart; cut < full.size(); ++cut) {
        INFO("cut at byte " << cut << " of " << full.size());
        writeBytes(path, full.substr(0, cut));
        std::vector<std::string> warnings;
        Document doc = Document::open(path, &warnings);
        CHECK(doc.hash() == shortHash);
        if (cut == lastStart) {
            CHECK(warnings.empty());
        } else {
            REQUIRE(warnings.size() == 1);
            CHECK_THAT(warnings[0], Contains("line 13") && Contains("torn"));
        }
        // the tail is cut off the file before anything is appended
        CHECK(readBytes(path) == withoutLast);
        doc.execute(SetColourCommand{PieceId(1), Colour{0.5, 0.5, 0.5}});
        std::vector<std::string> again;
        const Document reopened = Document::open(path, &again);
        CHECK(again.empty());
        CHECK(reopened.hash() == doc.hash());
    }
    // the complete file once more
    writeBytes(path, full);
    std::vector<std::string> warnings;
    CHECK(Document::open(path, &warnings).hash() == fullHash);
    CHECK(warnings.empty());
}

TEST_CASE("a garbled last entry is dropped - a garbled entry elsewhere is an error with its line") {
    TempDir dir;
    const auto path = dir / "j.netj";
    journaledDocument(path);
    const std::vector<std::string> lines = linesOf(readBytes(path));

    SECTION("bad checksum on the last line: dropped with a warning naming it") {
        auto edited = lines;
        edited[12][20] ^= 1;
        writeBytes(path, joinLines(edited));
        std::vector<std::string> warnings;
        Document doc = Document::open(path, &warnings);
        REQUIRE(warnings.size() == 1);
        CHECK_THAT(warnings[0], Contains("line 13") && Contains("checksum"));
        CHECK(entriesOf(path).size() == 11);
    }
    SECTION("bad JSON on the last line, even if re-signed: dropped with a warning") {
        auto edited = lines;
        edited[12] = resign(edited[12].substr(0, edited[12].size() - 3));
        writeBytes(path, joinLines(edited));
        std::vector<std::string> warnings;
        Document doc = Document::open(path, &warnings);
        REQUIRE(warnings.size() == 1);
        CHECK_THAT(warnings[0], Contains("line 13") && Contains("JSON"));
        CHECK(entriesOf(path).size() == 11);
    }
    SECTION("a damaged line end before the last line: both entries dropped, and the warning "
            "says two") {
        auto edited = lines;
        edited[11] += "\v" + edited[12];
        edited.pop_back();
        writeBytes(path, joinLines(edited));
        std::vector<std::string> warnings;
        Document doc = Document::open(path, &warnings);
        REQUIRE(warnings.size() == 1);
        CHECK_THAT(warnings[0], Contains("line 12") && Contains("the text of 2 entries"));
        CHECK(entriesOf(path).size() == 10);
    }
    SECTION("bad JSON elsewhere, even if re-signed, is an error") {
        auto edited = lines;
        edited[6] = resign(edited[6].substr(0, edited[6].size() - 1));
        writeBytes(path, joinLines(edited));
        REQUIRE_THROWS_WITH(Document::open(path), Contains("line 7:") && Contains("JSON"));
    }
    for (int line : {2, 6, 9, 12}) {
        SECTION("bad checksum on line " + std::to_string(line)) {
            auto edited = lines;
            edited[std::size_t(line) - 1][30] ^= 4;
            const std::string bytes = joinLines(edited);
            writeBytes(path, bytes);
            REQUIRE_THROWS_WITH(Document::open(path), Contains("line " + std::to_string(line) + ":") &&
                                                          Contains("checksum"));
            CHECK(readBytes(path) == bytes); // a failed open changes nothing
        }
    }
    SECTION("a missing line is a sequence error") {
        auto edited = lines;
        edited.erase(edited.begin() + 4);
        writeBytes(path, joinLines(edited));
        REQUIRE_THROWS_WITH(Document::open(path), Contains("line 5") && Contains("sequence number 5, expected 4"));
    }
    SECTION("a blank line in the middle") {
        auto edited = lines;
        edited.insert(edited.begin() + 3, "");
        writeBytes(path, joinLines(edited));
        REQUIRE_THROWS_WITH(Document::open(path), Contains("line 4"));
    }
    SECTION("an unknown command or argument, correctly signed") {
        auto edited = lines;
        std::string& l = edited[4];
        l.replace(l.find("attach_to_piece"), 15, "attach_to_plece");
        l = resign(l);
        writeBytes(path, joinLines(edited));
        REQUIRE_THROWS_WITH(Document::open(path), Contains("line 5") && Contains("attach_to_plece"));
        edited = lines;
        std::string& m = edited[3];
        m.replace(m.find("\"reverse\":false}"), 16, "\"reverse\":false,\"rowz\":3}");
        m = resign(m);
        writeBytes(path, joinLines(edited));
        REQUIRE_THROWS_WITH(Document::open(path), Contains("line 4") && Contains("rowz"));
    }
    SECTION("a number beyond a double's range, correctly signed, is an error naming the line") {
        auto edited = lines;
        std::string& l = edited[3];
        l.replace(l.find("\"bar\":0.4"), 9, "\"bar\":1e400");
        l = resign(l);
        const std::string bytes = joinLines(edited);
        writeBytes(path, bytes);
        REQUIRE_THROWS_WITH(Document::open(path), Contains("line 4:") && Contains("bad JSON") &&
                                                      Contains("1e400"));
        CHECK(readBytes(path) == bytes);
    }
    SECTION("a created id that does not match is an error naming the entry") {
        auto edited = lines;
        std::string& l = edited[3];
        l.replace(l.find("\"pieces\":[1]"), 12, "\"pieces\":[9]");
        l = resign(l);
        writeBytes(path, joinLines(edited));
        REQUIRE_THROWS_WITH(Document::open(path), Contains("line 4 (attach_to_rail)") && Contains("piece 1") &&
                                                      Contains("piece 9"));
    }
    SECTION("a command that no longer applies is an error naming the entry") {
        auto edited = lines;
        std::string& l = edited[4];
        l.replace(l.find("\"rows\":3"), 8, "\"rows\":0");
        l = resign(l);
        writeBytes(path, joinLines(edited));
        REQUIRE_THROWS_WITH(Document::open(path), Contains("line 5 (attach_to_piece)") && Contains("got 0"));
    }
}

TEST_CASE("journal versions and headers") {
    TempDir dir;
    const auto path = dir / "j.netj";
    journaledDocument(path);
    std::string bytes = readBytes(path);
    SECTION("a newer format is refused") {
        writeBytes(path, "netsculpt-journal 2" + bytes.substr(bytes.find('\n')));
        REQUIRE_THROWS_WITH(Document::open(path), Contains("journal format 2 is newer than this netsculpt (reads 1)"));
        REQUIRE_THROWS_WITH(Document::load(path), Contains("journal format 2 is newer than this netsculpt (reads 1)"));
    }
    SECTION("not a journal") {
        writeBytes(path, "hello\nworld\n");
        REQUIRE_THROWS_WITH(Document::open(path), Contains("not a netsculpt journal"));
    }
    SECTION("an empty or torn-header file starts afresh, with a warning") {
        for (std::string start : {std::string(), std::string("netsc"), std::string("netsculpt-journal 1")}) {
            writeBytes(path, start);
            std::vector<std::string> warnings;
            Document doc = Document::open(path, &warnings);
            CHECK(warnings.size() == 1);
            CHECK(doc.hash() == hashSculpture(Sculpture{}));
            doc.execute(AddRailCommand{"r", polygonRail(5, 1, 1)});
            CHECK(entriesOf(path).size() == 1);
            CHECK_THAT(readBytes(path), StartsWith("netsculpt-journal 1\n"));
        }
    }
    SECTION("a missing file is an error that says so") {
        REQUIRE_THROWS_AS(Document::open(dir / "missing.netj"), UserError);
        // The studio's --open and File > Open said only "cannot open PATH".
        REQUIRE_THROWS_WITH(Document::load(dir / "missing.netj"),
                            Contains("missing.netj: No such file or directory"));
    }
}

TEST_CASE("save writes the compacted history - saveSnapshot the model and shape") {
    TempDir dir;
    Document doc = journaledDocument(dir / "j.netj");
    doc.execute(SetRowsCommand{PieceId(2), 9});
    doc.undo(); // a redo branch, which save drops
    const std::uint64_t hash = doc.hash();

    SECTION("compacted journal") {
        doc.save(dir / "saved.netj");
        CHECK(doc.isClean());
        const auto entries = entriesOf(dir / "saved.netj");
        // 12 entries minus the undo/redo pair, minus nothing else: the merged set_rows stays merged
        REQUIRE(entries.size() == 10);
        for (const auto& e : entries) CHECK(e.kind == JournalEntry::Kind::Command);
        CHECK_FALSE(entries[4].merge);
        CHECK(entries[5].merge);
        Document reopened = Document::open(dir / "saved.netj");
        CHECK(reopened.hash() == hash);
        CHECK_FALSE(reopened.canRedo());
        int steps = 0;
        while (reopened.canUndo()) {
            reopened.undo();
            ++steps;
        }
        CHECK(steps == 9);
        // the attached journal is untouched and still attached
        CHECK(entriesOf(dir / "j.netj").size() == 14);
        doc.execute(SetRowsCommand{PieceId(2), 2});
        CHECK(entriesOf(dir / "j.netj").size() == 15);
    }
    SECTION("saving onto the attached journal compacts it and keeps appending") {
        doc.save(dir / "j.netj");
        CHECK(entriesOf(dir / "j.netj").size() == 10);
        CHECK_FALSE(doc.canRedo());
        doc.execute(SetRowsCommand{PieceId(2), 2});
        doc.undo();
        CHECK(entriesOf(dir / "j.netj").size() == 12);
        CHECK(Document::open(dir / "j.netj").hash() == hash);
    }
    SECTION("snapshot") {
        DocumentRelaxOptions options;
        options.solver.maxSteps = 500; // not converged: only the shape matters here
        doc.relax(options);
        doc.saveSnapshot(dir / "snap.nets");
        CHECK_THAT(readBytes(dir / "snap.nets"), StartsWith("netsculpt-snapshot 5\n"));
        std::vector<std::string> warnings;
        Document loaded = Document::load(dir / "snap.nets", &warnings);
        CHECK(warnings.empty());
        CHECK(loaded.hash() == hash);
        requireSameSystem(loaded.compiled(), doc.compiled());
        CHECK(loaded.isRelaxed() == doc.isRelaxed());
        CHECK(loaded.canUndo());
        loaded.save(dir / "from-snapshot.netj");
        CHECK(Document::load(dir / "from-snapshot.netj").hash() == hash);
        // a newer snapshot format and an inconsistent one are refused
        std::string bytes = readBytes(dir / "snap.nets");
        writeBytes(dir / "v6.nets", "netsculpt-snapshot 6" + bytes.substr(bytes.find('\n')));
        CHECK_THROWS_WITH(Document::load(dir / "v6.nets"), Contains("snapshot format 6 is newer"));
        const std::size_t at = bytes.find("\"next_piece_id\":") + 16;
        bytes[at] = bytes[at] == '9' ? '8' : '9';
        writeBytes(dir / "bad.nets", bytes);
        CHECK_THROWS_WITH(Document::load(dir / "bad.nets"), Contains("inconsistent"));
    }
}

TEST_CASE("a snapshot holding a number beyond a double's range is refused as damaged") {
    TempDir dir;
    journaledDocument(dir / "j.netj").saveSnapshot(dir / "snap.nets");
    std::string bytes = readBytes(dir / "snap.nets");
    const std::size_t first = bytes.find("\"positions\":[") + 13;
    bytes.replace(first, bytes.find(',', first) - first, "-1e400");
    writeBytes(dir / "snap.nets", bytes);
    REQUIRE_THROWS_WITH(Document::load(dir / "snap.nets"),
                        Contains("snap.nets: the snapshot is damaged (bad JSON") &&
                            Contains("-1e400"));
}

TEST_CASE("arrays nested 100,000 deep in a journal or a snapshot are refused as damaged") {
    // nlohmann's copy and dump recurse once per level: this overflowed the stack.
    TempDir dir;
    Document saved = journaledDocument(dir / "j.netj");
    saved.saveSnapshot(dir / "snap.nets");
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    std::vector<std::string> lines = linesOf(readBytes(dir / "j.netj"));
    std::string& l = lines[3];
    l.replace(l.find("\"rows\":6"), 8, "\"rows\":" + deep);
    l = resign(l);
    const std::string bytes = joinLines(lines);
    writeBytes(dir / "j.netj", bytes);
    REQUIRE_THROWS_WITH(Document::open(dir / "j.netj"),
                        Contains("line 4:") && Contains("bad JSON") &&
                            Contains("nested more than 100 levels deep"));
    CHECK(readBytes(dir / "j.netj") == bytes);

    std::string snapshot = readBytes(dir / "snap.nets");
    snapshot.replace(snapshot.find("\"rows\":6"), 8, "\"rows\":" + deep);
    writeBytes(dir / "snap.nets", snapshot);
    REQUIRE_THROWS_WITH(Document::load(dir / "snap.nets"),
                        Contains("snap.nets: the snapshot is damaged (bad JSON") &&
                            Contains("nested more than 100 levels deep"));

    // Brackets inside a string are text, not nesting.
    Document named;
    named.execute(AddRailCommand{"[{" + std::string(150, '[') + "\\\"", polygonRail(12, 1.0, 3.0)});
    named.save(dir / "named.netj");
    CHECK(Document::open(dir / "named.netj").hash() == named.hash());
}

TEST_CASE("a snapshot whose knots are too far apart for their forces starts from Eq. 2") {
    TempDir dir;
    Document saved = journaledDocument(dir / "j.netj");
    saved.saveSnapshot(dir / "snap.nets");
    std::string bytes = readBytes(dir / "snap.nets");
    const std::size_t first = bytes.find("\"positions\":[") + 13;
    bytes.replace(first, bytes.find(',', first) - first, "1e200"); // a bar's length squared: inf
    writeBytes(dir / "snap.nets", bytes);
    std::vector<std::string> warnings;
    const Document loaded = Document::load(dir / "snap.nets", &warnings);
    REQUIRE(warnings.size() == 1);
    CHECK_THAT(warnings[0], Contains("snap.nets: the saved shape's knots are too far apart"));
    CHECK(loaded.hash() == saved.hash()); // the model and its history are kept
    CHECK(loaded.compiled().system.position == saved.compiled().system.position);
    CHECK(std::isfinite(residual(loaded.compiled().system)));
}

TEST_CASE("a relaxed snapshot whose shape was edited or damaged opens as not relaxed, from Eq. 2") {
    TempDir dir;
    Document saved = journaledDocument(dir / "j.netj");
    const std::vector<Vec3> initial = saved.compiled().system.position;
    DocumentRelaxOptions options;
    options.solver.maxSeconds = 30;
    REQUIRE(saved.relax(options).converged);
    saved.saveSnapshot(dir / "snap.nets");
    const std::string bytes = readBytes(dir / "snap.nets");
    REQUIRE(Document::load(dir / "snap.nets").isRelaxed());
    // Replaces number `index` of the array after `"key":[` and loads the file: one warning that
    // says `why`, the model kept, the shape the initial geometry, not relaxed.
    const auto damaged = [&](const std::string& key, std::size_t index, double change,
                             const std::string& why) {
        std::string text = bytes;
        std::size_t at = text.find("\"" + key + "\":[") + key.size() + 4;
        for (std::size_t n = 0; n < index; ++n) at = text.find(',', at) + 1;
        const std::size_t end = text.find_first_of(",]", at);
        const double value = std::stod(text.substr(at, end - at));
        text.replace(at, end - at, formatNumber(change == 0 ? 1e308 : value + change));
        writeBytes(dir / "damaged.nets", text);
        std::vector<std::string> warnings;
        const Document loaded = Document::load(dir / "damaged.nets", &warnings);
        INFO(key << "[" << index << "] + " << change);
        REQUIRE(warnings.size() == 1);
        CHECK_THAT(warnings[0], Contains(why));
        CHECK_FALSE(loaded.isRelaxed());
        CHECK(loaded.hash() == saved.hash()); // the model and its history are kept
        CHECK(loaded.compiled().system.position == initial);
    };
    const auto& fixed = saved.compiled().system.fixed;
    const std::size_t free = std::size_t(std::find(fixed.begin(), fixed.end(), 0) - fixed.begin());
    // A free knot half a metre lower: no longer in balance.
    damaged("positions", 3 * free + 2, -0.5, "not the equilibrium it was saved as");
    // The origin moved: every knot with it, the held ones off their rails.
    damaged("origin", 0, 0.5, "knots held by rails are not where the rails hold them");
    damaged("origin", 0, 0, "knots held by rails are not where the rails hold them"); // 1e308
}

TEST_CASE("a snapshot relaxed in a wind opens relaxed, with its wind") {
    TempDir dir;
    Document doc;
    addRingWithTube(doc, {0, 0, 0}, 1);
    DocumentRelaxOptions options;
    options.solver.maxSeconds = 30;
    options.solver.wind = Wind{{1, 0, 0}, 0.05};
    REQUIRE(doc.relax(options).converged);
    doc.saveSnapshot(dir / "windy.nets");
    std::vector<std::string> warnings;
    const Document loaded = Document::load(dir / "windy.nets", &warnings);
    CHECK(warnings.empty());
    CHECK(loaded.isRelaxed());
    REQUIRE(loaded.shapeWind().has_value());
    CHECK(loaded.shapeWind()->pressure == 0.05);
    requireSameSystem(loaded.compiled(), doc.compiled());
}

TEST_CASE("a journal becomes the equivalent Lua script") {
    TempDir dir;
    Document doc = journaledDocument(dir / "j.netj");
    doc.execute(ImportRailsCommand{"rails/ring.csv", {{"imported", lineRail({0, 0, 4}, {1, 0.5, 4})}}});
    CurveSpec spline = polygonRail(6, 1.5, 5);
    spline.spline = true;
    spline.degree = 2;
    spline.sampling = Sampling::Parameter;
    doc.execute(AddRailCommand{"spline", spline});
    doc.execute(SetGearCommand{PieceId(2), Gear{3, 1}}, true);
    doc.execute(hang(1, Gear{1, 2}, 2, 0.6));
    doc.execute(SetColourCommand{PieceId(1), Colour{0.25, 0.5, 1}});
    doc.execute(ConnectToRailCommand{PieceId(2), RailId(2), 0.125, true});
    doc.undo();
    const std::string lua = doc.toLua();
    INFO(lua);
    CHECK_THAT(lua, StartsWith("-- Generated by netsculpt"));
    CHECK_THAT(lua, Contains("local ns = require \"netsculpt\"\nlocal doc = ns.new()\n"));
    CHECK_THAT(lua, Contains("local r1 = doc:add_rail{name = \"top\", points = {{1.0, 0.0, 3.0}, "));
    CHECK_THAT(lua, Contains(", closed = true}\n"));
    CHECK_THAT(lua, Contains("local p1 = doc:attach_to_rail{rail = r1, columns = 12, rows = 6, bar = 0.4}\n"));
    // an entry without a material gave the default rope, which the call is told (else: the
    // parent's)
    CHECK_THAT(
        lua, Contains("local p2 = doc:attach_to_piece{piece = p1, gear = 2, rows = 3, bar = 0.3, "
                      "material = {stiffness = 2e+05, compression_ratio = 0.01, knot_mass = 0.002, "
                      "linear_density = 0.006}}\n"));
    CHECK_THAT(lua, Contains("doc:set_rows{piece = p2, rows = 4}\ndoc:set_rows{piece = p2, rows = 5}\n"
                             "doc:undo()\ndoc:undo()\ndoc:redo()\ndoc:redo()\n")); // the merged step is two calls
    CHECK_THAT(lua, Contains("local _, p3 = doc:split{piece = p1, column = 4}\n"));
    CHECK_THAT(lua, Contains("doc:set_gravity{x = 0.1, y = -0.2, z = -9.80665}\n"));
    CHECK_THAT(lua, Contains("doc:rename{piece = p3, name = \"left \\\"half\\\" \\\\ é\"}\n"));
    CHECK_THAT(lua, Contains("doc:set_bar_length{piece = p1, column = 4, length = 0.45}\n"));
    CHECK_THAT(lua, Contains("-- import_rails(\"rails/ring.csv\")"));
    CHECK_THAT(lua, Contains("local r3 = doc:add_rail{name = \"imported\", points = {{0.0, 0.0, 4.0}, {1.0, 0.5, 4.0}}, "
                             "closed = false}\n"));
    CHECK_THAT(lua, Contains("local r4 = doc:add_rail{name = \"spline\", control = {{1.5, 0.0, 5.0}, "));
    CHECK_THAT(lua, Contains(", degree = 2, closed = true, sampling = \"parameter\"}\n"));
    CHECK_THAT(lua, Contains("doc:set_gear{piece = p2, gear = 3}\n"));
    CHECK_THAT(
        lua,
        Contains("local p4 = doc:attach_to_piece{piece = p1, gear = \"1/2\", rows = 2, bar = 0.6, "
                 "material = {"));
    CHECK_THAT(lua, Contains("doc:set_colour{piece = p1, colour = {0.25, 0.5, 1.0}}\n"));
    CHECK_THAT(lua, Contains("doc:connect_to_rail{piece = p2, rail = r2, at = 0.125, reverse = true}\ndoc:undo()\n"));
    CHECK_THAT(lua, Contains("\nreturn doc\n"));
    // the journal read back from the file gives the same script
    CHECK(journalToLua(entriesOf(dir / "j.netj")) == lua);
}

TEST_CASE("a long journal's Lua keeps handles in tables (Lua allows 200 locals)") {
    Document doc;
    doc.execute(AddRailCommand{"top", polygonRail(12, 1.0, 3.0)});
    for (int i = 0; i < 160; ++i) doc.execute(attach(1, 6, 1, 0.6));
    doc.execute(RemovePieceCommand{PieceId(160)});
    const std::string lua = doc.toLua();
    CHECK_THAT(lua, Contains("local rail, piece = {}, {}\n"));
    CHECK_THAT(lua, Contains("piece[160] = doc:attach_to_rail{rail = rail[1], columns = 6, rows = 1, bar = 0.6}\n"));
    CHECK_THAT(lua, Contains("doc:remove_piece{piece = piece[160]}\n"));
}

TEST_CASE("format 1 journals written by this version keep opening, byte for byte") {
    const std::filesystem::path data = std::filesystem::path(NETSCULPT_SOURCE_DIR) / "tests/data/journals";
    TempDir dir;
    const auto path = dir / "example.netj";
    std::filesystem::copy_file(data / "example-v1.netj", path); // opening may append or cut: use a copy
    const std::string bytes = readBytes(path);
    std::vector<std::string> warnings;
    Document doc = Document::open(path, &warnings);
    CHECK(warnings.empty());
    const Sculpture& s = doc.sculpture();
    REQUIRE(s.rails.size() == 1);
    REQUIRE(s.pieces.size() == 3);
    CHECK(s.pieces.at(PieceId(2)).rows == 6);                      // the merged gesture, redone
    CHECK(s.pieces.at(PieceId(2)).parentTop().gear == Gear{1, 2});
    CHECK(s.pieces.at(PieceId(1)).columns == 5);                   // split at column 4 of 12
    CHECK(s.pieces.at(PieceId(3)).columns == 9);
    CHECK(sameBits(s.gravity, Vec3{0, 0.1, -9.80665}));
    CHECK(doc.compiled().system.knotCount() == 12 * 6 + 6 * 6 - 6);
    // this version writes the very same bytes for the same entries
    std::string rewritten = journalHeader();
    for (const JournalEntry& e : entriesOf(path)) rewritten += encodeJournalLine(e);
    CHECK(rewritten == bytes);
    int steps = 0;
    while (doc.canUndo()) {
        doc.undo();
        ++steps;
    }
    CHECK(steps == 6); // rail, piece, child, the set_rows gesture, split, gravity

    SECTION("the same journal torn in its last entry") {
        std::filesystem::copy_file(data / "example-v1-torn.netj", dir / "torn.netj");
        std::vector<std::string> tornWarnings;
        Document torn = Document::open(dir / "torn.netj", &tornWarnings);
        REQUIRE(tornWarnings.size() == 1);
        CHECK_THAT(tornWarnings[0], Contains("line 10") && Contains("torn"));
        CHECK(sameBits(torn.sculpture().gravity, Vec3{0, 0, -9.81}));
        CHECK(torn.sculpture().pieces.size() == 3);
    }
}

TEST_CASE("a sculpture in site coordinates relaxes to the tolerance, and its snapshot keeps the "
          "shape to the last bit, and a format 1 snapshot still opens") {
    TempDir dir;
    const Vec3 site{512345.678, 5412345.678, 231.5};
    Document doc;
    addRingWithTube(doc, site, 1);
    const DocumentRelaxOptions options;
    const RelaxResult relaxed = doc.relax(options);
    INFO(relaxed.stopReason << ", residual " << relaxed.residual);
    REQUIRE(relaxed.converged);
    CHECK(doc.compiled().system.origin == Vec3{512346, 5412346, 232});
    CHECK(residual(doc.compiled().system) < 1e-6);

    doc.saveSnapshot(dir / "site.nets");
    Document loaded = Document::load(dir / "site.nets");
    requireSameSystem(loaded.compiled(), doc.compiled());
    CHECK(loaded.isRelaxed());
    CHECK(residual(loaded.compiled().system) == residual(doc.compiled().system));

    // Format 1 wrote the sculpture's coordinates and no origin: they are moved to the origin.
    const std::string bytes = readBytes(dir / "site.nets");
    const std::size_t shape = bytes.find("\"shape\":");
    REQUIRE(shape != std::string::npos);
    const MassSpringSystem& system = doc.compiled().system;
    std::string positions;
    for (std::size_t k = 0; k < system.knotCount(); ++k)
        for (double v : {system.worldPosition(k).x, system.worldPosition(k).y,
                         system.worldPosition(k).z})
            positions.append(positions.empty() ? "" : ",")
                .append(codec::number(v, "a position").dump());
    writeBytes(dir / "v1.nets", "netsculpt-snapshot 1" +
                                    bytes.substr(bytes.find('\n'), shape - bytes.find('\n')) +
                                    "\"shape\":{\"positions\":[" + positions +
                                    "],\"relaxed\":true,\"warm\":true}}\n");
    std::vector<std::string> warnings;
    const Document old = Document::load(dir / "v1.nets", &warnings);
    CHECK(warnings.empty());
    REQUIRE(old.compiled().system.knotCount() == system.knotCount());
    double worst = 0;
    for (std::size_t k = 0; k < system.knotCount(); ++k)
        worst = std::max(worst, distance(old.compiled().system.position[k], system.position[k]));
    CHECK(worst > 0);       // rounded to the site's coordinates on the way ...
    CHECK(worst < 1e-9);    // ... by at most half a unit in their last place (4.7e-10 m)
}

TEST_CASE("a journal or a snapshot with Windows line endings opens as the same sculpture") {
    // A file checked out through git with CRLF line endings: every line ends in "\r\n".
    TempDir dir;
    Document doc = journaledDocument(dir / "j.netj");
    doc.saveSnapshot(dir / "snap.nets");
    const auto withCrlf = [](const std::string& bytes) {
        std::string out;
        for (char c : bytes) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
        return out;
    };
    writeBytes(dir / "crlf.netj", withCrlf(readBytes(dir / "j.netj")));
    writeBytes(dir / "crlf.nets", withCrlf(readBytes(dir / "snap.nets")));
    std::vector<std::string> warnings;
    CHECK(Document::open(dir / "crlf.netj", &warnings).hash() == doc.hash());
    CHECK(warnings.empty());
    const Document snapshot = Document::load(dir / "crlf.nets", &warnings);
    CHECK(warnings.empty());
    CHECK(snapshot.hash() == doc.hash());
    requireSameSystem(snapshot.compiled(), doc.compiled());
    // Opened, it keeps appending: "\n" lines after the "\r\n" ones, and both read back.
    std::uint64_t edited = 0;
    {
        Document appended = Document::open(dir / "crlf.netj");
        appended.execute(SetRowsCommand{PieceId(2), 2});
        edited = appended.hash();
    }
    const std::string mixed = readBytes(dir / "crlf.netj");
    CHECK(mixed.find("\r\n") != std::string::npos);
    CHECK(mixed.ends_with("}\n"));
    CHECK(Document::open(dir / "crlf.netj").hash() == edited);
}
