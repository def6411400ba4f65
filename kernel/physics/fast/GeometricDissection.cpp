#include "physics/fast/GeometricDissection.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

namespace netsculpt {

namespace {

/// Dissects order_[begin, end) in place into [dissected lower part | dissected upper part |
/// separator]; the whole array is then the elimination order.
class Dissector {
  public:
    explicit Dissector(const GeometricGraph& graph) : graph_(graph) {
        const std::size_t nodes = graph.coordinates.size();
        order_.resize(nodes);
        for (std::size_t i = 0; i < nodes; ++i)
            order_[i] = static_cast<std::uint32_t>(i);
        mark_.assign(nodes, 0);
        boundary_.assign(nodes, 0);
        buffer_.resize(nodes);
    }

    void dissect(std::size_t begin, std::size_t end);
    std::vector<std::uint32_t>& order() { return order_; }
    std::size_t topSeparator() const { return topSeparator_; }

  private:
    struct Split {
        std::size_t separator = 0; ///< its node count
        bool inLower = true;    ///< the separator is the lower half's boundary (else the upper's)
        std::size_t middle = 0; ///< the upper half starts at order_[middle]
    };
    Split split(std::size_t begin, std::size_t end, int axis);

    const GeometricGraph& graph_;
    std::vector<std::uint32_t> order_;
    std::vector<std::uint32_t> mark_; ///< per node: the stamp of the half it was last put in
    /// Per node: has a neighbour in the other half (last split).
    std::vector<std::uint8_t> boundary_;
    std::vector<std::uint32_t> buffer_;
    std::vector<std::pair<double, std::uint32_t>> keys_; ///< scratch of split()
    std::uint32_t stamp_ = 0;
    std::size_t topSeparator_ = 0;
    bool top_ = true;
};

/// Splits order_[begin, end) along coordinate `axis` (ties by node number) at the widest gap
/// between consecutive coordinates within kSplitWindow of the median (the nearest to the median
/// among equal gaps): on a net that is between two rows or two columns of knots rather than
/// through one, whose separator is then one row or column instead of a jagged strip. Marks the
/// two halves and their boundary nodes; returns the smaller boundary.
Dissector::Split Dissector::split(std::size_t begin, std::size_t end, int axis) {
    // The selection runs on a contiguous copy of the keys (the positions are scattered).
    const std::size_t count = end - begin;
    keys_.resize(count);
    for (std::size_t k = begin; k < end; ++k)
        keys_[k - begin] = {graph_.coordinates[order_[k]][static_cast<std::size_t>(axis)],
                            order_[k]};
    const std::size_t half = count / 2;
    const auto window = static_cast<std::size_t>(kSplitWindow * static_cast<double>(count));
    std::size_t cut = half; // the lower half is keys_[0, cut)
    if (window >= 1 && half > window) {
        const std::size_t low = half - window, high = std::min(half + window, count - 1);
        const auto at = [&](std::size_t k) {
            return keys_.begin() + static_cast<std::ptrdiff_t>(k);
        };
        std::nth_element(keys_.begin(), at(low), keys_.end());
        std::nth_element(at(low), at(high), keys_.end());
        std::sort(at(low), at(high)); // keys_[low, high] in order, all others on their side
        double widest = -1;
        for (std::size_t k = low + 1; k <= high; ++k) {
            const double gap = keys_[k].first - keys_[k - 1].first;
            const std::size_t offCentre = k > half ? k - half : half - k;
            const std::size_t bestOff = cut > half ? cut - half : half - cut;
            if (gap > widest * (1 + 1e-9) || (gap >= widest * (1 - 1e-9) && offCentre < bestOff)) {
                widest = std::max(widest, gap);
                cut = k;
            }
        }
    } else {
        std::nth_element(keys_.begin(), keys_.begin() + static_cast<std::ptrdiff_t>(half),
                         keys_.end());
    }
    for (std::size_t k = begin; k < end; ++k)
        order_[k] = keys_[k - begin].second;
    const std::size_t middle = begin + cut;
    const std::uint32_t lower = ++stamp_, upper = ++stamp_;
    for (std::size_t k = begin; k < end; ++k)
        mark_[order_[k]] = k < middle ? lower : upper;
    std::size_t lowerBoundary = 0, upperBoundary = 0;
    for (std::size_t k = begin; k < end; ++k) {
        const std::uint32_t u = order_[k];
        const std::uint32_t other = k < middle ? upper : lower;
        std::uint8_t touches = 0;
        for (std::int64_t e = graph_.adjacencyStart[u]; e < graph_.adjacencyStart[u + 1]; ++e)
            if (mark_[graph_.adjacency[static_cast<std::size_t>(e)]] == other) {
                touches = 1;
                break;
            }
        boundary_[u] = touches;
        (k < middle ? lowerBoundary : upperBoundary) += touches;
    }
    return lowerBoundary <= upperBoundary ? Split{lowerBoundary, true, middle}
                                          : Split{upperBoundary, false, middle};
}

void Dissector::dissect(std::size_t begin, std::size_t end) {
    const std::size_t count = end - begin;
    if (count <= kDissectionLeaf) {
        std::sort(order_.begin() + static_cast<std::ptrdiff_t>(begin),
                  order_.begin() + static_cast<std::ptrdiff_t>(end));
        return;
    }
    // The axis whose median split has the smallest separator, among those whose extent is at
    // least kMinAxisShare of the largest (splitting across the thin side of a patch of surface
    // cuts it everywhere). Tried from the shortest to the longest, so that the split left in
    // order_ is most often the one chosen.
    std::array<double, 3> low, high;
    low.fill(std::numeric_limits<double>::infinity());
    high.fill(-std::numeric_limits<double>::infinity());
    for (std::size_t k = begin; k < end; ++k) {
        const auto& p = graph_.coordinates[order_[k]];
        for (std::size_t a = 0; a < 3; ++a) {
            low[a] = std::min(low[a], p[a]);
            high[a] = std::max(high[a], p[a]);
        }
    }
    std::array<int, 3> axes = {0, 1, 2};
    const auto extent = [&](int a) {
        return high[static_cast<std::size_t>(a)] - low[static_cast<std::size_t>(a)];
    };
    std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return extent(a) < extent(b); });
    int best = -1, last = -1;
    Split chosen;
    for (int a : axes) {
        if (!(extent(a) > 0) || extent(a) < kMinAxisShare * extent(axes[2]))
            continue;
        const Split s = split(begin, end, a);
        last = a;
        if (best < 0 || s.separator < chosen.separator) {
            best = a;
            chosen = s;
        }
    }
    if (best < 0) // all the nodes at one position: split by node number
        best = 0;
    if (best != last)
        chosen = split(begin, end, best);

