#pragma once
// The shapes a drag's previews settled in, one per step, for the next step's start: a drag
// repeats one rest-length edit (a bar length dragged a little further at every frame), so its
// equilibria lie on a smooth path x(t), t the edit's size so far, and the next one is near the
// polynomial through the last few, extrapolated to the next t (the predictor of a continuation
// method). Degree 1 is the secant (the last step repeated); on the studio's 20,000-knot demo
// tube a bar-length drag's steps start 0.6-1 knot weights off their equilibrium by it, 0.02 by
// degree 2 and 0.002 by degree 3 (docs/performance.md).

#include "geometry/Vec3.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace netsculpt {

/// `now` as a multiple rho of `last` (rest-length changes, one per bar): rho = <now, last> /
/// <last, last> when it is in (0, most] and `now` less rho `last` is below `tolerance` of `now`
/// (Euclidean norms), else empty: not the same edit again.
std::optional<double> repeatRatio(const std::vector<double>& now, const std::vector<double>& last,
                                  double tolerance, double most = 2);

class DragPath {
  public:
    /// Highest degree a prediction takes (four shapes kept).
    static constexpr int kMaxDegree = 3;
    /// Steps cut short (skip) and the next one together: at most this many times the path's last
    /// step, else the path ends (its prediction that far ahead is no guide).
    static constexpr double kMaxAhead = 4;

    /// A converged step of a drag: from `start` (the path's last shape, or the first shape of a
    /// new path; empty when the step did not start at an equilibrium, a new path then starting
    /// at `end` alone) by the rest-length change `restChange` to `end`. A step that does not
    /// repeat the last one (repeatRatio with `tolerance`), or does not start where the path
    /// ends, starts a new path.
    void add(const std::vector<Vec3>& start, const std::vector<Vec3>& end,
             std::vector<double> restChange, double tolerance);
    /// A step whose preview was cut short before it settled (the next edit came first): its
    /// change is carried into the next step's, which the path then measures from its last
    /// shape. A step that does not repeat the last one ends the path.
    void skip(const std::vector<double>& restChange, double tolerance);
    void clear();
    /// The highest degree a prediction can have now: the steps on the path, at most kMaxDegree.
    int degrees() const {
        return shapes_.empty() ? 0 : std::min<int>(int(shapes_.size()) - 1, kMaxDegree);
    }
    /// The ratio of `restChange`, with the steps skipped since the path's last shape, to the
    /// path's last step (see repeatRatio), empty when it does not repeat it or the path is empty.
    std::optional<double> ratio(const std::vector<double>& restChange, double tolerance) const;
    /// The shape after one more step of `ratio` times the last one: the polynomial of `degree`
    /// (1 to degrees()) through the last degree + 1 shapes, per coordinate, at the next t; knots
    /// `fixed` keep their place in the last shape.
    void predict(double ratio, int degree, const std::vector<std::uint8_t>& fixed,
                 std::vector<Vec3>& out) const;

  private:
    std::vector<std::vector<Vec3>> shapes_; ///< x_0 ... x_m, oldest first
    std::vector<double> t_;                 ///< the edit's size at each, in the first step's units
    double lastStep_ = 1;                   ///< t_'s last increment (1 for the first step)
    std::vector<double> lastChange_;        ///< the last step's rest-length change
    std::vector<double> skipped_;           ///< the skipped steps' change since then; empty: none

    /// `restChange` plus the skipped steps' change.
    std::vector<double> sinceLastShape(const std::vector<double>& restChange) const;
};

} // namespace netsculpt
