// The quantised groups of the k-nearest query's index (stages/knn_index.h,
// issue 19, rounds 5 and 6): each subtree of at most kKnnGroupBelow points
// of the kd-tree has a copy of its points at 8 bits per coordinate, from
// which a conservative lower bound of each point's squared distance rules
// points out without reading their doubles. Only a filter: the points it
// does not rule out are read from the tree and kept by their exact distance.
#pragma once

#include <immintrin.h>

#include <cmath>
#include <cstdint>

#include "stages/kdtree.h"

namespace pt {

/// The quantised groups are the subtrees of at most this many points
/// reached by the descent (a group holds its buckets and the inner nodes
/// between them).
constexpr uint32_t kKnnGroupBelow = 64;

/// A group (at most kKnnGroupBelow points, in tree order) quantised to 8
/// bits per coordinate, one cache line per axis: point j lies within `step`
/// of origin + code[.][j] * step on each axis (the rounding leaves half a
/// step; the other half is margin). Only a filter: a point is read from
/// the tree before it is kept.
struct alignas(64) KnnGroup {
    uint8_t code[3][kKnnGroupBelow] = {};  ///< code[axis][j], point lo + j of the group [lo, hi)
    float origin[3] = {0, 0, 0};           ///< at or below the group's smallest coordinate on each axis
    float step = 0;                        ///< the group's largest extent / 255, rounded up (0: all points at origin)
};

/// Quantises the group [lo, hi) into `bucket` (see KnnGroup); false when
/// a coordinate is out of the filter's range or a point is not within
/// 0.75 steps of its code on each axis (then the index holds no groups).
bool quantise_group(const KdTree& tree, size_t lo, size_t hi, KnnGroup& bucket);

/// Whether knn_group_candidates' arithmetic is exact enough for p and
/// bound (coordinates and bound far below float's range; else it is not used).
bool knn_group_filter_applies(const Vec3& p, double bound);

/// Which of the n points of `group` may lie within `bound` (squared) of p:
/// bit j clear only when point j is certainly farther. Needs AVX2 (the
/// caller checks). Sixteen points per AVX2 operation, in integers (issue 19, round 6; round 5 computed it in float, eight per
/// operation). In units of the step s, point j lies within 0.75 of its code
/// c (quantise_group checks it), and the query at u = (p - origin) / s; with
/// q = floor(u) computed in double (error far below 0.25 for |u| < 2^14),
///     |x - p| / s >= |c - u| - 0.75 > |c - q| - 2,
/// so L = max(0, |c - q| - 2) per axis (16-bit lanes, q clamped to
/// [-16000, 16255], which only lowers L) is a lower bound, and a point is
/// dropped only when the exact integer L_x^2 + L_y^2 + L_z^2 (at most
/// 8 * 10^8, in 32-bit lanes) exceeds bound / s^2, rounded up. The bound is
/// one step looser than round 5's float one: 2% more candidates.
[[gnu::target("avx2")]] inline uint64_t knn_group_candidates(const KnnGroup& bucket, uint32_t n, const Vec3& p,
                                                             double bound) {
    const uint64_t all = n >= 64 ? ~uint64_t(0) : (uint64_t(1) << n) - 1;
    const double step = bucket.step;
    if (!(step > 0)) return all;
    const double q = bound / (step * step);
    if (!(q < 2e9)) return all;
    const __m256i limit = _mm256_set1_epi32(int32_t(q * (1 + 0x1p-48)) + 1);
    __m256i at[3];
    for (int a = 0; a < 3; ++a) {
        double u = std::floor((p[a] - double(bucket.origin[a])) / step);
        u = u >= -16000 ? (u <= 16255 ? u : 16255) : -16000;
        at[a] = _mm256_set1_epi16(int16_t(u));
    }
    const __m256i two = _mm256_set1_epi16(2), zero = _mm256_setzero_si256();
    uint64_t mask = 0;
    for (uint32_t block = 0; 16 * block < n; ++block) {
        __m256i low[3];
        for (int a = 0; a < 3; ++a) {
            const __m256i code = _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(bucket.code[a] + 16 * block)));
            low[a] = _mm256_subs_epu16(_mm256_abs_epi16(_mm256_sub_epi16(code, at[a])), two);
        }
        const __m256i xy_lo = _mm256_unpacklo_epi16(low[0], low[1]), xy_hi = _mm256_unpackhi_epi16(low[0], low[1]);
        const __m256i z_lo = _mm256_unpacklo_epi16(low[2], zero), z_hi = _mm256_unpackhi_epi16(low[2], zero);
        const __m256i sum_lo = _mm256_add_epi32(_mm256_madd_epi16(xy_lo, xy_lo), _mm256_madd_epi16(z_lo, z_lo));
        const __m256i sum_hi = _mm256_add_epi32(_mm256_madd_epi16(xy_hi, xy_hi), _mm256_madd_epi16(z_hi, z_hi));
        const uint32_t far_lo = uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(sum_lo, limit))));
        const uint32_t far_hi = uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(sum_hi, limit))));
        const uint64_t far = (far_lo & 0xF) | (far_hi & 0xF) << 4 | (far_lo & 0xF0) << 4 | (far_hi & 0xF0) << 8;
        mask |= far << (16 * block);
    }
    return ~mask & all;
}

}  // namespace pt
