// Sample warps: maps from uniform points u in [0, 1)^2 to directions or
// points with a known density (pdf), the building blocks of Monte Carlo
// estimators. Each warp has its pdf beside it; tests/statistical checks
// every pair with a chi-square test.
//
// Formulas: pbrt-v3 chapter 13 (Pharr, Jakob, Humphreys), and Shirley and
// Chiu, "A Low Distortion Map Between Disk and Square" (JGT 1997) for the
// concentric disk. Directions are in the local frame with the normal on +z.
#pragma once

#include <cmath>

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

}  // namespace pt
