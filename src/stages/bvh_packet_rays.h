// A packet's rays prepared for the box tests all at once: the fields of
// bvh_kernels::SlabRay for eight rays, one ray per AVX lane, computed with
// eight-lane (and four-lane double) instructions instead of eight scalar
// SlabRay constructions. Internal to stages/bvh_wide.cpp (the 8-wide AVX2
// packet traversal).
//
// Why: `perf` and a set-up-only run of `bench accel` showed that preparing
// a packet of camera rays one by one (three double divisions per ray,
// the directed roundings' branches, then the transposition into lanes)
// cost about as much as Embree's whole trace of the same rays.
//
// Exactness: each lane is SlabRay's arithmetic on its ray, bit for bit:
// 1 / d in double (VDIVPD), rounded to float to nearest (VCVTPD2PS, as the
// scalar conversion); the origin and t_min rounded down or up by the same
// rule as flat_bvh.h's float_down / float_up (convert to nearest, convert
// back, and step the bit pattern by one when the conversion went the wrong
// way, -0 and +0 handled as next_float_down / next_float_up do); t_max as
// box_t_max. SlabRay's special cases (a ray prepared to visit every box,
// and 1/d overflowing float or infinite) are not done here: when any ray
// of the packet needs one, prepare_packet returns false and the caller
// builds SlabRays one by one. tests/bvh/test_bvh_packet_rays.cpp compares
// every lane with SlabRay.
#pragma once

#include <cfloat>
#include <cstdint>

#include "core/ray.h"
#include "stages/accelerator.h"
#include "stages/bvh_kernels.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace pt::bvh_kernels {

#if defined(__x86_64__) || defined(__i386__)

/// SlabRay's fields, lane k for ray k (unused lanes repeat ray 0). inv is
/// both inv_near and inv_far; its sign bit is `negative` (BLENDVPS reads
/// it); t_box is box_t_max(ray.t_max).
struct AvxPacketRays {
    __m256 o_near[3], o_far[3], inv[3], t_min, t_box;
};

namespace packet_rays_detail {

/// Two four-lane double masks (all ones or zero per lane) as one eight-lane float mask.
[[gnu::target("avx2")]] inline __m256 pack_masks(__m256d lo, __m256d hi) {
    const __m256i even = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
    const __m256 a = _mm256_permutevar8x32_ps(_mm256_castpd_ps(lo), even);
    const __m256 b = _mm256_permutevar8x32_ps(_mm256_castpd_ps(hi), even);
    return _mm256_permute2f128_ps(a, b, 0x20);
}

/// x (eight doubles in two halves) rounded to float to nearest, and masks
/// of the lanes where that is above x and below x.
struct Rounded {
    __m256 f, above, below;
};
[[gnu::target("avx2")]] inline Rounded round_nearest(__m256d lo, __m256d hi) {
    Rounded r;
    const __m128 flo = _mm256_cvtpd_ps(lo), fhi = _mm256_cvtpd_ps(hi);
    r.f = _mm256_set_m128(fhi, flo);
    const __m256d blo = _mm256_cvtps_pd(flo), bhi = _mm256_cvtps_pd(fhi);
    r.above = pack_masks(_mm256_cmp_pd(blo, lo, _CMP_GT_OQ), _mm256_cmp_pd(bhi, hi, _CMP_GT_OQ));
    r.below = pack_masks(_mm256_cmp_pd(blo, lo, _CMP_LT_OQ), _mm256_cmp_pd(bhi, hi, _CMP_LT_OQ));
    return r;
}

/// float_down: where the nearest float is above x, next_float_down of it
/// (0 counts as -0; then one step: down for positive values, up in
/// magnitude for negative ones and -0).
[[gnu::target("avx2")]] inline __m256 float_down8(__m256d lo, __m256d hi) {
    const Rounded r = round_nearest(lo, hi);
    const __m256 zero = _mm256_setzero_ps(), sign = _mm256_set1_ps(-0.0f);
    const __m256 g = _mm256_or_ps(r.f, _mm256_and_ps(_mm256_cmp_ps(r.f, zero, _CMP_EQ_OQ), sign));
    const __m256i step = _mm256_or_si256(_mm256_set1_epi32(1),  // +1, or -1 where g > 0
                                         _mm256_castps_si256(_mm256_cmp_ps(g, zero, _CMP_GT_OQ)));
    const __m256 down = _mm256_castsi256_ps(_mm256_add_epi32(_mm256_castps_si256(g), step));
    return _mm256_blendv_ps(r.f, down, r.above);
}

/// float_up: where the nearest float is below x, next_float_up of it (-0
/// counts as +0; then one step: up for positive values and +0, down in
/// magnitude for negative ones).
[[gnu::target("avx2")]] inline __m256 float_up8(__m256d lo, __m256d hi) {
    const Rounded r = round_nearest(lo, hi);
    const __m256 zero = _mm256_setzero_ps();
    const __m256 g = _mm256_add_ps(r.f, zero);  // -0 + 0 = +0; every other value unchanged
    const __m256i step = _mm256_or_si256(_mm256_set1_epi32(1),  // +1, or -1 where g < 0
                                         _mm256_castps_si256(_mm256_cmp_ps(g, zero, _CMP_LT_OQ)));
    const __m256 up = _mm256_castsi256_ps(_mm256_add_epi32(_mm256_castps_si256(g), step));
    return _mm256_blendv_ps(r.f, up, r.below);
}

}  // namespace packet_rays_detail