    // [lower half minus separator | upper half minus separator | separator]
    const std::size_t middle = chosen.middle;
    const std::size_t lowerCount = middle - begin - (chosen.inLower ? chosen.separator : 0);
    const std::size_t upperCount = count - lowerCount - chosen.separator;
    std::size_t nextLower = 0, nextUpper = lowerCount, nextSeparator = lowerCount + upperCount;
    for (std::size_t k = begin; k < end; ++k) {
        const std::uint32_t u = order_[k];
        const bool inLower = k < middle;
        if (boundary_[u] && inLower == chosen.inLower)
            buffer_[nextSeparator++] = u;
        else
            buffer_[inLower ? nextLower++ : nextUpper++] = u;
    }
    assert(nextLower == lowerCount && nextUpper == lowerCount + upperCount &&
           nextSeparator == count);
    std::copy(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(count),
              order_.begin() + static_cast<std::ptrdiff_t>(begin));
    if (top_) {
        topSeparator_ = chosen.separator;
        top_ = false;
    }
    dissect(begin, begin + lowerCount);
    dissect(begin + lowerCount, begin + lowerCount + upperCount);
}

} // namespace

std::vector<std::uint32_t> geometricNestedDissection(const GeometricGraph& graph) {
    const std::size_t nodes = graph.coordinates.size();
    assert(graph.adjacencyStart.size() == nodes + 1);
    for (const auto& p : graph.coordinates)
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            return {};
    Dissector dissector(graph);
    dissector.dissect(0, nodes);
    if (static_cast<double>(dissector.topSeparator()) >
        kMaxTopSeparator * std::sqrt(static_cast<double>(nodes)) + kDissectionLeaf)
        return {};
    return std::move(dissector.order());
}

} // namespace netsculpt
