// Fresnel equations: the fraction of light a smooth interface reflects, for
// unpolarised light (the mean of the s- and p-polarised reflectances).
//
//   dielectric (glass): real indices on both sides; beyond the critical angle
//     sin(theta_t) = sin(theta_i) / eta >= 1 all light is reflected (total
//     internal reflection). Born and Wolf, "Principles of Optics", section
//     1.5; pbrt-v3 section 8.2.1.
//   conductor (metal): complex index eta + i k relative to the outside
//     medium; exact for unpolarised light (pbrt-v3 section 8.2.1, after
//     Born and Wolf), per colour channel.
//   artist-friendly conductor: eta and k from the normal-incidence
//     reflectance r (Gulbrandsen, "Artist Friendly Metallic Fresnel", JCGT
//     2014, with the edge tint equal to r), so that a metal can be given by
//     its colour (scene "reflectance", MTL Kd).
//
// Tests: tests/unit/test_materials.cpp (normal incidence ((n-1)/(n+1))^2,
// total internal reflection, grazing incidence 1, the reflectance round trip).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/color.h"
#include "core/math.h"

namespace pt {

/// Reflectance of a dielectric interface for light arriving at cos_i to
/// its normal (> 0: from the outside, whose index is 1, into index eta;
/// < 0: from the inside, leaving towards index 1), unpolarised. 1 under total
/// internal reflection.
inline double fresnel_dielectric(double cos_i, double eta) {
    cos_i = clamp(cos_i, -1.0, 1.0);
    if (cos_i < 0) {  // inside: swap the media
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);  // Snell: sin_t = sin_i / eta
    if (sin2_t >= 1.0) return 1.0;                        // total internal reflection
    double cos_t = safe_sqrt(1.0 - sin2_t);
    double r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    double r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (r_parallel * r_parallel + r_perpendicular * r_perpendicular);
}

/// Reflectance of a conductor with complex index eta + i k (relative to the
/// outside) at cos_i in [0, 1], one channel.
inline double fresnel_conductor(double cos_i, double eta, double k) {
    cos_i = clamp(cos_i, 0.0, 1.0);
    double cos2 = cos_i * cos_i, sin2 = 1.0 - cos2;
    double t0 = eta * eta - k * k - sin2;
    double a2_plus_b2 = std::sqrt(t0 * t0 + 4.0 * eta * eta * k * k);
    double a = safe_sqrt(0.5 * (a2_plus_b2 + t0));
    double t1 = a2_plus_b2 + cos2, t2 = 2.0 * a * cos_i;
    double rs = (t1 - t2) / (t1 + t2);
    double t3 = cos2 * a2_plus_b2 + sin2 * sin2, t4 = t2 * sin2;
    double rp = rs * (t3 - t4) / (t3 + t4);
    return 0.5 * (rp + rs);
}

inline Color fresnel_conductor(double cos_i, const Color& eta, const Color& k) {
    return {fresnel_conductor(cos_i, eta.r, k.r), fresnel_conductor(cos_i, eta.g, k.g),
            fresnel_conductor(cos_i, eta.b, k.b)};
}

/// eta and k of a conductor whose reflectance at normal incidence is r in
/// [0, 1) (Gulbrandsen 2014 with edge tint g = r): the metal "of colour r".
struct ConductorIndex {
    Color eta, k;
};
inline ConductorIndex conductor_from_reflectance(const Color& reflectance) {
    auto one = [](double r, double* eta, double* k) {
        r = std::clamp(r, 0.0, 0.999);  // r = 1 would need k = infinity
        double sqrt_r = std::sqrt(r);
        // n(r, g) with g = r: between the n of minimal and maximal edge tint.
        double n = r * (1.0 - r) / (1.0 + r) + (1.0 - r) * (1.0 + sqrt_r) / (1.0 - sqrt_r);
        // k from r = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2), solved for k.
        double k2 = (r * (n + 1.0) * (n + 1.0) - (n - 1.0) * (n - 1.0)) / (1.0 - r);
        *eta = n;
        *k = safe_sqrt(k2);
    };
    ConductorIndex c;
    one(reflectance.r, &c.eta.r, &c.k.r);
    one(reflectance.g, &c.eta.g, &c.k.g);
    one(reflectance.b, &c.eta.b, &c.k.b);
    return c;
}

}  // namespace pt
