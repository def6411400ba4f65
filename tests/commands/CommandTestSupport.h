#pragma once
// Shared by the command tests: small rails, a fixture document, temporary folders, and checks
// that two compiled systems are the same bit for bit.

#include "commands/Document.h"
#include "commands/Journal.h"
#include "model/Error.h"
#include "model/TestSculptures.h"

#include <catch2/catch.hpp>

#include <atomic>
#include <bit>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace netsculpt::test {

/// A folder under /dev/shm (fast: fsync is free there) or the system's temp folder, removed at
/// the end of the test.
class TempDir {
  public:
    explicit TempDir(bool preferMemory = true) {
        static std::atomic<int> counter{0};
        std::filesystem::path root = std::filesystem::temp_directory_path();
        if (preferMemory && std::filesystem::is_directory("/dev/shm")) root = "/dev/shm";
        path_ = root / ("netsculpt-cmdtests-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
};

inline std::string readBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream buffer;
    buffer << in.rdbuf();
    return buffer.str();
}

inline void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
}

inline bool sameBits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }
inline bool sameBits(const Vec3& a, const Vec3& b) { return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z); }

/// The two compiled systems are the same: knots (positions bit for bit, masses, fixed), bars
/// (ends, rest lengths, stiffnesses) and the piece tables.
inline void requireSameSystem(const CompiledSculpture& a, const CompiledSculpture& b) {
    const MassSpringSystem& x = a.system;
    const MassSpringSystem& y = b.system;
    REQUIRE(x.knotCount() == y.knotCount());
    REQUIRE(x.barCount() == y.barCount());
    CHECK(sameBits(x.origin, y.origin));
    std::size_t positionsDiffer = 0, massesDiffer = 0, barsDiffer = 0;
    for (std::size_t k = 0; k < x.knotCount(); ++k) {
        positionsDiffer += !sameBits(x.position[k], y.position[k]);
        massesDiffer += !sameBits(x.mass[k], y.mass[k]) || x.fixed[k] != y.fixed[k];
    }
    for (std::size_t b = 0; b < x.barCount(); ++b)
        barsDiffer += x.barA[b] != y.barA[b] || x.barB[b] != y.barB[b] || !sameBits(x.restLength[b], y.restLength[b]) ||
                      !sameBits(x.kTension[b], y.kTension[b]) || !sameBits(x.kCompression[b], y.kCompression[b]);
    CHECK(positionsDiffer == 0);
    CHECK(massesDiffer == 0);
    CHECK(barsDiffer == 0);
    REQUIRE(a.pieces.size() == b.pieces.size());
    for (const auto& [id, pk] : a.pieces) {
        REQUIRE(b.pieces.count(id) == 1);
        CHECK(pk.index == b.pieces.at(id).index);
    }
}

/// Fixture: rail 1 a closed 12-gon of radius 1 at z = 3 (knot spacing ~0.518 m with 12
/// columns), rail 2 a straight open rail, rail 3 a closed 12-gon at z = 0; piece 1 hangs from
/// rail 1 (12 columns, 6 rows, bar 0.4 m).
inline Document fixtureDocument() {
    Document doc;
    doc.execute(AddRailCommand{"top", polygonRail(12, 1.0, 3.0)});
    doc.execute(AddRailCommand{"line", lineRail({-2, 3, 3}, {2, 3, 3})});
    doc.execute(AddRailCommand{"bottom", polygonRail(12, 1.0, 0.0)});
    AttachToRailArgs args;
    args.rail = RailId(1);
    args.columns = 12;
    args.rows = 6;
    args.bar = 0.4;
    doc.execute(AttachToRailCommand{args});
    return doc;
}

inline AttachToRailCommand attach(std::uint32_t rail, int columns, int rows, double bar) {
    AttachToRailArgs a;
    a.rail = RailId(rail);
    a.columns = columns;
    a.rows = rows;
    a.bar = bar;
    return AttachToRailCommand{a};
}

/// Adds a ring rail of 12 points, radius 1 m, about `centre` and hangs a tube of 12 columns and 8
/// rows of 0.3 m bars (the default rope) from it: rail `rail`, the piece after it.
inline void addRingWithTube(Document& doc, const Vec3& centre, std::uint32_t rail) {
    CurveSpec ring;
    ring.closed = true;
    ring.points = circlePoints(centre, 1.0, 12);
    doc.execute(AddRailCommand{"ring " + std::to_string(rail), ring});
    doc.execute(attach(rail, 12, 8, 0.3));
}

inline AttachToPieceCommand hang(std::uint32_t parent, Gear gear, int rows, double bar) {
    AttachToPieceArgs a;
    a.parent = PieceId(parent);
    a.gear = gear;
    a.rows = rows;
    a.bar = bar;
    return AttachToPieceCommand{a};
}

/// The entries of a journal file (no replay).
inline std::vector<JournalEntry> entriesOf(const std::filesystem::path& path) { return readJournal(path).entries; }

} // namespace netsculpt::test
