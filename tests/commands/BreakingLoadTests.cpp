// A material's breaking load through the document: set_material sets it (undoable), a split
// copies it, the journal writes it only when given and replays it, the Lua export names it, and
// snapshots keep it (format 5) while those of format 4 still open.

#include "CommandTestSupport.h"

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

/// The material piece 1 of the fixture has, with `newtons` as its breaking load.
SetMaterialCommand breakingLoad(const Document& doc, std::optional<double> newtons) {
    Material m = doc.sculpture().piece(PieceId(1)).material;
    m.breakingLoad = newtons;
    return SetMaterialCommand{PieceId(1), m};
}

std::optional<double> breakingLoadOf(const Document& doc, std::uint32_t piece) {
    return doc.sculpture().piece(PieceId(piece)).material.breakingLoad;
}

/// Replaces the first `from` in line `number` of the journal (1: the header) and signs it again.
void editJournalLine(const std::filesystem::path& path, std::size_t number, const std::string& from,
                     const std::string& to) {
    std::istringstream in(readBytes(path));
    std::string text, line;
    for (std::size_t i = 1; std::getline(in, line); ++i) {
        if (i == number) {
            std::string json = line.substr(9);
            REQUIRE(json.find(from) != std::string::npos);
            json.replace(json.find(from), from.size(), to);
            char crc[9];
            std::snprintf(crc, sizeof crc, "%08x", crc32(json));
            line = std::string(crc) + " " + json;
        }
        text += line + "\n";
    }
    writeBytes(path, text);
}

} // namespace

TEST_CASE("a breaking load is set, undone, redone and removed with the rest of the material") {
    Document doc = fixtureDocument();
    const std::uint64_t without = doc.hash();
    CHECK_FALSE(breakingLoadOf(doc, 1).has_value());

    doc.execute(breakingLoad(doc, 3000));
    CHECK(breakingLoadOf(doc, 1) == 3000);
    const std::uint64_t with = doc.hash();
    CHECK(with != without);
    doc.undo();
    CHECK_FALSE(breakingLoadOf(doc, 1).has_value());
    CHECK(doc.hash() == without);
    doc.redo();
    CHECK(breakingLoadOf(doc, 1) == 3000);
    CHECK(doc.hash() == with);

    // A material without one removes it: the model is then the one that never had it.
    doc.execute(breakingLoad(doc, std::nullopt));
    CHECK_FALSE(breakingLoadOf(doc, 1).has_value());
    CHECK(doc.hash() == without);
    doc.undo();

    // Both parts of a split are the same rope.
    doc.execute(SplitCommand{PieceId(1), 5});
    CHECK(breakingLoadOf(doc, 1) == 3000);
    CHECK(breakingLoadOf(doc, 2) == 3000);
}

TEST_CASE("the journal writes a breaking load only when given and replays it bit for bit") {
    TempDir dir;
    const auto path = dir / "j.netj";
    Document doc = fixtureDocument();
    doc.attachJournal(path);
    doc.execute(SetMaterialCommand{PieceId(1), Material{}});
    doc.execute(breakingLoad(doc, 2750.0000000000005)); // a number that needs every digit
    doc.execute(breakingLoad(doc, 1200));
    doc.undo();
    doc.execute(SplitCommand{PieceId(1), 4});
    doc.execute(SetMaterialCommand{PieceId(2), Material{}}); // the right part's removed again

    const std::string bytes = readBytes(path);
    CHECK_THAT(bytes, Contains("\"linear_density\":0.006}}\n")); // the first set_material
    CHECK_THAT(bytes, Contains(",\"breaking_load\":2750.0000000000005}}\n"));
    CHECK_THAT(bytes, Contains(",\"breaking_load\":1200.0}}\n"));

    std::vector<std::string> warnings;
    Document replayed = Document::open(path, &warnings);
    CHECK(warnings.empty());
    CHECK(replayed.hash() == doc.hash());
    CHECK(breakingLoadOf(replayed, 1) == 2750.0000000000005);
    CHECK_FALSE(breakingLoadOf(replayed, 2).has_value());
    while (doc.canUndo()) { // the same undo steps, state for state
        REQUIRE(replayed.canUndo());
        doc.undo();
        replayed.undo();
        CHECK(replayed.hash() == doc.hash());
    }
}

