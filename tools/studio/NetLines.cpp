#include "NetLines.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace netsculpt::studio {

namespace {

constexpr std::uint32_t kNoBar = NetStrands::kNoBar;
constexpr double kStraightEnough = -0.5; ///< cosine of the angle between two paired bars' directions

/// A bar end: 2 * bar + (0 at barA, 1 at barB).
std::uint32_t knotAtEnd(const MassSpringSystem& sys, std::uint32_t end) {
    return end % 2 == 0 ? sys.barA[end / 2] : sys.barB[end / 2];
}

std::uint32_t otherKnot(const MassSpringSystem& sys, std::uint32_t bar, std::uint32_t knot) {
    return sys.barA[bar] == knot ? sys.barB[bar] : sys.barA[bar];
}

/// The bar ends at each knot, as CSR: ends[start[k] .. start[k + 1]).
void endsByKnot(const MassSpringSystem& sys, std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& ends) {
    start.assign(sys.knotCount() + 1, 0);
    for (std::uint32_t end = 0; end < 2 * sys.barCount(); ++end) ++start[knotAtEnd(sys, end) + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    ends.resize(2 * sys.barCount());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t end = 0; end < 2 * sys.barCount(); ++end) ends[fill[knotAtEnd(sys, end)]++] = end;
}

struct PairCandidate {
    double cosine;
    std::size_t i, j;
};

/// Reused between knots (a knot has a handful of bars; this is called for every knot).
struct PairingScratch {
    std::vector<Vec3> away;
    std::vector<PairCandidate> candidates;
};

/// Pairs the bar ends meeting at one knot, most nearly opposite first; continuation[end] gets the
/// partner's bar.
void pairAtKnot(const MassSpringSystem& sys, std::uint32_t knot, const std::uint32_t* ends, std::size_t count,
                PairingScratch& scratch, std::vector<std::uint32_t>& continuation) {
    std::vector<Vec3>& away = scratch.away;
    away.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3 d = sys.position[otherKnot(sys, ends[i] / 2, knot)] - sys.position[knot];
        const double length = d.norm();
        away[i] = length > 0 ? d / length : Vec3{};
    }
    std::vector<PairCandidate>& candidates = scratch.candidates;
    candidates.clear();
    for (std::size_t i = 0; i < count; ++i)
        for (std::size_t j = i + 1; j < count; ++j) {
            const double cosine = away[i].dot(away[j]);
            if (cosine < kStraightEnough && sys.barPiece[ends[i] / 2] == sys.barPiece[ends[j] / 2])
                candidates.push_back({cosine, i, j});
        }
    std::sort(candidates.begin(), candidates.end(),
              [](const PairCandidate& a, const PairCandidate& b) { return a.cosine < b.cosine; });
    for (const PairCandidate& c : candidates) {
        std::uint32_t& fromI = continuation[ends[c.i]];
        std::uint32_t& fromJ = continuation[ends[c.j]];
        if (fromI != kNoBar || fromJ != kNoBar) continue;
        fromI = ends[c.j] / 2;
        fromJ = ends[c.i] / 2;
    }
}

/// continuation[2 * bar + end]: the bar that continues `bar` beyond that end, or kNoBar.
std::vector<std::uint32_t> pairBars(const MassSpringSystem& sys) {
    std::vector<std::uint32_t> start, ends;
    endsByKnot(sys, start, ends);
    std::vector<std::uint32_t> continuation(2 * sys.barCount(), kNoBar);
    PairingScratch scratch;
    for (std::uint32_t k = 0; k < sys.knotCount(); ++k)
        pairAtKnot(sys, k, ends.data() + start[k], start[k + 1] - start[k], scratch, continuation);
    return continuation;
}

/// Where the strand through `bar` begins: walking back beyond its barA end until no bar continues
/// (or, on a closed strand, back at `bar`). Returns (first bar, the knot the strand starts at).
std::pair<std::uint32_t, std::uint32_t> strandStart(const MassSpringSystem& sys,
                                                    const std::vector<std::uint32_t>& continuation,
                                                    std::uint32_t bar) {
    std::uint32_t current = bar, outer = sys.barA[bar];
    for (std::size_t steps = 0; steps < sys.barCount(); ++steps) {
        const std::uint32_t next = continuation[2 * current + (sys.barA[current] == outer ? 0 : 1)];
        if (next == kNoBar) break;
        if (next == bar) return {bar, sys.barA[bar]};
        outer = otherKnot(sys, next, outer);
        current = next;
    }
    return {current, outer};
}

} // namespace

