// The slab test of one ray against the W boxes of a wide BVH node
// (stages/bvh_wide.h), three ways with the same answers: a portable scalar
// loop over the lanes, SSE for 4-wide nodes, AVX for 8-wide ones. Internal
// to stages/bvh_wide.cpp.
//
// Each lane is exactly bvh_kernels::slab_test: (bound - origin) * (1 / d)
// per plane, the near distance the largest of t_min and the three near
// plane distances, the far one the smallest of t_max and the far ones, and
// a hit when near <= far * kFarScale. The SIMD versions use the same float
// operations in the same order; MAXPS/MINPS (and their AVX forms) return
// their second operand when one is NaN, which is what the scalar selects
// `t0 > t_near ? t0 : t_near` do, so a NaN distance (a ray in a slab's
// plane) never replaces t_near or t_far in any version (bvh_kernels.h).
#pragma once

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

#include "stages/accelerator.h"
#include "stages/bvh_kernels.h"
#include "stages/bvh_packet_frustum.h"
#include "stages/bvh_wide.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define PT_WIDE_BVH_X86 1
#else
#define PT_WIDE_BVH_X86 0
#endif

namespace pt::bvh_kernels {

/// The portable version: a loop over the lanes.
template <int W>
struct ScalarWideSlab {
    ScalarWideSlab() = default;
    explicit ScalarWideSlab(const SlabRay& s) : slab(&s) {}
    const SlabRay* slab = nullptr;  ///< the ray, prepared (outlives this)

    /// Bit i set when the ray enters child i's box before t_max; the entry
    /// distances go to t_enter.
    unsigned test(const WideBvhNode<W>& node, float t_max, float t_enter[W]) const {
        unsigned mask = 0;
        for (int i = 0; i < W; ++i) {
            float t_near = slab->t_min, t_far = t_max;
            for (int a = 0; a < 3; ++a) {
                float t0 = (node.bounds[slab->near_plane[a]][i] - slab->o_near[a]) * slab->inv_near[a];
                float t1 = (node.bounds[slab->far_plane[a]][i] - slab->o_far[a]) * slab->inv_far[a];
                t_near = t0 > t_near ? t0 : t_near;
                t_far = t1 < t_far ? t1 : t_far;
            }
            t_enter[i] = t_near;
            if (t_near <= t_far * kFarScale) mask |= 1u << i;
        }
        return mask & node.valid;
    }
};

/// A packet of up to kPacketSize rays against one node, one ray at a time
/// with the single-ray test `Slab`: for each child hit by some active ray,
/// the rays that hit it (lane_rays) and the smallest entry distance among
/// them (lane_t); returns the mask of those children. Entries of children
/// no ray hits are left unset.
template <int W, class Slab>
struct PerRayPacketSlab {
    explicit PerRayPacketSlab(const SlabRay* slabs) {
        for (int k = 0; k < kPacketSize; ++k)
            boxes[k] = Slab(slabs[k]);
    }
    Slab boxes[kPacketSize];

    unsigned test(const WideBvhNode<W>& node, uint32_t active, const float* t_box, uint32_t lane_rays[W],
                  float lane_t[W]) const {
        unsigned any = 0;
        for (int i = 0; i < W; ++i) {
            lane_rays[i] = 0;
            lane_t[i] = INFINITY;
        }
        for (; active != 0; active &= active - 1) {
            int k = __builtin_ctz(active);
            alignas(32) float t_enter[W];
            unsigned mask = boxes[k].test(node, t_box[k], t_enter);
            any |= mask;
            for (; mask != 0; mask &= mask - 1) {
                int i = __builtin_ctz(mask);
                lane_rays[i] |= 1u << k;
                lane_t[i] = t_enter[i] < lane_t[i] ? t_enter[i] : lane_t[i];
            }
        }
        return any;
    }

