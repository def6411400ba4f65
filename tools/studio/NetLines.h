#pragma once
// The net's bars as the lines the renderer draws, window-free. A dense net (20,000 knots) has
// bars a few pixels long, and a software renderer pays for every line it sets up. So the bars are
// chained into strands (a rope of the net: each bar continued by the most nearly straight bar of
// the same piece at each knot); whenever the shape or the camera changes, every run of a strand
// that stays within a fraction of a pixel of one straight line on screen, in one colour, becomes
// that one line: no knot is further than the tolerance from its line. The 20,000-knot demo tube
// seen whole needs a tenth of the lines.

#include "interaction/Camera.h"
#include "physics/MassSpringSystem.h"

#include <cstdint>
#include <vector>

namespace netsculpt::studio {

/// Chains of bars through knots, each within one piece, together covering every bar once.
/// Strand s runs through knots[first[s] .. first[s + 1]); bar[i] joins knots[i] and knots[i + 1]
/// (the entry at a strand's last knot is kNoBar). Strands are ordered by piece.
struct NetStrands {
    static constexpr std::uint32_t kNoBar = 0xffffffffu;
    std::vector<std::uint32_t> knots;
    std::vector<std::uint32_t> bar;
    std::vector<std::uint32_t> first; ///< strandCount() + 1 offsets into knots
    std::vector<PieceId> piece;       ///< per strand

    std::size_t strandCount() const { return piece.size(); }
};

/// Chains `system`'s bars: at each knot, bars of one piece whose directions (at the current
/// positions) are within 60 degrees of opposite are paired, most nearly opposite first.
NetStrands buildStrands(const MassSpringSystem& system);

/// A knot projected to the window: pixels, and whether it is in front of the near plane.
struct ScreenKnot {
    float x = 0, y = 0;
    bool inFront = false;
};

std::vector<ScreenKnot> projectKnots(const std::vector<Vec3>& positions, const Camera& camera);

/// One line to draw: from knot a to knot b, in the colour of `bar` (the run's first bar).
struct NetLine {
    std::uint32_t a = 0, b = 0, bar = 0;
};

struct NetLineOptions {
    double tolerancePixels = 0.4; ///< largest distance of a skipped knot from the line, px
    int longestRun = 24;          ///< bars per line at most (bounds the work per line)
};

/// The lines for this view: a run of a strand's bars becomes one line while every knot it skips
/// is within the tolerance of the line, on screen, all are in front of the camera and its bars
/// have the same colourKey (per bar, a quantized colour: runs never mix colours). Lines come
/// strand by strand, so each piece's lines are one range. Replaces the contents of `lines`.
void mergeStrands(const NetStrands& strands, const std::vector<ScreenKnot>& screen,
                  const std::vector<std::uint32_t>& colourKey, const NetLineOptions& options,
                  std::vector<NetLine>& lines);

/// Every bar as its own line, strand by strand (no merging: the same order as mergeStrands).
void strandBars(const NetStrands& strands, std::vector<NetLine>& lines);

} // namespace netsculpt::studio
