#pragma once
// The bars the compiler has added so far, as unordered pairs of knots, to skip a bar it meets
// twice (a seam's shared column). Internal to the model's compiler (Compiler.cpp).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <unordered_set>
#include <vector>

namespace netsculpt {

/// Each knot keeps the higher-numbered ends of its first kSlots bars in a flat table (a knot's
/// bars to the row below: two, or more at a gear), any further ones a hash set. A hash set of
/// every bar was a third of a 20,000-knot recompilation, which every drag step of the studio
/// runs.
class BarPairs {
  public:
    static constexpr std::size_t kSlots = 4;

    explicit BarPairs(std::size_t knots) : partners_(kSlots * knots, kNone) {}

    /// Adds the pair {a, b} (a != b, both below the knot count given); false when it is there
    /// already.
    bool insert(std::uint32_t a, std::uint32_t b) {
        const std::uint32_t low = std::min(a, b), high = std::max(a, b);
        std::uint32_t* slot = &partners_[kSlots * std::size_t{low}];
        for (std::size_t i = 0; i < kSlots; ++i) {
            if (slot[i] == high)
                return false;
            if (slot[i] == kNone) {
                slot[i] = high;
                return true;
            }
        }
        return more_.insert((std::uint64_t{low} << 32) | high).second;
    }

  private:
    static constexpr std::uint32_t kNone = 0xffffffffu;
    std::vector<std::uint32_t> partners_;
    std::unordered_set<std::uint64_t> more_;
};

} // namespace netsculpt