    /// Bit k set when t <= t_cull[k]: ray k's closest hit has not passed t.
    static unsigned not_passed(float t, const float* t_cull) {
        unsigned rays = 0;
        for (int k = 0; k < kPacketSize; ++k)
            rays |= (t <= t_cull[k] ? 1u : 0u) << k;
        return rays;
    }
};

#if PT_WIDE_BVH_X86

/// 4 lanes with SSE (every x86-64 processor has it). The ray's values are
/// broadcast once per ray, not once per node.
struct SseWideSlab {
    SseWideSlab() = default;
    explicit SseWideSlab(const SlabRay& s) : slab(&s) {
        for (int a = 0; a < 3; ++a) {
            o_near[a] = _mm_set1_ps(s.o_near[a]);
            o_far[a] = _mm_set1_ps(s.o_far[a]);
            inv_near[a] = _mm_set1_ps(s.inv_near[a]);
            inv_far[a] = _mm_set1_ps(s.inv_far[a]);
        }
        t_min = _mm_set1_ps(s.t_min);
    }
    const SlabRay* slab = nullptr;
    __m128 o_near[3], o_far[3], inv_near[3], inv_far[3], t_min;

    unsigned test(const WideBvhNode<4>& node, float t_max, float t_enter[4]) const {
        __m128 t_near = t_min, t_far = _mm_set1_ps(t_max);
        for (int a = 0; a < 3; ++a) {
            __m128 t0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[slab->near_plane[a]]), o_near[a]), inv_near[a]);
            __m128 t1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[slab->far_plane[a]]), o_far[a]), inv_far[a]);
            t_near = _mm_max_ps(t0, t_near);  // t0 > t_near ? t0 : t_near (NaN keeps t_near)
            t_far = _mm_min_ps(t1, t_far);    // t1 < t_far ? t1 : t_far
        }
        _mm_storeu_ps(t_enter, t_near);
        __m128 hit = _mm_cmple_ps(t_near, _mm_mul_ps(t_far, _mm_set1_ps(kFarScale)));
        return unsigned(_mm_movemask_ps(hit)) & node.valid;
    }
};

