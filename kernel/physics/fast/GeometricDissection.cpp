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
        bool inLower = true;       ///< the separator is the lower half's boundary (else the upper's)
    };
    Split split(std::size_t begin, std::size_t end, int axis);

    const GeometricGraph& graph_;
    std::vector<std::uint32_t> order_;
    std::vector<std::uint32_t> mark_;    ///< per node: the stamp of the half it was last put in
    std::vector<std::uint8_t> boundary_; ///< per node: has a neighbour in the other half (last split)
    std::vector<std::uint32_t> buffer_;
    std::vector<std::pair<double, std::uint32_t>> keys_; ///< scratch of split()
    std::uint32_t stamp_ = 0;
    std::size_t topSeparator_ = 0;
    bool top_ = true;
};

/// Orders order_[begin, end) by coordinate `axis` (ties by node number) around its median, marks
/// the two halves and their boundary nodes, and returns the smaller boundary.
Dissector::Split Dissector::split(std::size_t begin, std::size_t end, int axis) {
    // The selection runs on a contiguous copy of the keys (the positions are scattered).
    const std::size_t middle = begin + (end - begin) / 2;
    keys_.resize(end - begin);
    for (std::size_t k = begin; k < end; ++k)
        keys_[k - begin] = {graph_.coordinates[order_[k]][static_cast<std::size_t>(axis)], order_[k]};
    std::nth_element(keys_.begin(), keys_.begin() + static_cast<std::ptrdiff_t>(middle - begin),
                     keys_.end()); // by coordinate, ties by node number
    for (std::size_t k = begin; k < end; ++k)
        order_[k] = keys_[k - begin].second;
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
    return lowerBoundary <= upperBoundary ? Split{lowerBoundary, true} : Split{upperBoundary, false};
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
    const auto extent = [&](int a) { return high[static_cast<std::size_t>(a)] - low[static_cast<std::size_t>(a)]; };
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
    const std::size_t middle = begin + (end - begin) / 2;
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
    assert(nextLower == lowerCount && nextUpper == lowerCount + upperCount && nextSeparator == count);
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
