#include "interaction/DragPath.h"

#include <algorithm>
#include <cassert>

namespace netsculpt {

std::optional<double> repeatRatio(const std::vector<double>& now, const std::vector<double>& last,
                                  double tolerance, double most) {
    if (now.size() != last.size())
        return std::nullopt;
    double dot = 0, lastSquared = 0, nowSquared = 0;
    for (std::size_t b = 0; b < now.size(); ++b) {
        dot += now[b] * last[b];
        lastSquared += last[b] * last[b];
        nowSquared += now[b] * now[b];
    }
    if (!(lastSquared > 0) || !(nowSquared > 0))
        return std::nullopt;
    const double rho = dot / lastSquared;
    double offSquared = 0;
    for (std::size_t b = 0; b < now.size(); ++b) {
        const double off = now[b] - rho * last[b];
        offSquared += off * off;
    }
    if (!(rho > 0 && rho <= most) || offSquared > tolerance * tolerance * nowSquared)
        return std::nullopt;
    return rho;
}

void DragPath::clear() {
    shapes_.clear();
    t_.clear();
    lastChange_.clear();
    skipped_.clear();
}

std::vector<double> DragPath::sinceLastShape(const std::vector<double>& restChange) const {
    std::vector<double> change = restChange;
    if (skipped_.size() == change.size())
        for (std::size_t b = 0; b < change.size(); ++b)
            change[b] += skipped_[b];
    return change;
}

std::optional<double> DragPath::ratio(const std::vector<double>& restChange,
                                      double tolerance) const {
    if (shapes_.empty())
        return std::nullopt;
    if (skipped_.empty())
        return repeatRatio(restChange, lastChange_, tolerance);
    if (!repeatRatio(restChange, lastChange_, tolerance)) // this step alone: not the same edit
        return std::nullopt;
    return repeatRatio(sinceLastShape(restChange), lastChange_, tolerance, kMaxAhead);
}

void DragPath::skip(const std::vector<double>& restChange, double tolerance) {
    if (!ratio(restChange, tolerance)) {
        clear();
        return;
    }
    skipped_ = sinceLastShape(restChange);
}

void DragPath::add(const std::vector<Vec3>& start, const std::vector<Vec3>& end,
                   std::vector<double> restChange, double tolerance) {
    const std::optional<double> rho = ratio(restChange, tolerance);
    // After skipped steps the step goes on from where their runs stopped, not the last shape.
    if (!rho || (skipped_.empty() && shapes_.back() != start)) {
        clear();
        if (!start.empty()) {
            shapes_.push_back(start);
            t_.push_back(0);
        }
        t_.push_back(1); // the first step is the unit of t
        lastStep_ = 1;
    } else {
        lastStep_ *= *rho;
        t_.push_back(t_.back() + lastStep_);
        restChange = sinceLastShape(restChange);
        skipped_.clear();
    }
    shapes_.push_back(end);
    lastChange_ = std::move(restChange);
    if (shapes_.size() > std::size_t(kMaxDegree) + 1) {
        shapes_.erase(shapes_.begin());
        t_.erase(t_.begin());
    }
}

void DragPath::predict(double ratio, int degree, const std::vector<std::uint8_t>& fixed,
                       std::vector<Vec3>& out) const {
    assert(degree >= 1 && degree <= degrees());
    const std::size_t m = shapes_.size() - 1, first = m - std::size_t(degree);
    const double next = t_[m] + ratio * lastStep_;
    const std::vector<Vec3>& last = shapes_[m];
    out.assign(last.begin(), last.end());
    Vec3 table[kMaxDegree + 1];
    for (std::size_t j = 0; j < last.size(); ++j) {
        if (fixed[j])
            continue;
        // Newton's divided differences of the shapes first ... m, then its form at `next`.
        for (int i = 0; i <= degree; ++i)
            table[i] = shapes_[first + std::size_t(i)][j];
        for (int level = 1; level <= degree; ++level)
            for (int i = degree; i >= level; --i)
                table[i] = (table[i] - table[i - 1]) /
                           (t_[first + std::size_t(i)] - t_[first + std::size_t(i - level)]);
        Vec3 value = table[degree];
        for (int i = degree - 1; i >= 0; --i)
            value = table[i] + value * (next - t_[first + std::size_t(i)]);
        out[j] = value;
    }
}

} // namespace netsculpt