/// SlabRay's constructor without data-dependent branches, with AVX2: the
/// same fields bit for bit (tests/bvh compares the two on hard rays). The
/// scalar constructor's branches on each direction's sign and on each
/// origin's rounding (float_up/float_down) are unpredictable for incoherent
/// rays and cost about a tenth of such a ray (docs/bvh_history.md, seventh run); here
/// the three axes go through one division and blends: next_float_up and
/// next_float_down become an integer step of the float's bits (+1 or -1 by
/// its sign, a zero first made +0 or -0, an infinity kept), chosen per lane
/// where the scalar code would call them. Only functions compiled for AVX2
/// may call it.
[[gnu::target("avx2")]] inline SlabRay make_slab_ray_avx(const Ray& ray, bool float_scene) {
    SlabRay s;
    s.t_min = float_down(ray.t_min);
    const double o_max = std::max({std::fabs(ray.o.x), std::fabs(ray.o.y), std::fabs(ray.o.z)});
    const double d_max = std::max({std::fabs(ray.d.x), std::fabs(ray.d.y), std::fabs(ray.d.z)});
    const bool visit_all = !float_scene || !(o_max <= 1e30) || !(d_max >= 1e-7);

    // A mask of 4 x 32 bits from the low 4 bits of a MOVMSKPD result.
    const __m128i lane_bits = _mm_setr_epi32(1, 2, 4, 8);
    auto lanes = [&lane_bits](int bits) {
        return _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(bits), lane_bits), lane_bits));
    };
    const __m128 sign = _mm_set1_ps(-0.0f), inf = _mm_set1_ps(INFINITY), zero = _mm_setzero_ps();
    const __m128i one = _mm_set1_epi32(1);

    const __m256d o = _mm256_setr_pd(ray.o.x, ray.o.y, ray.o.z, 0.0);
    const __m256d d = _mm256_setr_pd(ray.d.x, ray.d.y, ray.d.z, 1.0);
    const __m256d inv = _mm256_div_pd(_mm256_set1_pd(1.0), d);
    const int neg_bits = _mm256_movemask_pd(inv) & 7;  // signbit(1 / d)
    const __m128 negative = lanes(neg_bits);
    const __m128 inv_far = _mm256_cvtpd_ps(inv);  // float(inv)
    // inv_near: +-FLT_MAX where float(inv) is infinite though d != 0.
    const __m128 overflow = _mm_and_ps(_mm_cmpeq_ps(_mm_andnot_ps(sign, inv_far), inf),
                                       lanes(_mm256_movemask_pd(_mm256_cmp_pd(d, _mm256_setzero_pd(), _CMP_NEQ_UQ))));
    const __m128 inv_near =
        _mm_blendv_ps(inv_far, _mm_or_ps(_mm_and_ps(inv_far, sign), _mm_set1_ps(FLT_MAX)), overflow);

    __m128 o_near, o_far;
    if (visit_all) {
        o_near = _mm_blendv_ps(inf, _mm_xor_ps(inf, sign), negative);  // negative ? -inf : inf
        o_far = _mm_xor_ps(o_near, sign);
    } else {
        const __m128 f = _mm256_cvtpd_ps(o);
        const __m256d back = _mm256_cvtps_pd(f);
        // float_up: next_float_up(f) where double(f) < o.
        const __m128 fu = _mm_andnot_ps(_mm_cmpeq_ps(f, zero), f);  // -0 -> +0
        const __m128i ge = _mm_castps_si128(_mm_cmpge_ps(fu, zero));
        const __m128i step_up = _mm_sub_epi32(_mm_sub_epi32(_mm_setzero_si128(), _mm_add_epi32(ge, ge)), one);
        __m128 next_up = _mm_castsi128_ps(_mm_add_epi32(_mm_castps_si128(fu), step_up));
        next_up = _mm_blendv_ps(next_up, f, _mm_cmpeq_ps(f, inf));
        const __m128 up = _mm_blendv_ps(f, next_up, lanes(_mm256_movemask_pd(_mm256_cmp_pd(back, o, _CMP_LT_OQ))));
        // float_down: next_float_down(f) where double(f) > o.
        const __m128 fd = _mm_or_ps(f, _mm_and_ps(_mm_cmpeq_ps(f, zero), sign));  // +0 -> -0
        const __m128i gt = _mm_castps_si128(_mm_cmpgt_ps(fd, zero));
        const __m128i step_down = _mm_add_epi32(_mm_add_epi32(gt, gt), one);
        __m128 next_down = _mm_castsi128_ps(_mm_add_epi32(_mm_castps_si128(fd), step_down));
        next_down = _mm_blendv_ps(next_down, f, _mm_cmpeq_ps(f, _mm_xor_ps(inf, sign)));
        const __m128 down =
            _mm_blendv_ps(f, next_down, lanes(_mm256_movemask_pd(_mm256_cmp_pd(back, o, _CMP_GT_OQ))));
        o_near = _mm_blendv_ps(up, down, negative);
        o_far = _mm_blendv_ps(down, up, negative);
    }
    alignas(16) float v[4];
    _mm_store_ps(v, o_near);
    std::memcpy(s.o_near, v, sizeof s.o_near);
    _mm_store_ps(v, o_far);
    std::memcpy(s.o_far, v, sizeof s.o_far);
    _mm_store_ps(v, inv_near);
    std::memcpy(s.inv_near, v, sizeof s.inv_near);
    _mm_store_ps(v, inv_far);
    std::memcpy(s.inv_far, v, sizeof s.inv_far);
    for (int a = 0; a < 3; ++a) {
        const uint32_t n = uint32_t(neg_bits >> a & 1);
        s.negative[a] = n != 0;
        s.near_plane[a] = uint32_t(a) + 3 * n;
        s.far_plane[a] = uint32_t(a) + 3 * (1 - n);
    }
    return s;
}

