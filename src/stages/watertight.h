// The arithmetic of the watertight ray-triangle test (Woop, Benthin and
// Wald, JCGT 2013), shared by reference::intersect_triangle_watertight and
// the reference BVH's inlined leaf test, so both give the same bits. The
// per-ray part (which axis becomes z, the shear) is computed once per ray.
// See stages/intersect_watertight.cpp for why the test is watertight.
#pragma once

#include <utility>

#include "core/ray.h"
#include "core/vec3.h"

namespace pt {

/// The ray transformed so that it runs along +z from the origin.
struct WatertightRay {
    int kx = 0, ky = 1, kz = 2;  ///< permuted axes; kz is where |d| is largest
    double sx = 0, sy = 0, sz = 0;  ///< shear constants d_x/d_z, d_y/d_z, 1/d_z
    bool valid = false;            ///< false for a zero or NaN direction
};

inline WatertightRay prepare_watertight(const Ray& ray) {
    WatertightRay w;
    w.kz = max_dimension(abs(ray.d));
    w.kx = (w.kz + 1) % 3;
    w.ky = (w.kx + 1) % 3;
    // Swapping x and y when d_z < 0 keeps the winding, and so the signs of U, V, W.
    if (ray.d[w.kz] < 0) std::swap(w.kx, w.ky);
    w.valid = ray.d[w.kz] != 0.0;  // false for 0 and NaN
    if (!w.valid) return w;
    w.sx = ray.d[w.kx] / ray.d[w.kz];
    w.sy = ray.d[w.ky] / ray.d[w.kz];
    w.sz = 1.0 / ray.d[w.kz];
    return w;
}

/// The watertight test on corners p0, p1, p2: on a hit within
/// [t_min, t_max], sets t and the barycentrics b1, b2 of p1 and p2.
inline bool watertight_hit(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Ray& ray, const WatertightRay& w,
                           double& t, double& b1, double& b2) {
    if (!w.valid) return false;
    // Vertices relative to the ray origin, sheared so the ray is the +z axis.
    const Vec3 a = p0 - ray.o, b = p1 - ray.o, c = p2 - ray.o;
    const double ax = a[w.kx] - w.sx * a[w.kz], ay = a[w.ky] - w.sy * a[w.kz];
    const double bx = b[w.kx] - w.sx * b[w.kz], by = b[w.ky] - w.sy * b[w.kz];
    const double cx = c[w.kx] - w.sx * c[w.kz], cy = c[w.ky] - w.sy * c[w.kz];
    // Scaled barycentrics: 2D edge functions seen from the ray. An edge
    // shared by two triangles has the same endpoints in both, so its edge
    // function is the same number with opposite signs.
    double u = cx * by - cy * bx;
    double v = ax * cy - ay * cx;
    double e = bx * ay - by * ax;
    if (u == 0.0 || v == 0.0 || e == 0.0) {
        // Exactly on an edge after rounding: decide in more precision (the paper's fallback).
        using LD = long double;
        u = double(LD(cx) * LD(by) - LD(cy) * LD(bx));
        v = double(LD(ax) * LD(cy) - LD(ay) * LD(cx));
        e = double(LD(bx) * LD(ay) - LD(by) * LD(ax));
    }
    // Inside when all three share a sign (either winding); zeros count as inside.
    if ((u < 0 || v < 0 || e < 0) && (u > 0 || v > 0 || e > 0)) return false;
    const double det = u + v + e;
    if (!(det != 0.0)) return false;  // degenerate or edge-on triangle, or NaN
    const double t_scaled = u * (w.sz * a[w.kz]) + v * (w.sz * b[w.kz]) + e * (w.sz * c[w.kz]);
    const double inv_det = 1.0 / det;
    const double th = t_scaled * inv_det;
    if (!(th >= ray.t_min && th <= ray.t_max)) return false;
    t = th;
    b1 = v * inv_det;
    b2 = e * inv_det;
    return true;
}

}  // namespace pt
