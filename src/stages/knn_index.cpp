// The query-side copy of a kd-tree's inner nodes (stages/knn_index.h).
#include "stages/knn_index.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
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

/// The depths of the shallowest and the deepest group below a range of n
/// points (the right range is never larger than the left one, so the
/// shallowest lies on the rightmost path and the deepest on the leftmost).
int group_depth(size_t n, bool deepest) {
    int depth = 0;
    for (; n > kKnnGroupBelow; ++depth) n = deepest ? n / 2 : n - n / 2 - 1;
    return depth;
}

void copy_nodes(const KdTree& tree, KnnIndex& index, size_t lo, size_t hi, uint32_t h, bool in_group, bool& quantised) {
    if (!in_group && hi - lo <= kKnnGroupBelow) {
        if (quantised) quantised = quantise_group(tree, lo, hi, index.groups[h - index.first_group]);
        in_group = true;
    }
    if (hi - lo <= kScanBelow) return;
    const size_t mid = lo + (hi - lo) / 2;
    KnnNode& node = index.pairs[h / 2].node[h % 2];
    node.point = tree.points[mid];
    node.axis = tree.axis[mid];
    copy_nodes(tree, index, lo, mid, 2 * h, in_group, quantised);
    copy_nodes(tree, index, mid + 1, hi, 2 * h + 1, in_group, quantised);
}

