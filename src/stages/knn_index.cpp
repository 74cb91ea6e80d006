// The query-side copy of a kd-tree's inner nodes (stages/knn_index.h).
#include "stages/knn_index.h"

#include <immintrin.h>

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
    Vec3 last_p{std::numeric_limits<double>::infinity()};  ///< the last query's point
};

/// A query within this many times the last k-th squared distance of the
/// last query's point is taken as coherent (its buckets are likely cached)
/// and scans them as it meets them; a farther one lists them first and
/// prefetches their lines (chosen with `bench kdtree`, docs/photon_mapping.md).
#ifndef PT_KNN_NEAR2
#define PT_KNN_NEAR2 16.0
#endif
constexpr double kCoherent2 = PT_KNN_NEAR2;

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


/// The lines of a bucket that starts at `first` (16 points of 24 bytes
/// touch at most 7 lines): a fixed count, no loop to mispredict.
inline void prefetch_bucket(const Vec3* first) {
    const char* line = reinterpret_cast<const char*>(first);
    __builtin_prefetch(line);
    __builtin_prefetch(line + 64);
    __builtin_prefetch(line + 128);
    __builtin_prefetch(line + 192);
    __builtin_prefetch(line + 256);
    __builtin_prefetch(line + 320);
    __builtin_prefetch(line + 383);
}