TEST_CASE("a journal entry with a bad breaking load is an error naming its line and the value") {
    TempDir dir;
    const auto path = dir / "j.netj";
    {
        Document doc = fixtureDocument();
        doc.attachJournal(path);                    // lines 2-5: the fixture's commands
        doc.execute(breakingLoad(doc, 3000));       // line 6
        doc.execute(SetRowsCommand{PieceId(1), 7}); // so that line 6 is not the last
    }
    for (const auto& [value, mentions] :
         {std::pair{"0", "got 0"}, std::pair{"-3000.0", "got -3000"},
          std::pair{"\"3000\"", "must be a number, got \"3000\""},
          std::pair{"null", "must be a number, got null"}}) {
        INFO(value);
        const auto copy = dir / "bad.netj";
        std::filesystem::copy_file(path, copy, std::filesystem::copy_options::overwrite_existing);
        editJournalLine(copy, 6, "\"breaking_load\":3000.0",
                        std::string("\"breaking_load\":") + value);
        const std::string bytes = readBytes(copy);
        REQUIRE_THROWS_WITH(Document::open(copy), Contains("line 6") && Contains(mentions));
        CHECK(readBytes(copy) == bytes);
    }
}

TEST_CASE("the Lua export names a breaking load, and says false where one was removed") {
    Document plain = fixtureDocument();
    plain.execute(SetMaterialCommand{PieceId(1), Material{}});
    CHECK_THAT(plain.toLua(), Contains("linear_density = 0.006}\n")); // as before breaking loads

    Document doc = fixtureDocument();
    doc.execute(breakingLoad(doc, 3000));
    doc.execute(breakingLoad(doc, std::nullopt));
    const std::string lua = doc.toLua();
    INFO(lua);
    CHECK_THAT(lua, Contains("doc:set_material{piece = p1, stiffness = 2e+05, "
                             "compression_ratio = 0.01, knot_mass = 0.002, linear_density = "
                             "0.006, breaking_load = 3000.0}\n"));
    CHECK_THAT(lua, Contains("linear_density = 0.006, breaking_load = false}\n"));
}

TEST_CASE("a snapshot keeps the breaking loads (format 5)") {
    TempDir dir;
    Document doc = fixtureDocument();
    doc.execute(breakingLoad(doc, 3000));
    doc.saveSnapshot(dir / "snap.nets");
    const std::string bytes = readBytes(dir / "snap.nets");
    CHECK_THAT(bytes, StartsWith("netsculpt-snapshot 5\n"));
    CHECK_THAT(bytes, Contains("\"linear_density\":0.006,\"breaking_load\":3000.0},\"colour\""));

    std::vector<std::string> warnings;
    Document loaded = Document::load(dir / "snap.nets", &warnings);
    CHECK(warnings.empty());
    CHECK(loaded.hash() == doc.hash());
    CHECK(breakingLoadOf(loaded, 1) == 3000);
    loaded.undo(); // the history came with it
    CHECK_FALSE(breakingLoadOf(loaded, 1).has_value());
}

TEST_CASE("a format 4 snapshot, written before breaking loads, still opens relaxed") {
    const std::filesystem::path data =
        std::filesystem::path(NETSCULPT_SOURCE_DIR) / "tests/data/snapshots";
    TempDir dir;
    std::vector<std::string> warnings;
    Document old = Document::load(data / "example-v4.nets", &warnings);
    CHECK(warnings.empty());
    CHECK(old.isRelaxed()); // its shape and hash as written: nothing to relax again
    REQUIRE(old.sculpture().pieces.size() == 2);
    CHECK(old.sculpture().piece(PieceId(1)).material.stiffness == 2e4);
    for (const auto& [id, piece] : old.sculpture().pieces)
        CHECK_FALSE(piece.material.breakingLoad.has_value());

    // Saved again it is format 5, with no breaking load written, and the same model.
    old.saveSnapshot(dir / "again.nets");
    const std::string bytes = readBytes(dir / "again.nets");
    CHECK_THAT(bytes, StartsWith("netsculpt-snapshot 5\n"));
    CHECK(bytes.find("breaking_load") == std::string::npos);
    CHECK(Document::load(dir / "again.nets").hash() == old.hash());

    Material m = old.sculpture().piece(PieceId(1)).material;
    m.breakingLoad = 900;
    old.execute(SetMaterialCommand{PieceId(1), m});
    CHECK(breakingLoadOf(old, 1) == 900);
}