/// The search reads inner nodes from the index: node h, and while it is
/// examined the lines of its four grandchildren's pairs and its eight
/// great-grandchildren's (its children's pair was fetched by its parent).
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
        // And the four lines of its eight great-grandchildren: a random
        // query misses the cache on the lower levels, and two levels of
        // lead did not hide it (issue 19, round 6).
        if (4 * h + 3 < count) {
            __builtin_prefetch(&pairs[4 * h]);
            __builtin_prefetch(&pairs[4 * h + 1]);
            __builtin_prefetch(&pairs[4 * h + 2]);
            __builtin_prefetch(&pairs[4 * h + 3]);
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

/// When fewer than k points lie within the guess, the query collects once
/// more from this times the guess (a radius 1.22 times as large) before it
/// falls back to the search without a guess (PT_KNN_RETRY2 to try others,
/// 0 for none; docs/photon_mapping.md).
#ifndef PT_KNN_RETRY2
#define PT_KNN_RETRY2 1.5
#endif
constexpr double kRetryGrowth2 = PT_KNN_RETRY2;

/// What a thread remembers of its last two queries on an index with one k:
/// their k-th squared distances (infinity: no answer of k points).
struct QueryMemory {
    const KnnIndex* index = nullptr;
    size_t k = 0;
    double kth_dist2[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    Vec3 last_p{std::numeric_limits<double>::infinity()};  ///< the last query's point
};

/// Without the quantised groups, a query within this many times the last
/// k-th squared distance of the last query's point is taken as coherent (its
/// buckets are likely cached) and scans them as it meets them; a farther one
/// lists them first and prefetches their lines (chosen with `bench kdtree`,
/// docs/photon_mapping.md).
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

/// The ranks (how many of the m keys are smaller) of the keys of blocks
/// v .. v + B - 1, eight keys each: the B blocks held in registers, each of
/// the m keys broadcast once and compared with all of them, so that every
/// lane counts for its own key and no horizontal sum is needed (issue 19,
/// round 6: the rank step 0.12 us faster per query than one key against
/// all blocks with a horizontal sum each).
constexpr size_t kRankBlocks = 6;
template <int B>
[[gnu::target("avx2"), gnu::always_inline]] inline void rank_blocks(const float* key, size_t m, size_t v, uint32_t* rank) {
    __m256 mine[B];
    __m256i nearer[B];
    for (int b = 0; b < B; ++b) {
        mine[b] = _mm256_loadu_ps(key + 8 * (v + b));
        nearer[b] = _mm256_setzero_si256();
    }
    for (size_t j = 0; j < m; ++j) {
        const __m256 kj = _mm256_broadcast_ss(key + j);
        for (int b = 0; b < B; ++b)
            nearer[b] = _mm256_sub_epi32(nearer[b], _mm256_castps_si256(_mm256_cmp_ps(kj, mine[b], _CMP_LT_OQ)));
    }
    for (int b = 0; b < B; ++b) _mm256_storeu_si256(reinterpret_cast<__m256i*>(rank + 8 * (v + b)), nearer[b]);
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
/// `far`: the query is not coherent (see kCoherent2), so its groups'
/// candidates are prefetched as each group is filtered.
/// `quantised` (the groups) only with `prefetch`: groups are listed as they
/// are reached, never scanned as they come.
enum class Collected { kAnswer, kFewer, kTie, kCrowded };
[[gnu::target("avx2")]] Collected collect_search(const KdTree& tree, const IndexNodes& nodes, const Vec3& p, size_t k,
                                                 double bound, bool prefetch, bool far, const KnnIndex* quantised, double* best,
                                                 uint32_t* best_at) {
    // At most this many points within the guess are ranked; more (a guess
    // too large for this query) go to the sorted insertion. Through the
    // groups every point within the guess is collected before the count is
    // known, so ranking up to 4k + 16 of them costs less than the insertion's
    // second traversal (bench kdtree: 3.5% of random queries crowded at
    // 2k + 16, 0.06% at 4k + 16, and 1.0 to 1.06 times as fast).
    const size_t capacity = (quantised ? 4 : 2) * k + 16;
    constexpr int kMaxBuckets = 64;
    thread_local std::vector<double> dist2_storage;
    thread_local std::vector<uint32_t> at_storage, order_storage;
    thread_local std::vector<float> key_storage;
    thread_local std::vector<uint32_t> rank_storage;
    const size_t storage = capacity + kKnnGroupBelow * (kMaxBuckets + 1);
    if (at_storage.size() < storage) {
        dist2_storage.resize(storage);
        at_storage.resize(storage);
        order_storage.resize(storage);
        key_storage.resize(capacity + kScanBelow + 8);
        rank_storage.resize(capacity + kScanBelow + 8);
    }
    double* dist2 = dist2_storage.data();
    uint32_t* at = at_storage.data();
    const Vec3* points = tree.points.data();
    const uint32_t* ids = tree.ids.data();
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
    uint32_t bucket_lo[kMaxBuckets], bucket_hi[kMaxBuckets], bucket_heap[kMaxBuckets];
    int bucket_count = 0;
    constexpr int kStackSize = 128;
    kdtree_detail::PendingCell stack[kStackSize];
    int top = 0;
    kdtree_detail::Cell cell = kdtree_detail::Cell::root(tree);
    double offset[3] = {0, 0, 0};
    for (;;) {
        if (quantised) kdtree_detail::descend_to_bucket<kKnnGroupBelow>(nodes, p, cell, offset, stack, top);
        else kdtree_detail::descend_to_bucket(nodes, p, cell, offset, stack, top);
        if (prefetch) {
            // The bound is fixed, so every bucket reached is scanned: listed
            // now with its lines prefetched and scanned after the traversal,
            // so that the misses on the buckets overlap.
            if (bucket_count == kMaxBuckets) return Collected::kCrowded;
            bucket_lo[bucket_count] = cell.lo;
            bucket_hi[bucket_count] = cell.hi;
            bucket_heap[bucket_count++] = cell.heap;
            if (quantised) {
                const char* group = reinterpret_cast<const char*>(&quantised->groups[cell.heap - quantised->first_group]);
                __builtin_prefetch(group);
                __builtin_prefetch(group + 64);
                __builtin_prefetch(group + 128);
                __builtin_prefetch(group + 192);
            } else {
                prefetch_bucket(points + cell.lo);
            }
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
    if (quantised) {
        // The quantised groups name the points that may lie within the
        // bound (a few more than do); only those are read from the tree,
        // their lines prefetched first, and kept by their exact distance:
        // the same points as a scan of the groups' buckets and inner nodes
        // keeps.
        uint32_t* candidate = order_storage.data();
        size_t candidates = 0;
        // Each candidate's lines prefetched, and its id's line too: the
        // answers' ids are looked up at the end, a miss each otherwise.
        auto take = [&](uint32_t lo, uint64_t mask) {
            for (; mask; mask &= mask - 1) {
                const uint32_t c = lo + uint32_t(__builtin_ctzll(mask));
                candidate[candidates++] = c;
                __builtin_prefetch(points + c);
                __builtin_prefetch(reinterpret_cast<const char*>(points + c) + sizeof(Vec3) - 1);
                __builtin_prefetch(ids + c);
            }
        };
        auto filter = [&](int b) {
            return knn_group_candidates(quantised->groups[bucket_heap[b] - quantised->first_group], bucket_hi[b] - bucket_lo[b], p, bound);
        };
        if (far) {
            // The candidates of a far query are prefetched as soon as their
            // group is filtered: their misses overlap the filter of the next
            // groups (whose lines may still be on their way).
            for (int b = 0; b < bucket_count; ++b) take(bucket_lo[b], filter(b));
        } else {
            // A coherent query's groups and points are cached: all groups
            // filtered first, in a loop without a data-dependent branch, so
            // that the processor overlaps them, and then the candidates taken.
            uint64_t masks[kMaxBuckets];
            for (int b = 0; b < bucket_count; ++b) masks[b] = filter(b);
            for (int b = 0; b < bucket_count; ++b) take(bucket_lo[b], masks[b]);
        }
        for (size_t i = 0; i < candidates; ++i) {
            const double d2 = (points[candidate[i]] - p).norm2();
            dist2[m] = d2;
            at[m] = candidate[i];
            m += d2 <= bound;
        }
        if (m > capacity) return Collected::kCrowded;
    } else {
        for (int b = 0; b < bucket_count; ++b)
            if (!scan(bucket_lo[b], bucket_hi[b])) return Collected::kCrowded;
    }
    if (m < k) return Collected::kFewer;
    // Ranks on float keys, padded with infinity to whole vectors.
    float* key = key_storage.data();
    for (size_t i = 0; i < m; ++i) key[i] = float(dist2[i]);
    const size_t vectors = (m + 7) / 8;
    for (size_t i = m; i < 8 * vectors; ++i) key[i] = std::numeric_limits<float>::infinity();
    uint32_t* order = order_storage.data();
    uint32_t* rank = rank_storage.data();
    // Six blocks at a time: 12 registers for the keys and their counts.
    for (size_t v = 0; v < vectors;) {
        const size_t b = std::min<size_t>(vectors - v, kRankBlocks);
        switch (b) {
            case 6: rank_blocks<6>(key, m, v, rank); break;
            case 5: rank_blocks<5>(key, m, v, rank); break;
            case 4: rank_blocks<4>(key, m, v, rank); break;
            case 3: rank_blocks<3>(key, m, v, rank); break;
            case 2: rank_blocks<2>(key, m, v, rank); break;
            default: rank_blocks<1>(key, m, v, rank); break;
        }
        v += b;
    }
    // How many ranks lie below k, and their sum, per lane (a padding lane
    // ranks m >= k: never counted). When k lie below, a lane's sum is at
    // most k(k - 1), which fits in 32 bits for the k this runs with.
    const __m256i kk = _mm256_set1_epi32(int(k));
    __m256i below_v = _mm256_setzero_si256(), sum_v = _mm256_setzero_si256();
    for (size_t v = 0; v < vectors; ++v) {
        const __m256i r = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(rank + 8 * v));
        const __m256i in = _mm256_cmpgt_epi32(kk, r);
        below_v = _mm256_sub_epi32(below_v, in);
        sum_v = _mm256_add_epi32(sum_v, _mm256_and_si256(in, r));
    }
    for (size_t i = 0; i < m; ++i) order[rank[i]] = uint32_t(i);  // rank < m
    alignas(32) uint32_t lanes[8], sums[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), below_v);
    _mm256_store_si256(reinterpret_cast<__m256i*>(sums), sum_v);
    size_t below = 0, rank_sum = 0;
    for (int l = 0; l < 8; ++l) {
        below += lanes[l];
        rank_sum += sums[l];
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
    if (tree.empty()) return index;
    // Groups are numbered 2^shallowest .. 2^(deepest + 1) - 1.
    index.first_group = uint32_t(1) << group_depth(tree.size(), false);
    index.groups.resize((size_t(1) << (group_depth(tree.size(), true) + 1)) - index.first_group);
    const int depth = inner_depth(0, tree.size());
    // Numbers 1 .. 2^(depth + 1) - 1: pairs 0 .. 2^depth - 1.
    if (depth >= 0) index.pairs.resize(size_t(1) << depth);
    bool quantised = true;
    copy_nodes(tree, index, 0, tree.size(), 1, false, quantised);
    if (!quantised) {
        index.groups.clear();
        index.groups.shrink_to_fit();
    }
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
    // Through the quantised groups every query lists its groups first, a
    // coherent one too: filtering 64 cached points by their codes costs less
    // than scanning their doubles (bench kdtree, spatial order: 1.2 times
    // as fast; docs/photon_mapping.md, round 6). Without the groups only a
    // far query lists its buckets.
    auto collect = [&](double bound) {
        const bool groups = !index.groups.empty() && knn_group_filter_applies(p, bound);
        return collect_search(tree, nodes, p, kept, bound, groups || !coherent, !coherent, groups ? &index : nullptr, best, at);
    };
    double bound = guess;
    // The rank count's per-lane sums need k below 2^16 (see collect_search).
    Collected collected = guess < max_dist2 && avx2 && kept < 65536 ? collect(guess) : Collected::kCrowded;
    // Fewer than k points within the guess (too small for this query):
    // once more from kRetryGrowth2 times it before the search without one.
    if (kRetryGrowth2 > 1 && collected == Collected::kFewer && kRetryGrowth2 * guess < max_dist2) {
        bound = kRetryGrowth2 * guess;
        collected = collect(bound);
        ++guess_counts.retried;
    }
    if (collected == Collected::kAnswer) {
        answered = true;
        found = kept;
        ++guess_counts.guessed;
    } else if (bound < max_dist2 && collected == Collected::kCrowded) {
        bool ties = false;
        found = kdtree_detail::knn_search<IndexNodes, true>(tree, nodes, p, kept, bound, best, at, &ties);
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