/// 8 lanes with AVX. Only functions compiled for AVX2 (target attribute) may
/// construct or call it; stages/bvh_wide.cpp checks the processor first.
/// Not "fma": with FMA enabled GCC contracts a * b - c * d in the inlined
/// double-precision triangle test into fused operations, which changes its
/// bits and with them the agreement with the linear scan.
struct AvxWideSlab {
    AvxWideSlab() = default;
    [[gnu::target("avx2")]] explicit AvxWideSlab(const SlabRay& s) : slab(&s) {
        for (int a = 0; a < 3; ++a) {
            o_near[a] = _mm256_set1_ps(s.o_near[a]);
            o_far[a] = _mm256_set1_ps(s.o_far[a]);
            inv_near[a] = _mm256_set1_ps(s.inv_near[a]);
            inv_far[a] = _mm256_set1_ps(s.inv_far[a]);
        }
        t_min = _mm256_set1_ps(s.t_min);
    }
    const SlabRay* slab = nullptr;
    __m256 o_near[3], o_far[3], inv_near[3], inv_far[3], t_min;

    [[gnu::target("avx2")]] unsigned test(const WideBvhNode<8>& node, float t_max, float t_enter[8]) const {
        __m256 t_near = t_min, t_far = _mm256_set1_ps(t_max);
        for (int a = 0; a < 3; ++a) {
            __m256 t0 =
                _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node.bounds[slab->near_plane[a]]), o_near[a]), inv_near[a]);
            __m256 t1 =
                _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node.bounds[slab->far_plane[a]]), o_far[a]), inv_far[a]);
            t_near = _mm256_max_ps(t0, t_near);
            t_far = _mm256_min_ps(t1, t_far);
        }
        _mm256_storeu_ps(t_enter, t_near);
        __m256 hit = _mm256_cmp_ps(t_near, _mm256_mul_ps(t_far, _mm256_set1_ps(kFarScale)), _CMP_LE_OQ);
        return unsigned(_mm256_movemask_ps(hit)) & node.valid;
    }
};

static_assert(kPacketSize == 8, "AvxPacketSlab holds one ray per AVX lane");

/// A packet of 8 rays against an 8-wide node with the rays in the AVX
/// lanes ("transposed"): each child box is tested against all rays at once,
/// so the rays that hit it come out of one MOVMSKPS with no branch per ray.
/// Per lane the operations are bvh_kernels::slab_test's: the near plane is
/// picked per ray by the sign of its direction (BLENDVPS with the sign
/// mask, where the single-ray test indexes the plane), then the same
/// subtract, multiply, max and min in the same order. Only functions
/// compiled for AVX2 may use it (AvxWideSlab). The children that no ray
/// of the packet can hit are first cleared all at once by the packet's
/// frustum (bvh_packet_frustum.h), so only the others are tested ray by ray.
struct AvxPacketSlab {
    /// From rays prepared at once (bvh_packet_rays.h).
    [[gnu::target("avx2")]] explicit AvxPacketSlab(const AvxPacketRays& p) : frustum(p) {
        for (int a = 0; a < 3; ++a) {
            o_near[a] = p.o_near[a];
            o_far[a] = p.o_far[a];
            inv_near[a] = inv_far[a] = negative[a] = p.inv[a];  // the sign bit selects in BLENDVPS
        }
        t_min = p.t_min;
    }
    /// From SlabRays built one by one.
    [[gnu::target("avx2")]] explicit AvxPacketSlab(const SlabRay* slabs) : frustum(slabs) {
        for (int a = 0; a < 3; ++a) {
            alignas(32) float on[8], of[8], in[8], inf[8], neg[8];
            for (int k = 0; k < 8; ++k) {
                on[k] = slabs[k].o_near[a];
                of[k] = slabs[k].o_far[a];
                in[k] = slabs[k].inv_near[a];
                inf[k] = slabs[k].inv_far[a];
                neg[k] = slabs[k].negative[a] ? -0.0f : 0.0f;  // the sign bit selects in BLENDVPS
            }
            o_near[a] = _mm256_load_ps(on);
            o_far[a] = _mm256_load_ps(of);
            inv_near[a] = _mm256_load_ps(in);
            inv_far[a] = _mm256_load_ps(inf);
            negative[a] = _mm256_load_ps(neg);
        }
        alignas(32) float tm[8];
        for (int k = 0; k < 8; ++k)
            tm[k] = slabs[k].t_min;
        t_min = _mm256_load_ps(tm);
    }
    AvxPacketFrustum frustum;
    __m256 o_near[3], o_far[3], inv_near[3], inv_far[3], negative[3], t_min;

