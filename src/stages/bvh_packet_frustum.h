// A conservative test of a whole packet of rays against the 8 child boxes
// of a wide node at once: it clears a child only when no ray of the packet
// can hit its box, so the packet traversal (stages/bvh_wide.cpp) runs the
// exact per-ray box test (AvxPacketSlab, bvh_wide_slab.h) only on the few
// children that pass. Internal to stages/bvh_wide.cpp.
//
// Why: camera rays of neighbouring pixels form a thin pencil; most children
// of a node lie beside it, and testing each of them against the eight rays
// cost eight single-ray tests' worth of arithmetic per node. This test
// costs one single-ray test for all eight children.
//
// How (interval arithmetic over the packet; Boulos, Wald, Benthin, Shirley
// et al., "Packet-based Whitted and Distribution Ray Tracing", GI 2007, and
// Wald, Boulos and Shirley, "Ray Tracing Deformable Scenes Using Dynamic
// Bounding Volume Hierarchies", ACM TOG 2007): when every ray of the packet
// runs the same way along each axis, the near plane of a box is the same
// one for all rays, and each ray's near distance
//     t0_k = fl(fl(b - o_k) * inv_k)
// is bounded below by the smallest over the packet's extreme origin and
// reciprocal direction: rounding to float is monotone, so fl(b - o) is
// monotone in o, fl(x * inv) monotone in x and in inv (for a fixed sign of
// the other), and the minimum of the rounded corners is at most every
// ray's value. Likewise each far distance is bounded above. The largest
// lower near bound over the axes (and the smallest t_min) is then at most
// every ray's t_near, the smallest upper far bound (and the largest t_max)
// at least every ray's t_far, so "lower near > upper far * kFarScale"
// implies that every ray's own test fails. No answer changes: a child the
// test clears would have been missed by every ray, and every child it
// keeps still goes through the exact per-ray test.
//
// Used only when every ray of the packet has finite float reciprocals and
// finite rounded origins (no NaN can then arise in a used lane: its bounds
// are finite; the lanes are independent, and unused ones are masked) and
// the same direction sign per axis; otherwise `usable` is false and every
// child goes to the per-ray test.
#pragma once

#include <cmath>

#include "stages/bvh_kernels.h"
#include "stages/bvh_packet_rays.h"
#include "stages/bvh_wide.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace pt::bvh_kernels {

#if defined(__x86_64__) || defined(__i386__)

struct AvxPacketFrustum {
    bool usable = false;
    int near_plane[3] = {}, far_plane[3] = {};
    __m256 o_near[3], o_far[3];  ///< the extreme origins (see above), broadcast
    __m256 inv_lo[3], inv_hi[3];  ///< the smallest and largest reciprocal, broadcast
    __m256 t_min;                 ///< the smallest t_min, broadcast

    AvxPacketFrustum() = default;
    /// From the packet's kPacketSize prepared rays (unused entries repeat a used one).
    [[gnu::target("avx2")]] explicit AvxPacketFrustum(const SlabRay* slabs) {
        float tm = slabs[0].t_min;
        for (int a = 0; a < 3; ++a) {
            const bool negative = slabs[0].negative[a];
            float on = slabs[0].o_near[a], of = slabs[0].o_far[a];
            float lo = slabs[0].inv_near[a], hi = lo;
            for (int k = 0; k < kPacketSize; ++k) {
                const SlabRay& s = slabs[k];
                const float inv = s.inv_near[a];
                if (s.negative[a] != negative || !std::isfinite(inv) || s.inv_far[a] != inv ||
                    !std::isfinite(s.o_near[a]) || !std::isfinite(s.o_far[a]))
                    return;  // not usable
                lo = inv < lo ? inv : lo;
                hi = inv > hi ? inv : hi;
                // The origin that gives the smallest near distance and the
                // largest far one: direction positive, the near bound is
                // b - o with o largest, the far one b - o with o smallest;
                // negative, the other way round.
                on = (negative ? s.o_near[a] < on : s.o_near[a] > on) ? s.o_near[a] : on;
                of = (negative ? s.o_far[a] > of : s.o_far[a] < of) ? s.o_far[a] : of;
                if (a == 0 && s.t_min < tm) tm = s.t_min;
            }
            near_plane[a] = negative ? 3 + a : a;
            far_plane[a] = negative ? a : 3 + a;
            o_near[a] = _mm256_set1_ps(on);
            o_far[a] = _mm256_set1_ps(of);
            inv_lo[a] = _mm256_set1_ps(lo);
            inv_hi[a] = _mm256_set1_ps(hi);
        }
        t_min = _mm256_set1_ps(tm);
        usable = true;
    }

    /// From the packet's rays prepared at once (prepare_packet: every
    /// reciprocal and origin finite).
    [[gnu::target("avx2")]] explicit AvxPacketFrustum(const AvxPacketRays& p) {
        for (int a = 0; a < 3; ++a) {
            const int signs = _mm256_movemask_ps(p.inv[a]);
            if (signs != 0 && signs != 0xff) return;  // not usable
            const bool negative = signs != 0;
            near_plane[a] = negative ? 3 + a : a;
            far_plane[a] = negative ? a : 3 + a;
            o_near[a] = negative ? all_min(p.o_near[a]) : all_max(p.o_near[a]);
            o_far[a] = negative ? all_max(p.o_far[a]) : all_min(p.o_far[a]);
            inv_lo[a] = all_min(p.inv[a]);
            inv_hi[a] = all_max(p.inv[a]);
        }
        t_min = all_min(p.t_min);
        usable = true;
    }

    /// The smallest (largest) of the eight lanes, in every lane.
    [[gnu::target("avx2")]] static __m256 all_min(__m256 v) {
        v = _mm256_min_ps(v, _mm256_permute2f128_ps(v, v, 1));
        v = _mm256_min_ps(v, _mm256_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 3, 2)));
        return _mm256_min_ps(v, _mm256_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
    }
    [[gnu::target("avx2")]] static __m256 all_max(__m256 v) {
        v = _mm256_max_ps(v, _mm256_permute2f128_ps(v, v, 1));
        v = _mm256_max_ps(v, _mm256_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 3, 2)));
        return _mm256_max_ps(v, _mm256_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
    }

    /// Bit i clear when no ray of the packet (with box test ends at most
    /// t_max) can hit child i's box; only for a usable frustum.
    [[gnu::target("avx2")]] unsigned test(const WideBvhNode<8>& node, float t_max) const {
        __m256 t_near = t_min, t_far = _mm256_set1_ps(t_max);
        for (int a = 0; a < 3; ++a) {
            const __m256 xn = _mm256_sub_ps(_mm256_load_ps(node.bounds[near_plane[a]]), o_near[a]);
            const __m256 xf = _mm256_sub_ps(_mm256_load_ps(node.bounds[far_plane[a]]), o_far[a]);
            const __m256 t0 = _mm256_min_ps(_mm256_mul_ps(xn, inv_lo[a]), _mm256_mul_ps(xn, inv_hi[a]));
            const __m256 t1 = _mm256_max_ps(_mm256_mul_ps(xf, inv_lo[a]), _mm256_mul_ps(xf, inv_hi[a]));
            t_near = _mm256_max_ps(t0, t_near);
            t_far = _mm256_min_ps(t1, t_far);
        }
        const __m256 hit = _mm256_cmp_ps(t_near, _mm256_mul_ps(t_far, _mm256_set1_ps(kFarScale)), _CMP_LE_OQ);
        return unsigned(_mm256_movemask_ps(hit)) & node.valid;
    }
};

#endif

}  // namespace pt::bvh_kernels
