// A leaf's triangles four at a time: up to four triangles stored as one
// structure-of-arrays block (doubles, or the corners as floats when that is
// lossless) and tested with AVX2, one triangle per lane, in double
// precision. Internal to stages/bvh_wide.cpp (the 8-wide BVH's AVX2
// traversal).
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
#include <limits>

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

/// Four triangles whose corners are all exactly floats, stored as those
/// floats: (p0, p1, p2) per lane; 144 bytes, half a TriangleBlock.
///
/// Why lossless: an OBJ mesh is read with float coordinates
/// (tinyobjloader's real_t), so an untransformed mesh's corners are floats
/// held in doubles. The test widens them back to the same doubles and forms
/// e1 = p1 - p0, e2 = p2 - p0 in double, as TriangleBlock's builder and the
/// reference test do (InlineMollerTrumbore::stored, reference::
/// intersect_triangle), so every lane computes the same bits as from a
/// TriangleBlock. A block with any other corner (a transformed mesh, a
/// generated one) stays a TriangleBlock (bvh_wide.cpp, make_blocks).
struct alignas(16) FloatCornerBlock {
    float p[3][3][4];  ///< [corner][axis][lane]

    FloatCornerBlock() {
        for (auto& corner : p)
            for (auto& axis : corner)
                for (float& v : axis)
                    v = NAN;  // an unused lane never hits (NaN widens to NaN)
    }
    /// Whether a corner is stored without loss (NaN and infinities are too).
    static bool exact(const Vec3& v) {
        for (int k = 0; k < 3; ++k) {
            const double x = v[k];
            if (std::isnan(x) || std::isinf(x)) continue;
            // Beyond float's range the conversion is undefined: not a float.
            if (!(std::fabs(x) <= double(std::numeric_limits<float>::max())) || double(float(x)) != x)
                return false;
        }
        return true;
    }
    void set(int lane, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
        for (int k = 0; k < 3; ++k) {
            p[0][k][lane] = float(p0[k]);
            p[1][k][lane] = float(p1[k]);
            p[2][k][lane] = float(p2[k]);
        }
    }
    Vec3 corner(int c, int lane) const { return Vec3(p[c][0][lane], p[c][1][lane], p[c][2][lane]); }
};

#if defined(__x86_64__) || defined(__i386__)
/// A block's four triangles in registers, one per lane: p0, e1, e2.
struct BlockLanes {
    __m256d p0x, p0y, p0z, e1x, e1y, e1z, e2x, e2y, e2z;
};

[[gnu::target("avx2")]] inline BlockLanes load_lanes(const TriangleBlock& b) {
    return {_mm256_load_pd(b.p0[0]), _mm256_load_pd(b.p0[1]), _mm256_load_pd(b.p0[2]),
            _mm256_load_pd(b.e1[0]), _mm256_load_pd(b.e1[1]), _mm256_load_pd(b.e1[2]),
            _mm256_load_pd(b.e2[0]), _mm256_load_pd(b.e2[1]), _mm256_load_pd(b.e2[2])};
}

/// Four floats widened to doubles (exact).
[[gnu::target("avx2")]] inline __m256d widen(const float* p) {
    return _mm256_cvtps_pd(_mm_load_ps(p));
}

/// The corners widened to double (exact), the edges subtracted in double:
/// the bits TriangleBlock would hold.
[[gnu::target("avx2")]] inline BlockLanes load_lanes(const FloatCornerBlock& b) {
    const __m256d p0x = widen(b.p[0][0]), p0y = widen(b.p[0][1]), p0z = widen(b.p[0][2]);
    return {p0x,
            p0y,
            p0z,
            _mm256_sub_pd(widen(b.p[1][0]), p0x),
            _mm256_sub_pd(widen(b.p[1][1]), p0y),
            _mm256_sub_pd(widen(b.p[1][2]), p0z),
            _mm256_sub_pd(widen(b.p[2][0]), p0x),
            _mm256_sub_pd(widen(b.p[2][1]), p0y),
            _mm256_sub_pd(widen(b.p[2][2]), p0z)};
}

/// The four lanes' Moller-Trumbore tests against the ray o + t d, t in
/// [t_min, t_max]: bit i set when lane i hits; its t, b1, b2 go to t[i],
/// b1[i], b2[i] (other lanes' entries are meaningless). The lanes loaded
/// once can serve several rays (a packet's).
[[gnu::target("avx2")]] inline unsigned intersect_lanes(const BlockLanes& b, const Vec3& o, const Vec3& d,
                                                        double t_min, double t_max, double t[4], double b1[4],
                                                        double b2[4]) {
    const __m256d dx = _mm256_set1_pd(d.x), dy = _mm256_set1_pd(d.y), dz = _mm256_set1_pd(d.z);
    const __m256d e1x = b.e1x, e1y = b.e1y, e1z = b.e1z;
    const __m256d e2x = b.e2x, e2y = b.e2y, e2z = b.e2z;
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
    const __m256d sx = _mm256_sub_pd(_mm256_set1_pd(o.x), b.p0x);
    const __m256d sy = _mm256_sub_pd(_mm256_set1_pd(o.y), b.p0y);
    const __m256d sz = _mm256_sub_pd(_mm256_set1_pd(o.z), b.p0z);
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

/// intersect_lanes on a TriangleBlock or a FloatCornerBlock (the same
/// answers for the same triangles).
template <class Block>
[[gnu::target("avx2")]] inline unsigned intersect_block(const Block& block, const Vec3& o, const Vec3& d,
                                                        double t_min, double t_max, double t[4], double b1[4],
                                                        double b2[4]) {
    return intersect_lanes(load_lanes(block), o, d, t_min, t_max, t, b1, b2);
}
#endif

}  // namespace pt::bvh_kernels
