// SupernodalCholesky's schedule for a factorization on a pool: which supernodes run together as
// one task, in what order, and which wide supernodes the pool's threads share.
#include "physics/fast/SupernodalCholesky.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace netsculpt {

namespace {

// A subtree of the supernodal elimination tree with fewer flops than this share of the whole
// factorization is one task of the schedule (tiny supernodes are not worth a hand-over).
constexpr double kTaskShare = 1.0 / 64;
// A supernode that is a task by itself and has at least this many columns is shared by the
// threads of a pool (measured on the tube benches: smaller ones do not pay for the hand-over),
// its columns in ranges of about kSharedWidth.
constexpr std::int64_t kSharedColumns = 96;
constexpr std::int64_t kSharedWidth = 48;

} // namespace

// The factorization's schedule: tasks of whole small subtrees or single supernodes, children
// before parents, each waiting for the tasks below it; and the supernodes shared by a pool's
// threads (tasks of one supernode, wide enough), their columns in ranges of whole nodes.
void SupernodalCholesky::planSchedule(const std::vector<std::uint32_t>& parent) {
    const std::size_t supers = superStart_.size() - 1;
    std::vector<double> work(supers, 0.0), subtree(supers, 0.0);
    std::vector<std::uint32_t> firstInSubtree(supers);
    double total = 0;
    for (std::size_t s = 0; s < supers; ++s) {
        const double cols = static_cast<double>(superColumns(s));
        const double below = static_cast<double>(superRows(s) - superColumns(s));
        work[s] = cols * cols * cols / 3 + below * cols * cols + below * below * cols + 1e3;
        total += work[s];
        firstInSubtree[s] = static_cast<std::uint32_t>(s);
    }
    std::vector<std::uint32_t> subtreeSize(supers, 1);
    for (std::size_t s = 0; s < supers; ++s) {
        subtree[s] += work[s];
        if (parent[s] != kNone) {
            subtree[parent[s]] += subtree[s];
            subtreeSize[parent[s]] += subtreeSize[s];
            firstInSubtree[parent[s]] = std::min(firstInSubtree[parent[s]], firstInSubtree[s]);
        }
    }
    bool postordered = true;
    for (std::size_t s = 0; s < supers; ++s)
        postordered = postordered && firstInSubtree[s] + subtreeSize[s] == s + 1;
    const double threshold =
        postordered ? total * kTaskShare : std::numeric_limits<double>::infinity();
    taskStart_.assign(1, 0);
    taskSupers_.clear();
    std::vector<std::uint32_t> taskOf(supers, kNone);
    for (std::size_t s = 0; s < supers; ++s) {
        const bool small = subtree[s] < threshold;
        const bool root = !small || parent[s] == kNone || subtree[parent[s]] >= threshold;
        if (!root)
            continue; // runs with the task of its small subtree's root
        const auto task = static_cast<std::uint32_t>(taskStart_.size() - 1);
        const std::uint32_t first = small ? firstInSubtree[s] : static_cast<std::uint32_t>(s);
        for (std::uint32_t k = first; k <= s; ++k) {
            taskSupers_.push_back(k);
            taskOf[k] = task;
        }
        taskStart_.push_back(static_cast<std::uint32_t>(taskSupers_.size()));
    }
    const std::size_t tasks = taskStart_.size() - 1;
    taskParent_.assign(tasks, kNone);
    taskWaits_.assign(tasks, 0);
    for (std::size_t t = 0; t < tasks; ++t) {
        const std::uint32_t top = taskSupers_[taskStart_[t + 1] - 1];
        if (parent[top] != kNone) {
            taskParent_[t] = taskOf[parent[top]];
            ++taskWaits_[taskParent_[t]];
        }
    }

    // Shared supernodes: tasks of one supernode, wide enough; column ranges of whole nodes.
    splitStart_.assign(supers + 1, 0);
    splitColumns_.clear();
    sharedSupernodes_ = 0;
    for (std::size_t t = 0; t < tasks; ++t) {
        if (taskStart_[t + 1] - taskStart_[t] != 1)
            continue;
        const std::uint32_t s = taskSupers_[taskStart_[t]];
        const std::int64_t cols = superColumns(s);
        if (cols < kSharedColumns)
            continue;
        const std::int64_t ranges =
            std::max<std::int64_t>(2, (cols + kSharedWidth / 2) / kSharedWidth);
        for (std::int64_t r = 0; r <= ranges; ++r)
            splitColumns_.push_back(static_cast<std::uint32_t>(3 * (cols / 3 * r / ranges) +
                                                               (r == ranges ? cols % 3 : 0)));
        splitStart_[s + 1] = static_cast<std::uint32_t>(ranges + 1);
        ++sharedSupernodes_;
    }
    for (std::size_t s = 0; s < supers; ++s)
        splitStart_[s + 1] += splitStart_[s];
}

} // namespace netsculpt
