// The studio's net lines (tools/studio/NetLines.h), without a window: strands cover every bar
// once along the ropes of the net, and a merged line never strays from the knots it stands for by
// more than the tolerance, never mixes colours and never spans a knot behind the camera.

#include "NetLines.h"

#include "interaction/DemoScenes.h"
#include "interaction/Handles.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace netsculpt;
using namespace netsculpt::studio;

namespace {

Camera framedCamera(const Document& doc) {
    Camera camera(1280, 800);
    const auto [lo, hi] = sceneBounds(doc.sculpture(), doc.compiled());
    camera.frame(lo, hi);
    return camera;
}

/// A straight rope of `bars` bars along x, one piece.
MassSpringSystem straightRope(int bars) {
    MassSpringSystem sys;
    for (int k = 0; k <= bars; ++k) sys.position.push_back({0.1 * k, 0, 1});
    for (int b = 0; b < bars; ++b) {
        sys.barA.push_back(std::uint32_t(b));
        sys.barB.push_back(std::uint32_t(b + 1));
        sys.barPiece.push_back(PieceId(1));
    }
    return sys;
}

Camera lookingAtRope() {
    Camera camera(1280, 800);
    camera.target = {0.5, 0, 1};
    camera.distance = 3;
    camera.yaw = -1.5707963267948966; // from -y, the rope across the screen
    camera.pitch = 0;
    return camera;
}

double distanceToSegment(const ScreenKnot& p, const ScreenKnot& a, const ScreenKnot& b) {
    const double abx = b.x - a.x, aby = b.y - a.y;
    const double length2 = abx * abx + aby * aby;
    const double t = length2 > 0 ? std::clamp(((p.x - a.x) * abx + (p.y - a.y) * aby) / length2, 0.0, 1.0) : 0.0;
    return std::hypot(p.x - a.x - t * abx, p.y - a.y - t * aby);
}

/// Walks the strands alongside the lines (which come strand by strand, in order) and returns the
/// largest distance of a skipped knot from its line, px; every bar must be spanned exactly once.
double largestSkippedDistance(const NetStrands& strands, const std::vector<ScreenKnot>& screen,
                              const std::vector<NetLine>& lines) {
    double largest = 0;
    std::size_t line = 0;
    for (std::size_t s = 0; s < strands.strandCount(); ++s)
        for (std::size_t i = strands.first[s]; i + 1 < strands.first[s + 1]; ++line) {
            REQUIRE(line < lines.size());
            REQUIRE(lines[line].a == strands.knots[i]);
            REQUIRE(lines[line].bar == strands.bar[i]);
            std::size_t end = i + 1;
            while (end + 1 < strands.first[s + 1] && strands.knots[end] != lines[line].b) ++end;
            REQUIRE(strands.knots[end] == lines[line].b);
            for (std::size_t m = i + 1; m < end; ++m)
                largest = std::max(largest, distanceToSegment(screen[strands.knots[m]], screen[lines[line].a],
                                                              screen[lines[line].b]));
            i = end;
        }
    CHECK(line == lines.size());
    return largest;
}

} // namespace

TEST_CASE("net lines: strands cover every bar once, follow the bars and stay in one piece") {
    Document doc;
    buildDemoSculpture(doc);
    const MassSpringSystem& sys = doc.compiled().system;
    const NetStrands strands = buildStrands(sys);
    REQUIRE(strands.first.size() == strands.strandCount() + 1);
    std::vector<int> seen(sys.barCount(), 0);
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        if (s > 0) CHECK(strands.piece[s - 1] <= strands.piece[s]); // piece by piece
        const std::size_t last = strands.first[s + 1] - 1;
        CHECK(strands.bar[last] == NetStrands::kNoBar);
        for (std::size_t i = strands.first[s]; i < last; ++i) {
            const std::uint32_t b = strands.bar[i];
            REQUIRE(b < sys.barCount());
            ++seen[b];
            CHECK(sys.barPiece[b] == strands.piece[s]);
            const auto ends = std::minmax(strands.knots[i], strands.knots[i + 1]);
            CHECK(ends == std::minmax(sys.barA[b], sys.barB[b]));
        }
    }
    CHECK(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
    // The bars run on through the knots along the ropes: strands are many bars long.
    CHECK(double(sys.barCount()) / double(strands.strandCount()) > 8);
}

TEST_CASE("net lines: a straight rope is one line, split where its colour changes") {
    const MassSpringSystem rope = straightRope(10);
    const NetStrands strands = buildStrands(rope);
    REQUIRE(strands.strandCount() == 1);
    const std::vector<ScreenKnot> screen = projectKnots(rope.position, lookingAtRope());
    std::vector<NetLine> lines;
    mergeStrands(strands, screen, std::vector<std::uint32_t>(10, 7), NetLineOptions{}, lines);
    REQUIRE(lines.size() == 1);
    CHECK(std::minmax(lines[0].a, lines[0].b) == std::minmax(0u, 10u));

    std::vector<std::uint32_t> colourKey(10, 7);
    for (int b = 6; b < 10; ++b) colourKey[std::size_t(b)] = 8;
    mergeStrands(strands, screen, colourKey, NetLineOptions{}, lines);
    CHECK(lines.size() == 2);

    strandBars(strands, lines);
    CHECK(lines.size() == 10);
}

TEST_CASE("net lines: a bent rope keeps its bend, and knots behind the camera are never skipped") {
    MassSpringSystem rope = straightRope(10);
    rope.position[5].z += 0.05; // 18 pixels at 3 m: a kink
    const NetStrands strands = buildStrands(rope);
    std::vector<NetLine> lines;
    const std::vector<std::uint32_t> oneColour(10, 0);
    std::vector<ScreenKnot> screen = projectKnots(rope.position, lookingAtRope());
    mergeStrands(strands, screen, oneColour, NetLineOptions{}, lines);
    // Straight up to the knot before the kink, its two bars, straight on from the knot after it.
    CHECK(lines.size() == 4);
    CHECK(largestSkippedDistance(strands, screen, lines) <= NetLineOptions{}.tolerancePixels);

    screen[3].inFront = false;
    mergeStrands(strands, screen, oneColour, NetLineOptions{}, lines);
    for (const NetLine& line : lines)
        if (line.a == 3 || line.b == 3) CHECK(std::abs(int(line.a) - int(line.b)) == 1);
}

TEST_CASE("net lines: a 20,000-knot tube seen whole needs a fraction of its bars as lines, within the tolerance") {
    Document doc;
    buildLargeDemoSculpture(doc, 20000);
    const MassSpringSystem& sys = doc.compiled().system;
    const NetStrands strands = buildStrands(sys);
    const std::vector<ScreenKnot> screen = projectKnots(sys.position, framedCamera(doc));
    std::vector<NetLine> lines;
    const std::vector<std::uint32_t> oneColour(sys.barCount(), 0);
    const NetLineOptions options;
    mergeStrands(strands, screen, oneColour, options, lines);
    INFO(lines.size() << " lines for " << sys.barCount() << " bars");
    CHECK(lines.size() * 5 < sys.barCount());
    CHECK(largestSkippedDistance(strands, screen, lines) <= options.tolerancePixels + 1e-6);
}
