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

#include "stages/bvh_kernels.h"
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
    explicit ScalarWideSlab(const SlabRay& s) : slab(s) {}
    const SlabRay& slab;

    /// Bit i set when the ray enters child i's box before t_max; the entry
    /// distances go to t_enter.
    unsigned test(const WideBvhNode<W>& node, float t_max, float t_enter[W]) const {
        unsigned mask = 0;
        for (int i = 0; i < W; ++i) {
            float t_near = slab.t_min, t_far = t_max;
            for (int a = 0; a < 3; ++a) {
                float t0 = (node.bounds[slab.near_plane[a]][i] - slab.o_near[a]) * slab.inv_near[a];
                float t1 = (node.bounds[slab.far_plane[a]][i] - slab.o_far[a]) * slab.inv_far[a];
                t_near = t0 > t_near ? t0 : t_near;
                t_far = t1 < t_far ? t1 : t_far;
            }
            t_enter[i] = t_near;
            if (t_near <= t_far * kFarScale) mask |= 1u << i;
        }
        return mask & node.valid;
    }
};

#if PT_WIDE_BVH_X86

/// 4 lanes with SSE (every x86-64 processor has it). The ray's values are
/// broadcast once per ray, not once per node.
struct SseWideSlab {
    explicit SseWideSlab(const SlabRay& s) : slab(s) {
        for (int a = 0; a < 3; ++a) {
            o_near[a] = _mm_set1_ps(s.o_near[a]);
            o_far[a] = _mm_set1_ps(s.o_far[a]);
            inv_near[a] = _mm_set1_ps(s.inv_near[a]);
            inv_far[a] = _mm_set1_ps(s.inv_far[a]);
        }
        t_min = _mm_set1_ps(s.t_min);
    }
    const SlabRay& slab;
    __m128 o_near[3], o_far[3], inv_near[3], inv_far[3], t_min;

    unsigned test(const WideBvhNode<4>& node, float t_max, float t_enter[4]) const {
        __m128 t_near = t_min, t_far = _mm_set1_ps(t_max);
        for (int a = 0; a < 3; ++a) {
            __m128 t0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[slab.near_plane[a]]), o_near[a]), inv_near[a]);
            __m128 t1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[slab.far_plane[a]]), o_far[a]), inv_far[a]);
            t_near = _mm_max_ps(t0, t_near);  // t0 > t_near ? t0 : t_near (NaN keeps t_near)
            t_far = _mm_min_ps(t1, t_far);    // t1 < t_far ? t1 : t_far
        }
        _mm_storeu_ps(t_enter, t_near);
        __m128 hit = _mm_cmple_ps(t_near, _mm_mul_ps(t_far, _mm_set1_ps(kFarScale)));
        return unsigned(_mm_movemask_ps(hit)) & node.valid;
    }
};

/// 8 lanes with AVX. Only functions compiled for AVX2 (target attribute) may
/// construct or call it; stages/bvh_wide.cpp checks the processor first.
/// Not "fma": with FMA enabled GCC contracts a * b - c * d in the inlined
/// double-precision triangle test into fused operations, which changes its
/// bits and with them the agreement with the linear scan.
struct AvxWideSlab {
    [[gnu::target("avx2")]] explicit AvxWideSlab(const SlabRay& s) : slab(s) {
        for (int a = 0; a < 3; ++a) {
            o_near[a] = _mm256_set1_ps(s.o_near[a]);
            o_far[a] = _mm256_set1_ps(s.o_far[a]);
            inv_near[a] = _mm256_set1_ps(s.inv_near[a]);
            inv_far[a] = _mm256_set1_ps(s.inv_far[a]);
        }
        t_min = _mm256_set1_ps(s.t_min);
    }
    const SlabRay& slab;
    __m256 o_near[3], o_far[3], inv_near[3], inv_far[3], t_min;

    [[gnu::target("avx2")]] unsigned test(const WideBvhNode<8>& node, float t_max, float t_enter[8]) const {
        __m256 t_near = t_min, t_far = _mm256_set1_ps(t_max);
        for (int a = 0; a < 3; ++a) {
            __m256 t0 =
                _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node.bounds[slab.near_plane[a]]), o_near[a]), inv_near[a]);
            __m256 t1 =
                _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node.bounds[slab.far_plane[a]]), o_far[a]), inv_far[a]);
            t_near = _mm256_max_ps(t0, t_near);
            t_far = _mm256_min_ps(t1, t_far);
        }
        _mm256_storeu_ps(t_enter, t_near);
        __m256 hit = _mm256_cmp_ps(t_near, _mm256_mul_ps(t_far, _mm256_set1_ps(kFarScale)), _CMP_LE_OQ);
        return unsigned(_mm256_movemask_ps(hit)) & node.valid;
    }
};

#endif  // PT_WIDE_BVH_X86

}  // namespace pt::bvh_kernels
