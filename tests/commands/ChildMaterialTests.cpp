// A piece attached to another with a material (the Lua API and the studio give the parent's):
// the child is knotted from it, the journal writes it only when given and replays it, an entry
// without one keeps giving the default rope, a bad one is refused with the document as it was,
// and the Lua export passes it on.

#include "CommandTestSupport.h"

using namespace netsculpt;
using namespace netsculpt::test;
using Catch::Matchers::Contains;

namespace {

/// A rope unlike the default in every field.
Material thickRope() {
    Material m;
    m.stiffness = 5e4;
    m.compressionRatio = 0.02;
    m.knotMass = 0.011;
    m.linearDensity = 0.045;
    m.breakingLoad = 1800;
    return m;
}

AttachToPieceCommand hangWith(std::optional<Material> material) {
    AttachToPieceCommand c = hang(1, Gear{2, 1}, 3, 0.3);
    c.args.material = material;
    return c;
}

const Material& materialOf(const Document& doc, std::uint32_t piece) {
    return doc.sculpture().piece(PieceId(piece)).material;
}

} // namespace

TEST_CASE("a piece attached with a material is knotted from it, and without one from the "
          "default rope") {
    Document doc = fixtureDocument();
    doc.execute(SetMaterialCommand{PieceId(1), thickRope()});
    doc.execute(hangWith(thickRope()));
    CHECK(materialOf(doc, 2) == thickRope());
    // The child's knots weigh what the thick rope makes them: a knot of row 1 holds four bars
    // of 0.3 m, so 0.011 + 0.5 * 0.045 * 1.2 kg.
    const CompiledSculpture& compiled = doc.compiled();
    const std::uint32_t knot = compiled.knotOf(PieceId(2), 1, 1);
    CHECK(compiled.system.mass[knot] == Approx(0.011 + 0.5 * 0.045 * 4 * 0.3).epsilon(1e-12));
    doc.undo();
    doc.execute(hangWith(std::nullopt)); // as every entry before children took a material
    CHECK(materialOf(doc, 2) == Material{});
}

TEST_CASE("the journal writes a child's material only when given, and replays both kinds") {
    TempDir dir;
    const auto path = dir / "j.netj";
    Document doc = fixtureDocument();
    doc.attachJournal(path);
    doc.execute(hangWith(thickRope()));
    doc.execute(hangWith(std::nullopt));
    const std::string bytes = readBytes(path);
    CHECK_THAT(bytes, Contains("\"args\":{\"piece\":1,\"gear\":\"2\",\"rows\":3,\"bar\":0.3,"
                               "\"material\":{\"stiffness\":50000.0,\"compression_ratio\":0.02,"
                               "\"knot_mass\":0.011,\"linear_density\":0.045,"
                               "\"breaking_load\":1800.0}}"));
    CHECK_THAT(bytes, Contains("\"args\":{\"piece\":1,\"gear\":\"2\",\"rows\":3,\"bar\":0.3}"));

    std::vector<std::string> warnings;
    const Document replayed = Document::open(path, &warnings);
    CHECK(warnings.empty());
    CHECK(replayed.hash() == doc.hash());
    CHECK(materialOf(replayed, 2) == thickRope());
    CHECK(materialOf(replayed, 3) == Material{});
}

TEST_CASE("a child's bad material is refused, naming the value, with the document and journal as "
          "they were") {
    TempDir dir;
    const auto path = dir / "j.netj";
    Document doc = fixtureDocument();
    doc.attachJournal(path);
    const std::uint64_t before = doc.hash();
    const std::string bytes = readBytes(path);
    Material bad = thickRope();
    bad.compressionRatio = 1.5;
    REQUIRE_THROWS_WITH(doc.execute(hangWith(bad)), Contains("1.5"));
    bad = thickRope();
    bad.stiffness = -1;
    REQUIRE_THROWS_WITH(doc.execute(hangWith(bad)), Contains("-1"));
    CHECK(doc.hash() == before);
    CHECK(doc.sculpture().pieces.size() == 1);
    CHECK(readBytes(path) == bytes);
}

TEST_CASE("the Lua export gives every child its rope, so that the script does not inherit "
          "another") {
    // An entry without a material gave the default rope, though its parent's is another: the
    // script's call, which would take the parent's, is told the default.
    Document doc = fixtureDocument();
    doc.execute(SetMaterialCommand{PieceId(1), thickRope()});
    doc.execute(hangWith(std::nullopt));
    doc.execute(hangWith(thickRope()));
    const std::string lua = doc.toLua();
    INFO(lua);
    CHECK_THAT(lua,
               Contains("local p2 = doc:attach_to_piece{piece = p1, gear = 2, rows = 3, bar = "
                        "0.3, material = {stiffness = 2e+05, compression_ratio = 0.01, "
                        "knot_mass = 0.002, linear_density = 0.006, breaking_load = false}}\n"));
    CHECK_THAT(lua,
               Contains("local p3 = doc:attach_to_piece{piece = p1, gear = 2, rows = 3, bar = "
                        "0.3, material = {stiffness = 50000.0, compression_ratio = 0.02, "
                        "knot_mass = 0.011, linear_density = 0.045, breaking_load = 1800.0}}\n"));
}