/// Prepares rays[0..count) (1 <= count <= kPacketSize) as SlabRay(ray,
/// float_scene) would, into `out`; false, with `out` unspecified, when some
/// ray needs one of SlabRay's special cases (then use SlabRay).
[[gnu::target("avx2")]] inline bool prepare_packet(const Ray* rays, int count, bool float_scene,
                                                   AvxPacketRays& out) {
    using namespace packet_rays_detail;
    if (!float_scene) return false;
    const Ray* r[kPacketSize];
    for (int k = 0; k < kPacketSize; ++k)
        r[k] = &rays[k < count ? k : 0];
    const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
    __m256d d_max_lo = _mm256_setzero_pd(), d_max_hi = _mm256_setzero_pd();
    __m256d o_ok_lo = _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), o_ok_hi = o_ok_lo;
    __m256 inv_ok = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
    const __m256d one = _mm256_set1_pd(1.0), o_limit = _mm256_set1_pd(1e30);
    for (int a = 0; a < 3; ++a) {
        const __m256d dlo = _mm256_setr_pd(r[0]->d[a], r[1]->d[a], r[2]->d[a], r[3]->d[a]);
        const __m256d dhi = _mm256_setr_pd(r[4]->d[a], r[5]->d[a], r[6]->d[a], r[7]->d[a]);
        const __m256d olo = _mm256_setr_pd(r[0]->o[a], r[1]->o[a], r[2]->o[a], r[3]->o[a]);
        const __m256d ohi = _mm256_setr_pd(r[4]->o[a], r[5]->o[a], r[6]->o[a], r[7]->o[a]);
        // SlabRay's visit_all test: |o| <= 1e30 on every axis (false for NaN), max |d| >= 1e-7.
        o_ok_lo = _mm256_and_pd(o_ok_lo, _mm256_cmp_pd(_mm256_and_pd(olo, abs_mask), o_limit, _CMP_LE_OQ));
        o_ok_hi = _mm256_and_pd(o_ok_hi, _mm256_cmp_pd(_mm256_and_pd(ohi, abs_mask), o_limit, _CMP_LE_OQ));
        d_max_lo = _mm256_max_pd(_mm256_and_pd(dlo, abs_mask), d_max_lo);
        d_max_hi = _mm256_max_pd(_mm256_and_pd(dhi, abs_mask), d_max_hi);
        const __m256 inv = _mm256_set_m128(_mm256_cvtpd_ps(_mm256_div_pd(one, dhi)),
                                           _mm256_cvtpd_ps(_mm256_div_pd(one, dlo)));
        // Not infinite (1/d overflowed float, or d = 0) and not NaN.
        inv_ok = _mm256_and_ps(inv_ok, _mm256_cmp_ps(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), inv),
                                                     _mm256_set1_ps(FLT_MAX), _CMP_LE_OQ));
        out.inv[a] = inv;
        const __m256 up = float_up8(olo, ohi), down = float_down8(olo, ohi);
        out.o_near[a] = _mm256_blendv_ps(up, down, inv);  // negative: rounded down
        out.o_far[a] = _mm256_blendv_ps(down, up, inv);
    }
    const __m256d d_min = _mm256_set1_pd(1e-7);
    const __m256 ok = _mm256_and_ps(
        inv_ok, pack_masks(_mm256_and_pd(o_ok_lo, _mm256_cmp_pd(d_max_lo, d_min, _CMP_GE_OQ)),
                           _mm256_and_pd(o_ok_hi, _mm256_cmp_pd(d_max_hi, d_min, _CMP_GE_OQ))));
    if (_mm256_movemask_ps(ok) != 0xff) return false;
    out.t_min = float_down8(_mm256_setr_pd(r[0]->t_min, r[1]->t_min, r[2]->t_min, r[3]->t_min),
                            _mm256_setr_pd(r[4]->t_min, r[5]->t_min, r[6]->t_min, r[7]->t_min));
    // box_t_max: float_up(std::min(t_max, kFloatTraversalRange)); MINPD(a, b) is a < b ? a : b.
    const __m256d range = _mm256_set1_pd(kFloatTraversalRange);
    out.t_box = float_up8(
        _mm256_min_pd(range, _mm256_setr_pd(r[0]->t_max, r[1]->t_max, r[2]->t_max, r[3]->t_max)),
        _mm256_min_pd(range, _mm256_setr_pd(r[4]->t_max, r[5]->t_max, r[6]->t_max, r[7]->t_max)));
    return true;
}

#endif

}  // namespace pt::bvh_kernels
