// Sample warps: maps from uniform points u in [0, 1)^2 to directions or
// points with a known density (pdf), the building blocks of Monte Carlo
// estimators. Each warp has its pdf beside it; tests/statistical checks
// every pair with a chi-square test.
//
// Formulas: pbrt-v3 chapter 13 (Pharr, Jakob, Humphreys), and Shirley and
// Chiu, "A Low Distortion Map Between Disk and Square" (JGT 1997) for the
// concentric disk. Directions are in the local frame with the normal on +z.
//
// Every warp is finite for every u in [0, 1)^2, including u exactly 0, 0.5
// and 1 - 2^-24 (tests/statistical/test_warps.cpp checks these and runs a
// chi-square test of each warp against its pdf).
#pragma once

#include <cmath>

#include "core/frame.h"
#include "core/math.h"
#include "core/vec3.h"

namespace pt {

/// Uniform point on the unit disk, area pdf 1/pi (concentric map).
inline Vec2 sample_concentric_disk(Vec2 u) {
    double ox = 2.0 * u.x - 1.0, oy = 2.0 * u.y - 1.0;
    if (ox == 0 && oy == 0) return {0, 0};
    double r, theta;
    if (std::fabs(ox) > std::fabs(oy)) {
        r = ox;
        theta = (kPi / 4) * (oy / ox);
    } else {
        r = oy;
        theta = kPi / 2 - (kPi / 4) * (ox / oy);
    }
    return {r * std::cos(theta), r * std::sin(theta)};
}

/// Uniform direction on the hemisphere z >= 0, solid-angle pdf 1/(2 pi).
inline Vec3 sample_uniform_hemisphere(Vec2 u) {
    double z = u.x;
    double r = safe_sqrt(1.0 - z * z);
    double phi = kTwoPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline double uniform_hemisphere_pdf() { return kInvTwoPi; }

/// Cosine-weighted direction on the hemisphere z >= 0 (Malley's method),
/// solid-angle pdf cos(theta)/pi.
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
    Vec2 d = sample_concentric_disk(u);
    double z = safe_sqrt(1.0 - d.x * d.x - d.y * d.y);
    return {d.x, d.y, z};
}
inline double cosine_hemisphere_pdf(double cos_theta) { return cos_theta > 0 ? cos_theta * kInvPi : 0.0; }

/// Uniform direction on the unit sphere, solid-angle pdf 1/(4 pi).
inline Vec3 sample_uniform_sphere(Vec2 u) {
    double z = 1.0 - 2.0 * u.x;
    double r = safe_sqrt(1.0 - z * z);
    double phi = kTwoPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline double uniform_sphere_pdf() { return kInvFourPi; }

/// Uniform direction in the cone of directions within theta_max of +z,
/// solid-angle pdf 1 / (2 pi (1 - cos theta_max)) (pbrt-v3 section 13.6.4).
///
/// Takes one_minus_cos_max = 1 - cos(theta_max), in (0, 2], instead of
/// cos(theta_max): for the narrow cone of a distant light, cos(theta_max)
/// rounds to within an ulp of 1, so 1 - cos would cancel to 0 or to a
/// grossly wrong value. Callers compute it as sin^2 / (1 + cos) instead.
/// cos(theta) = 1 - u.x (1 - cos theta_max) is uniform in [cos theta_max, 1]
/// (Archimedes: equal heights of a sphere's zone have equal areas).
inline Vec3 sample_uniform_cone(Vec2 u, double one_minus_cos_max) {
    double one_minus_cos = u.x * one_minus_cos_max;
    double cos_theta = 1.0 - one_minus_cos;
    // sin^2 = (1 - cos)(1 + cos), exact for tiny angles where 1 - cos^2 cancels.
    double sin_theta = safe_sqrt(one_minus_cos * (2.0 - one_minus_cos));
    double phi = kTwoPi * u.y;
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}
inline double uniform_cone_pdf(double one_minus_cos_max) {
    return one_minus_cos_max > 0 ? 1.0 / (kTwoPi * one_minus_cos_max) : 0.0;
}

/// Uniform point on a triangle, as the barycentric weights (b1, b2) of its
/// second and third corners (the first weighs 1 - b1 - b2), the convention
/// of Hit. pdf 2 with respect to area in the (b1, b2) plane, i.e. 1 / area
/// on any triangle. Square-root warp of pbrt-v3 section 13.6.5: sqrt(u.x)
/// picks a line parallel to the first edge with density proportional to
/// its length, u.y a point on it.
inline Vec2 sample_uniform_triangle(Vec2 u) {
    double su = std::sqrt(u.x);
    return {1.0 - su, u.y * su};
}
inline double uniform_triangle_pdf() {
    return 2.0;
}

/// A point on the part of a sphere that is visible from a point outside it.
struct SphereCapSample {
    Vec3 p;          ///< point on the sphere, world space
    Vec3 n;          ///< unit outward normal at p
    Vec3 wi;         ///< unit direction from the reference point towards p
    double pdf = 0;  ///< solid-angle density of wi at the reference point; 0: no sample
};

/// Uniform direction in the cone that a sphere (center, radius) subtends at
/// `from`, and where it meets the sphere first (pbrt-v3 section 14.2.2):
/// only the cap facing `from` is ever chosen, so no sample is wasted on the
/// far side. pdf = 1 / (2 pi (1 - cos theta_max)), sin theta_max = r / d.
/// No sample (pdf 0) when `from` lies on or inside the sphere.
inline SphereCapSample sample_sphere_cap(Vec2 u, const Vec3& center, double radius,
                                         const Vec3& from) {
    SphereCapSample s;
    Vec3 axis = center - from;
    double d2 = axis.norm2();
    double sin2_max = radius * radius / d2;
    if (!(sin2_max < 1.0)) return s;  // inside or on the sphere (or NaN input)
    double d = std::sqrt(d2);
    axis = axis / d;
    double cos_max = safe_sqrt(1.0 - sin2_max);
    double one_minus_cos_max = sin2_max / (1.0 + cos_max);  // 1 - cos_max without cancellation
    Vec3 local = sample_uniform_cone(u, one_minus_cos_max);

    // The ray from `from` along the sampled direction meets the sphere where
    // the angle at the centre, between -axis and the hit point, is alpha with
    //   cos alpha = (d / r) sin^2 theta + cos theta sqrt(1 - (d / r)^2 sin^2 theta)
    // (law of sines in the triangle from, centre, hit point); (d/r)^2 sin^2
    // theta <= 1 inside the cone, and the safe square roots absorb rounding.
    double sin2_theta = local.x * local.x + local.y * local.y;
    double ratio2 = sin2_theta / sin2_max;  // (d / r)^2 sin^2 theta, in [0, 1]
    double cos_alpha =
        std::sqrt(ratio2) * std::sqrt(sin2_theta) + local.z * safe_sqrt(1.0 - ratio2);
    cos_alpha = clamp(cos_alpha, -1.0, 1.0);
    double sin_alpha = safe_sqrt(1.0 - cos_alpha * cos_alpha);
    double sin_theta = std::sqrt(sin2_theta);
    // The hit point's azimuth about the axis equals the direction's.
    double cos_phi = sin_theta > 0 ? local.x / sin_theta : 1.0;
    double sin_phi = sin_theta > 0 ? local.y / sin_theta : 0.0;

    // Any orthonormal frame about the axis will do.
    Frame frame(axis);
    s.n = frame.to_world(Vec3(sin_alpha * cos_phi, sin_alpha * sin_phi, -cos_alpha));
    s.n = s.n / s.n.norm();
    s.p = center + s.n * radius;
    s.wi = frame.to_world(local);
    s.pdf = uniform_cone_pdf(one_minus_cos_max);
    return s;
}

/// Solid-angle density of sample_sphere_cap at `from` for any direction that
/// hits the sphere; 0 when `from` is on or inside it.
inline double sphere_cap_pdf(const Vec3& center, double radius, const Vec3& from) {
    double sin2_max = radius * radius / (center - from).norm2();
    if (!(sin2_max < 1.0)) return 0.0;
    return uniform_cone_pdf(sin2_max / (1.0 + safe_sqrt(1.0 - sin2_max)));
}

/// Veach's power heuristic with exponent 2 (Veach 1997, section 9.2.4): the
/// weight of a sample drawn from strategy f (nf samples, density f_pdf) when
/// strategy g (ng samples, density g_pdf) could also have produced it:
///     w_f = (nf f_pdf)^2 / ((nf f_pdf)^2 + (ng g_pdf)^2).
/// Written as 1 / (1 + r^2), r = (ng g_pdf) / (nf f_pdf), so huge densities
/// (a light seen edge-on) never overflow to inf / inf = NaN.
inline double power_heuristic(double nf, double f_pdf, double ng, double g_pdf) {
    double f = nf * f_pdf, g = ng * g_pdf;
    if (!(f > 0)) return 0.0;
    if (std::isinf(f)) return std::isinf(g) ? 0.5 : 1.0;
    double r = g / f;
    return 1.0 / (1.0 + r * r);
}

/// Veach's balance heuristic (Veach 1997, section 9.2.2):
///     w_f = nf f_pdf / (nf f_pdf + ng g_pdf),
/// written as 1 / (1 + r) with r = (ng g_pdf) / (nf f_pdf) for the same
/// reason as power_heuristic; the same limits (0, 1, 0.5 for two deltas).
inline double balance_heuristic(double nf, double f_pdf, double ng, double g_pdf) {
    double f = nf * f_pdf, g = ng * g_pdf;
    if (!(f > 0)) return 0.0;
    if (std::isinf(f)) return std::isinf(g) ? 0.5 : 1.0;
    return 1.0 / (1.0 + g / f);
}

}  // namespace pt