NetStrands buildStrands(const MassSpringSystem& sys) {
    const std::vector<std::uint32_t> continuation = pairBars(sys);
    std::vector<std::uint32_t> byPiece(sys.barCount());
    std::iota(byPiece.begin(), byPiece.end(), 0u);
    std::stable_sort(byPiece.begin(), byPiece.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return sys.barPiece[a] < sys.barPiece[b]; });
    NetStrands strands;
    std::vector<std::uint8_t> drawn(sys.barCount(), 0);
    for (std::uint32_t seed : byPiece) {
        if (drawn[seed]) continue;
        auto [bar, knot] = strandStart(sys, continuation, seed);
        strands.first.push_back(std::uint32_t(strands.knots.size()));
        strands.piece.push_back(sys.barPiece[seed]);
        while (bar != kNoBar && !drawn[bar]) {
            drawn[bar] = 1;
            strands.knots.push_back(knot);
            strands.bar.push_back(bar);
            knot = otherKnot(sys, bar, knot);
            bar = continuation[2 * bar + (sys.barA[bar] == knot ? 0 : 1)];
        }
        strands.knots.push_back(knot);
        strands.bar.push_back(kNoBar);
    }
    strands.first.push_back(std::uint32_t(strands.knots.size()));
    return strands;
}

std::vector<ScreenKnot> projectKnots(const std::vector<Vec3>& positions, const Camera& camera) {
    const Mat4 m = camera.projection() * camera.view();
    const double halfWidth = 0.5 * camera.width(), halfHeight = 0.5 * camera.height();
    const double nearPlane = camera.nearPlane();
    std::vector<ScreenKnot> screen(positions.size());
    for (std::size_t k = 0; k < positions.size(); ++k) {
        const Vec3& p = positions[k];
        const double x = m(0, 0) * p.x + m(0, 1) * p.y + m(0, 2) * p.z + m(0, 3);
        const double y = m(1, 0) * p.x + m(1, 1) * p.y + m(1, 2) * p.z + m(1, 3);
        const double w = m(3, 0) * p.x + m(3, 1) * p.y + m(3, 2) * p.z + m(3, 3);
        if (!(w > nearPlane)) continue; // behind the camera: never merged
        screen[k] = {float(halfWidth * (1 + x / w)), float(halfHeight * (1 - y / w)), true};
    }
    return screen;
}

namespace {

/// Squared distance, px^2, from p to the segment from a to b.
double squaredDistanceToSegment(const ScreenKnot& p, const ScreenKnot& a, const ScreenKnot& b) {
    const double abx = b.x - a.x, aby = b.y - a.y, apx = p.x - a.x, apy = p.y - a.y;
    const double length2 = abx * abx + aby * aby;
    const double t = length2 > 0 ? std::clamp((apx * abx + apy * aby) / length2, 0.0, 1.0) : 0.0;
    const double dx = apx - t * abx, dy = apy - t * aby;
    return dx * dx + dy * dy;
}

/// Whether one line from knots[from] to knots[to] can stand for the bars between them.
bool oneLineFits(const NetStrands& strands, const std::vector<ScreenKnot>& screen,
                 const std::vector<std::uint32_t>& colourKey, std::size_t from, std::size_t to, double tolerance2) {
    const ScreenKnot& a = screen[strands.knots[from]];
    const ScreenKnot& b = screen[strands.knots[to]];
    if (!b.inFront || colourKey[strands.bar[to - 1]] != colourKey[strands.bar[from]]) return false;
    for (std::size_t i = from + 1; i < to; ++i)
        if (squaredDistanceToSegment(screen[strands.knots[i]], a, b) > tolerance2) return false;
    return true;
}

} // namespace

void mergeStrands(const NetStrands& strands, const std::vector<ScreenKnot>& screen,
                  const std::vector<std::uint32_t>& colourKey, const NetLineOptions& options,
                  std::vector<NetLine>& lines) {
    lines.clear();
    const double tolerance2 = options.tolerancePixels * options.tolerancePixels;
    const std::size_t longestRun = std::size_t(std::max(1, options.longestRun));
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        const std::size_t last = strands.first[s + 1] - 1; // the strand's last knot
        for (std::size_t from = strands.first[s]; from < last;) {
            std::size_t to = from + 1;
            if (screen[strands.knots[from]].inFront && screen[strands.knots[to]].inFront)
                while (to < last && to + 1 - from <= longestRun &&
                       oneLineFits(strands, screen, colourKey, from, to + 1, tolerance2))
                    ++to;
            lines.push_back({strands.knots[from], strands.knots[to], strands.bar[from]});
            from = to;
        }
    }
}

void strandBars(const NetStrands& strands, std::vector<NetLine>& lines) {
    lines.clear();
    for (std::size_t i = 0; i + 1 < strands.knots.size(); ++i)
        if (strands.bar[i] != kNoBar) lines.push_back({strands.knots[i], strands.knots[i + 1], strands.bar[i]});
}

} // namespace netsculpt::studio
