#pragma once
// Sculptures and file helpers shared by the io tests.

#include "model/TestSculptures.h"

#include "io/Report.h"
#include "physics/Relaxer.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace netsculpt::test {

/// The folder of the committed test data (tests/data).
inline std::filesystem::path dataDir() {
    return std::filesystem::path(NETSCULPT_SOURCE_DIR) / "tests" / "data";
}

/// A fresh, empty folder for one test's outputs under the build tree.
inline std::filesystem::path outputDir(const std::string& name) {
    const auto dir = std::filesystem::path(NETSCULPT_BINARY_DIR) / "test-output" / "io" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream buffer;
    buffer << in.rdbuf();
    return buffer.str();
}

inline void writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

/// A soft rope (EA 60 N) so that RK4 relaxes the test nets in well under a second.
inline Material softRope() {
    Material m;
    m.stiffness = 60;
    m.compressionRatio = 0.01;
    m.knotMass = 0.002;
    m.linearDensity = 0.006;
    return m;
}

/// An open sheet of rows x columns on a straight rail from (0,0,0) to (span,0,0), bar `bar`.
struct SheetNet {
    Sculpture s;
    RailId rail;
    PieceId piece;
    CompiledSculpture compiled;
};
inline SheetNet sheet(int rows, int columns, double span, double bar, bool soft = false) {
    SheetNet t;
    t.rail = edit(t.s, [&](Sculpture& s) {
        return addRail(s, "bar", lineRail({0, 0, 0}, {span, 0, 0}));
    });
    t.piece = edit(t.s, [&](Sculpture& s) {
        return attachToRail(s, {t.rail, columns, 0, rows, bar, 0, false});
    });
    if (soft)
        edit(t.s, [&](Sculpture& s) {
            setMaterial(s, t.piece, softRope());
            return 0;
        });
    t.compiled = compileSculpture(t.s);
    return t;
}

/// A closed tube on a ring (regular polygon) rail with a geared child below it (gear 2), the ring
/// 3 m above `site`.
struct Tube {
    Sculpture s;
    RailId rail;
    PieceId piece, child;
    CompiledSculpture compiled;
};
inline Tube tubeWithChild(int columns = 12, int rows = 5, double radius = 1.0, double bar = 0.4,
                          const Vec3& site = {}) {
    Tube t;
    t.rail = edit(t.s, [&](Sculpture& s) {
        return addRail(s, "ring", ringRail(site + Vec3{0, 0, 3}, radius, columns));
    });
    t.piece = edit(t.s, [&](Sculpture& s) {
        return attachToRail(s, {t.rail, columns, 0, rows, bar, 0, false});
    });
    t.child = edit(t.s, [&](Sculpture& s) {
        return attachToPiece(s, {t.piece, Gear{2, 1}, 3, 0.25});
    });
    edit(t.s, [&](Sculpture& s) {
        setColour(s, t.child, {0.1, 0.3, 0.8});
        renamePiece(s, t.piece, "upper");
        return 0;
    });
    t.compiled = compileSculpture(t.s);
    return t;
}

} // namespace netsculpt::test
