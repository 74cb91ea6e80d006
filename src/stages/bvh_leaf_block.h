// A leaf's triangles four at a time: up to four triangles stored as one
// structure-of-arrays block of doubles and tested with AVX2, one triangle
// per lane, in double precision. Internal to stages/bvh_wide.cpp (the
// 8-wide BVH's AVX2 traversal).
//
// Why: the SAH tree then can make leaves of up to four triangles (fewer
// nodes, a faster build: docs/bvh_history.md, "Build speed") without the rays
// paying for the extra triangle tests one at a time.
//
// Exactness: each lane performs exactly the reference Moller-Trumbore test
// (bvh_kernels::InlineMollerTrumbore::intersect, reference::intersect_triangle):
// the same IEEE double operations in the same order (cross, then dot as
// (x + y) + z, then times 1 / det), so t, b1 and b2 are its bits. No fused
// multiply-add: the callers are compiled for target "avx2" only, which has
// no FMA instruction for GCC to contract a product and a sum into (with
// "fma" enabled it would, and the bits would differ). The early exits of
// the scalar test become lane masks; the comparisons are the same
// (`det != 0` is true for NaN: _CMP_NEQ_UQ; the others are ordered, false
// for NaN), so a lane reports a hit exactly when the scalar test would.
// Unused lanes hold NaN corners, which fail the b1 test.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/vec3.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace pt::bvh_kernels {

/// Four triangles, (p0, e1 = p1 - p0, e2 = p2 - p0) per lane; 288 bytes.
struct alignas(32) TriangleBlock {
    double p0[3][4];  ///< [axis][lane]
    double e1[3][4];
    double e2[3][4];

    TriangleBlock() {
        for (int a = 0; a < 3; ++a)
            for (int l = 0; l < 4; ++l)
                p0[a][l] = e1[a][l] = e2[a][l] = NAN;  // an unused lane never hits
    }
    void set(int lane, const Vec3& p, const Vec3& a, const Vec3& b) {
        for (int k = 0; k < 3; ++k) {
            p0[k][lane] = p[k];
            e1[k][lane] = a[k];
            e2[k][lane] = b[k];
        }
    }
};

#if defined(__x86_64__) || defined(__i386__)
/// The four lanes' Moller-Trumbore tests against the ray o + t d, t in
/// [t_min, t_max]: bit i set when lane i hits; its t, b1, b2 go to t[i],
/// b1[i], b2[i] (other lanes' entries are meaningless).
[[gnu::target("avx2")]] inline unsigned intersect_block(const TriangleBlock& b, const Vec3& o,
                                                                             const Vec3& d, double t_min,
                                                                             double t_max, double t[4],
                                                                             double b1[4], double b2[4]) {
    const __m256d dx = _mm256_set1_pd(d.x), dy = _mm256_set1_pd(d.y), dz = _mm256_set1_pd(d.z);
    const __m256d e1x = _mm256_load_pd(b.e1[0]), e1y = _mm256_load_pd(b.e1[1]), e1z = _mm256_load_pd(b.e1[2]);
    const __m256d e2x = _mm256_load_pd(b.e2[0]), e2y = _mm256_load_pd(b.e2[1]), e2z = _mm256_load_pd(b.e2[2]);
    // pvec = cross(d, e2)
    const __m256d px = _mm256_sub_pd(_mm256_mul_pd(dy, e2z), _mm256_mul_pd(dz, e2y));
    const __m256d py = _mm256_sub_pd(_mm256_mul_pd(dz, e2x), _mm256_mul_pd(dx, e2z));
    const __m256d pz = _mm256_sub_pd(_mm256_mul_pd(dx, e2y), _mm256_mul_pd(dy, e2x));
    // det = dot(e1, pvec)
    const __m256d det = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(e1x, px), _mm256_mul_pd(e1y, py)),
                                      _mm256_mul_pd(e1z, pz));
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
    __m256d ok = _mm256_cmp_pd(det, zero, _CMP_NEQ_UQ);
    const __m256d inv_det = _mm256_div_pd(one, det);
    // s = o - p0
    const __m256d sx = _mm256_sub_pd(_mm256_set1_pd(o.x), _mm256_load_pd(b.p0[0]));
    const __m256d sy = _mm256_sub_pd(_mm256_set1_pd(o.y), _mm256_load_pd(b.p0[1]));
    const __m256d sz = _mm256_sub_pd(_mm256_set1_pd(o.z), _mm256_load_pd(b.p0[2]));
    // b1 = dot(s, pvec) * inv_det
    const __m256d u = _mm256_mul_pd(
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(sx, px), _mm256_mul_pd(sy, py)), _mm256_mul_pd(sz, pz)), inv_det);
    ok = _mm256_and_pd(ok, _mm256_and_pd(_mm256_cmp_pd(u, zero, _CMP_GE_OQ), _mm256_cmp_pd(u, one, _CMP_LE_OQ)));
    // qvec = cross(s, e1)
    const __m256d qx = _mm256_sub_pd(_mm256_mul_pd(sy, e1z), _mm256_mul_pd(sz, e1y));
    const __m256d qy = _mm256_sub_pd(_mm256_mul_pd(sz, e1x), _mm256_mul_pd(sx, e1z));
    const __m256d qz = _mm256_sub_pd(_mm256_mul_pd(sx, e1y), _mm256_mul_pd(sy, e1x));
    // b2 = dot(d, qvec) * inv_det
    const __m256d v = _mm256_mul_pd(
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, qx), _mm256_mul_pd(dy, qy)), _mm256_mul_pd(dz, qz)), inv_det);
    ok = _mm256_and_pd(ok, _mm256_and_pd(_mm256_cmp_pd(v, zero, _CMP_GE_OQ),
                                         _mm256_cmp_pd(_mm256_add_pd(u, v), one, _CMP_LE_OQ)));
    // t = dot(e2, qvec) * inv_det
    const __m256d tt = _mm256_mul_pd(
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(e2x, qx), _mm256_mul_pd(e2y, qy)), _mm256_mul_pd(e2z, qz)),
        inv_det);
    ok = _mm256_and_pd(ok, _mm256_and_pd(_mm256_cmp_pd(tt, _mm256_set1_pd(t_min), _CMP_GE_OQ),
                                         _mm256_cmp_pd(tt, _mm256_set1_pd(t_max), _CMP_LE_OQ)));
    const unsigned mask = unsigned(_mm256_movemask_pd(ok));
    if (mask != 0) {
        _mm256_storeu_pd(t, tt);
        _mm256_storeu_pd(b1, u);
        _mm256_storeu_pd(b2, v);
    }
    return mask;
}
#endif

}  // namespace pt::bvh_kernels