/// The query from a guessed bound, when the processor has AVX2: every point
/// within `bound` collected unsorted (exact double distances, appended
/// without a branch), then each one's rank (how many are nearer) counted
/// with AVX2 on float copies of the distances, eight per comparison, and
/// the k of rank below k placed at their ranks. The float conversion keeps
/// the order (it is monotone), so when the ranks below k are 0 .. k-1 each
/// once (their count is k and their sum k(k-1)/2; a tie among the k, or
/// between the k-th and the next, breaks one of the two), the k points are
/// the k nearest, with distinct distances, and no other point is as near as
/// the k-th: the answer of the exact search (kdtree_search.h) from any
/// bound. Otherwise the caller falls back: kFewer (fewer than k within the
/// bound), kTie, or kCrowded (more than 2k + 16 points within it: the
/// guess was too large for this query).
/// Why: with a good guess about 66 points lie within it (k = 50); keeping
/// them sorted as they come costs about 60 insertions with their shifts
/// and a mispredicted branch each (docs/photon_mapping.md), counting ranks
/// a few hundred vector operations.
/// With `prefetch` (a query far from the last one, whose buckets are
/// likely not cached) the buckets are listed during the traversal, their
/// lines prefetched, and scanned after it: the bound is fixed, so every
/// bucket reached will be scanned, and the misses overlap instead of
/// following one another (1.2 to 1.3 times as fast in random order; 1 to 3%
/// slower for coherent queries, which therefore scan as they go).
enum class Collected { kAnswer, kFewer, kTie, kCrowded };
[[gnu::target("avx2")]] Collected collect_search(const KdTree& tree, const IndexNodes& nodes, const Vec3& p, size_t k,
                                                 double bound, bool prefetch, double* best, uint32_t* best_at) {
    const size_t capacity = 2 * k + 16;
    thread_local std::vector<double> dist2_storage;
    thread_local std::vector<uint32_t> at_storage, order_storage;
    thread_local std::vector<float> key_storage;
    if (at_storage.size() < capacity + kScanBelow) {
        dist2_storage.resize(capacity + kScanBelow);
        at_storage.resize(capacity + kScanBelow);
        order_storage.resize(capacity + kScanBelow);
        key_storage.resize(capacity + kScanBelow + 8);
    }
    double* dist2 = dist2_storage.data();
    uint32_t* at = at_storage.data();
    const Vec3* points = tree.points.data();
    size_t m = 0;

    // Every point of the bucket [lo, hi) within the bound appended, without
    // a branch; false when the buffer could overflow.
    auto scan = [&](uint32_t lo, uint32_t hi) {
        if (m + kScanBelow > capacity) return false;
        for (uint32_t i = lo; i < hi; ++i) {
            const double d2 = (points[i] - p).norm2();
            dist2[m] = d2;
            at[m] = i;
            m += d2 <= bound;  // never a NaN
        }
        return true;
    };
    constexpr int kMaxBuckets = 64;
    uint32_t bucket_lo[kMaxBuckets], bucket_hi[kMaxBuckets];
    int bucket_count = 0;
    constexpr int kStackSize = 128;
    kdtree_detail::PendingCell stack[kStackSize];
    int top = 0;
    kdtree_detail::Cell cell = kdtree_detail::Cell::root(tree);
    double offset[3] = {0, 0, 0};
    for (;;) {
        kdtree_detail::descend_to_bucket(nodes, p, cell, offset, stack, top);
        if (prefetch) {
            // The bound is fixed, so every bucket reached is scanned: listed
            // now with its lines prefetched and scanned after the traversal,
            // so that the misses on the buckets overlap.
            if (bucket_count == kMaxBuckets) return Collected::kCrowded;
            bucket_lo[bucket_count] = cell.lo;
            bucket_hi[bucket_count++] = cell.hi;
            prefetch_bucket(points + cell.lo);
        } else if (!scan(cell.lo, cell.hi)) {
            return Collected::kCrowded;
        }
        // The bound is fixed: depth-first order, the far cells that can
        // still hold a point within it.
        const kdtree_detail::PendingCell* next = kdtree_detail::pop_within(stack, top, bound);
        if (!next) break;
        if (m >= capacity) return Collected::kCrowded;
        const double d2 = (nodes.point(next->node, next->heap / 2) - p).norm2();
        dist2[m] = d2;
        at[m] = next->node;
        m += d2 <= bound;
        cell = kdtree_detail::Cell::resume(*next, offset);
    }
    for (int b = 0; b < bucket_count; ++b)
        if (!scan(bucket_lo[b], bucket_hi[b])) return Collected::kCrowded;
    if (m < k) return Collected::kFewer;
    // Ranks on float keys, padded with infinity to whole vectors.
    float* key = key_storage.data();
    for (size_t i = 0; i < m; ++i) key[i] = float(dist2[i]);
    const size_t vectors = (m + 7) / 8;
    for (size_t i = m; i < 8 * vectors; ++i) key[i] = std::numeric_limits<float>::infinity();
    uint32_t* order = order_storage.data();
    size_t below = 0, rank_sum = 0;
    for (size_t i = 0; i < m; ++i) {
        const __m256 ki = _mm256_set1_ps(key[i]);
        __m256i nearer = _mm256_setzero_si256();
        for (size_t v = 0; v < vectors; ++v)
            nearer = _mm256_sub_epi32(nearer, _mm256_castps_si256(_mm256_cmp_ps(_mm256_loadu_ps(key + 8 * v), ki, _CMP_LT_OQ)));
        const __m128i sum4 = _mm_add_epi32(_mm256_castsi256_si128(nearer), _mm256_extracti128_si256(nearer, 1));
        const __m128i sum2 = _mm_add_epi32(sum4, _mm_shuffle_epi32(sum4, 0x4e));
        const uint32_t rank = uint32_t(_mm_cvtsi128_si32(_mm_add_epi32(sum2, _mm_shuffle_epi32(sum2, 0xb1))));
        order[rank] = uint32_t(i);  // rank < m
        const bool in = rank < k;
        below += in;
        rank_sum += in ? rank : 0;
    }
    if (below != k || rank_sum != k * (k - 1) / 2) return Collected::kTie;
    for (size_t r = 0; r < k; ++r) {
        best[r] = dist2[order[r]];
        best_at[r] = at[order[r]];
    }
    return Collected::kAnswer;
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
    static const bool avx2 = __builtin_cpu_supports("avx2") != 0;
    const bool coherent = (p - memory.last_p).norm2() <= kCoherent2 * memory.kth_dist2[0];
    memory.last_p = p;
    const Collected collected = guess < max_dist2 && avx2
                                    ? collect_search(tree, nodes, p, kept, guess, !coherent, best, at)
                                    : Collected::kCrowded;
    if (collected == Collected::kAnswer) {
        answered = true;
        found = kept;
        ++guess_counts.guessed;
    } else if (guess < max_dist2 && collected == Collected::kCrowded) {
        bool ties = false;
        found = kdtree_detail::knn_search<IndexNodes, true>(tree, nodes, p, kept, guess, best, at, &ties);
        answered = found == kept && !ties;
        for (size_t i = 1; answered && i < found; ++i) answered = best[i - 1] < best[i];
        ++guess_counts.guessed;
        ++guess_counts.crowded;
        guess_counts.fell_back += !answered;
    } else if (guess < max_dist2) {
        ++guess_counts.guessed;
        ++guess_counts.fell_back;
    }
    if (!answered) found = kdtree_detail::knn_search(tree, nodes, p, kept, max_dist2, best, at);
    memory.kth_dist2[1] = memory.kth_dist2[0];
    memory.kth_dist2[0] = found == kept ? best[kept - 1] : std::numeric_limits<double>::infinity();
    out.resize(found);
    for (size_t i = 0; i < found; ++i) out[i] = {tree.ids[at[i]], best[i]};
}

}  // namespace reference
}  // namespace pt