    [[gnu::target("avx2")]] unsigned test(const WideBvhNode<8>& node, uint32_t active, const float* t_box,
                                          uint32_t lane_rays[8], float lane_t[8]) const {
        const __m256 t_max = _mm256_load_ps(t_box);  // -inf in unused lanes: no hit there
        const __m256 scale = _mm256_set1_ps(kFarScale), inf = _mm256_set1_ps(INFINITY);
        unsigned candidates = node.valid;
        if (frustum.usable) {
            // The largest box t_max of the packet (a bound for the active rays').
            __m128 m = _mm_max_ps(_mm256_castps256_ps128(t_max), _mm256_extractf128_ps(t_max, 1));
            m = _mm_max_ps(m, _mm_movehl_ps(m, m));
            m = _mm_max_ss(m, _mm_shuffle_ps(m, m, 1));
            candidates = frustum.test(node, _mm_cvtss_f32(m));
        }
        unsigned any = 0;
        for (unsigned valid = candidates; valid != 0; valid &= valid - 1) {
            int c = __builtin_ctz(valid);
            __m256 t_near = t_min, t_far = t_max;
            for (int a = 0; a < 3; ++a) {
                __m256 lo = _mm256_set1_ps(node.bounds[a][c]), hi = _mm256_set1_ps(node.bounds[3 + a][c]);
                __m256 near_bound = _mm256_blendv_ps(lo, hi, negative[a]);
                __m256 far_bound = _mm256_blendv_ps(hi, lo, negative[a]);
                __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(near_bound, o_near[a]), inv_near[a]);
                __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(far_bound, o_far[a]), inv_far[a]);
                t_near = _mm256_max_ps(t0, t_near);
                t_far = _mm256_min_ps(t1, t_far);
            }
            __m256 hit = _mm256_cmp_ps(t_near, _mm256_mul_ps(t_far, scale), _CMP_LE_OQ);
            unsigned rays = unsigned(_mm256_movemask_ps(hit)) & active;
            if (rays == 0) continue;
            any |= 1u << c;
            lane_rays[c] = rays;
            // The smallest entry distance among the rays that hit: a horizontal min.
            __m256 t = _mm256_blendv_ps(inf, t_near, hit);
            __m128 m = _mm_min_ps(_mm256_castps256_ps128(t), _mm256_extractf128_ps(t, 1));
            m = _mm_min_ps(m, _mm_movehl_ps(m, m));
            m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
            lane_t[c] = _mm_cvtss_f32(m);
        }
        return any;
    }

    /// Bit k set when t <= t_cull[k] (t_cull: 32-byte aligned).
    [[gnu::target("avx2")]] static unsigned not_passed(float t, const float* t_cull) {
        return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(_mm256_set1_ps(t), _mm256_load_ps(t_cull), _CMP_LE_OQ)));
    }
};

#endif  // PT_WIDE_BVH_X86

}  // namespace pt::bvh_kernels
