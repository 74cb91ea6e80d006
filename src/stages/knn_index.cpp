// The query-side copy of a kd-tree's inner nodes (stages/knn_index.h).
#include "stages/knn_index.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "stages/kdtree_search.h"

namespace pt {
namespace {

using kdtree_detail::kScanBelow;

/// The deepest inner node's depth below [lo, hi) (-1: a bucket).
int inner_depth(size_t lo, size_t hi) {
    if (hi - lo <= kScanBelow) return -1;
    const size_t mid = lo + (hi - lo) / 2;
    // The right range is never larger than the left one.
    return 1 + inner_depth(lo, mid);
}

void copy_nodes(const KdTree& tree, KnnIndex& index, size_t lo, size_t hi, uint32_t h) {
    if (hi - lo <= kScanBelow) return;
    const size_t mid = lo + (hi - lo) / 2;
    KnnNode& node = index.pairs[h / 2].node[h % 2];
    node.point = tree.points[mid];
    node.axis = tree.axis[mid];
    copy_nodes(tree, index, lo, mid, 2 * h);
    copy_nodes(tree, index, mid + 1, hi, 2 * h + 1);
}

/// The search reads inner nodes from the index: node h, and while it is
/// examined the line of its four grandchildren's pairs (its children's
/// pair was fetched by its parent).
struct IndexNodes {
    const KnnNodePair* pairs;
    uint32_t count;  // pairs held
    int axis(uint32_t, uint32_t h) const { return int(pairs[h / 2].node[h % 2].axis); }
    const Vec3& point(uint32_t, uint32_t h) const { return pairs[h / 2].node[h % 2].point; }
    void prefetch(uint32_t, uint32_t, uint32_t, uint32_t h) const {
        if (2 * h + 1 < count) {
            __builtin_prefetch(&pairs[2 * h]);
            __builtin_prefetch(&pairs[2 * h + 1]);
        }
    }
};

/// The first bound of a query is this times the larger k-th squared
/// distance of the last two queries (a radius 1.1 times as large): chosen
/// with `bench kdtree` (PT_KNN_GROWTH2 to try others; docs/photon_mapping.md).
#ifndef PT_KNN_GROWTH2
#define PT_KNN_GROWTH2 1.21
#endif
constexpr double kGuessGrowth2 = PT_KNN_GROWTH2;

/// What a thread remembers of its last two queries on an index with one k:
/// their k-th squared distances (infinity: no answer of k points).
struct QueryMemory {
    const KnnIndex* index = nullptr;
    size_t k = 0;
    double kth_dist2[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
};

/// This thread's memory for (index, k): pm's two maps alternate, so a few
/// slots, the oldest replaced. A slot that is not this query's starts at
/// infinity (no guess).
thread_local KnnGuessCounts guess_counts;

QueryMemory& query_memory(const KnnIndex* index, size_t k) {
    constexpr int kSlots = 4;
    thread_local QueryMemory slots[kSlots];
    thread_local int next = 0;
    for (QueryMemory& slot : slots)
        if (slot.index == index && slot.k == k) return slot;
    QueryMemory& slot = slots[next];
    next = (next + 1) % kSlots;
    slot = QueryMemory{};
    slot.index = index;
    slot.k = k;
    return slot;
}

}  // namespace

KnnIndex build_knn_index(const KdTree& tree) {
    KnnIndex index;
    index.tree_size = tree.size();
    const int depth = inner_depth(0, tree.size());
    if (depth < 0) return index;
    // Numbers 1 .. 2^(depth + 1) - 1: pairs 0 .. 2^depth - 1.
    index.pairs.resize(size_t(1) << depth);
    copy_nodes(tree, index, 0, tree.size(), 1);
    return index;
}

KnnGuessCounts knn_guess_counts() { return guess_counts; }

namespace reference {

void k_nearest(const KdTree& tree, const KnnIndex& index, const Vec3& p, int k, double max_dist2,
               std::vector<Neighbor>& out) {
    if (index.tree_size != tree.size())
        throw std::logic_error("k_nearest: the index was built from another tree");
    out.clear();
    if (k <= 0 || tree.empty() || max_dist2 < 0) return;
    const size_t kept = std::min(size_t(k), tree.size());
    const kdtree_detail::KnnScratch scratch = kdtree_detail::knn_scratch(kept);
    double* best = scratch.best;
    uint32_t* at = scratch.at;
    const IndexNodes nodes{index.pairs.data(), uint32_t(index.pairs.size())};
    // The larger k-th distance of this thread's last two queries on this
    // index with this k, grown by kGuessGrowth2, as the first bound (the
    // larger of two falls back half as often as the last one alone): see the
    // file comment.
    QueryMemory& memory = query_memory(&index, kept);
    const double guess = kGuessGrowth2 * std::max(memory.kth_dist2[0], memory.kth_dist2[1]);
    size_t found = 0;
    bool answered = false;
    if (guess < max_dist2) {
        bool ties = false;
        found = kdtree_detail::knn_search<IndexNodes, true>(tree, nodes, p, kept, guess, best, at, &ties);
        answered = found == kept && !ties;
        for (size_t i = 1; answered && i < found; ++i) answered = best[i - 1] < best[i];
        ++guess_counts.guessed;
        guess_counts.fell_back += !answered;
    }
    if (!answered) found = kdtree_detail::knn_search(tree, nodes, p, kept, max_dist2, best, at);
    memory.kth_dist2[1] = memory.kth_dist2[0];
    memory.kth_dist2[0] = found == kept ? best[kept - 1] : std::numeric_limits<double>::infinity();
    out.resize(found);
    for (size_t i = 0; i < found; ++i) out[i] = {tree.ids[at[i]], best[i]};
}

}  // namespace reference
}  // namespace pt
