// The GGX (Trowbridge-Reitz) microfacet distribution with Smith masking and
// shadowing, in the local shading frame (normal +z), for the microfacet
// conductor BSDF (bsdf.cpp). A rough surface is modelled as tiny mirrors
// (microfacets) with normals m distributed by D(m); light reflected from wi
// to wo travels by the facets whose normal is the half vector
// m = (wo + wi) / |wo + wi|, so (Torrance and Sparrow 1967; Walter et al.,
// "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007)
//
//     f(wo, wi) = F(wo . m) D(m) G2(wo, wi) / (4 cos(theta_o) cos(theta_i))
//
//   D(m)      = alpha^2 / (pi (cos^2(theta_m) (alpha^2 - 1) + 1)^2)     (GGX)
//   Lambda(w) = (sqrt(1 + alpha^2 tan^2(theta)) - 1) / 2                (Smith, GGX)
//   G1(w)     = 1 / (1 + Lambda(w))              masking of one direction
//   G2(wo,wi) = 1 / (1 + Lambda(wo) + Lambda(wi)) height-correlated masking-shadowing
//               (Heitz, "Understanding the Masking-Shadowing Function", JCGT 2014)
//
// Sampling draws the half vector from the distribution of normals *visible*
// from wo, D_wo(m) = G1(wo) max(0, wo . m) D(m) / cos(theta_o) (Heitz,
// "Sampling the GGX Distribution of Visible Normals", JCGT 2018): stretch
// wo to the configuration alpha = 1, sample the projected hemisphere there,
// unstretch. Reflecting wo about m gives wi with density
//
//     pdf(wi) = D_wo(m) / (4 wo . m) = G1(wo) D(m) / (4 cos(theta_o)),
//
// so f cos(theta_i) / pdf = F G2 / G1 <= 1: the weights never exceed the
// Fresnel term (no fireflies from the sampling itself).
//
// Tests: tests/statistical/test_bsdf_sampling.cpp (chi-square of the
// sampled directions against pdf), tests/unit/test_materials.cpp (D
// integrates to 1 over projected area, energy <= 1, reciprocity).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math.h"
#include "core/vec3.h"

namespace pt::ggx {

/// GGX alpha below which the distribution is too peaked for double
/// precision to sample reliably; materials clamp to it.
constexpr double kMinAlpha = 1e-3;

/// D(m): density of microfacet normals per unit solid angle, normalised so
/// that integral D(m) cos(theta_m) dm = 1 (projected area). 0 below the horizon.
inline double D(const Vec3& m, double alpha) {
    if (m.z <= 0) return 0.0;
    double a2 = alpha * alpha;
    double t = m.z * m.z * (a2 - 1.0) + 1.0;
    return a2 / (kPi * t * t);
}

/// Smith's Lambda(w) for GGX.
inline double lambda(const Vec3& w, double alpha) {
    double cos2 = w.z * w.z;
    if (cos2 <= 0) return std::numeric_limits<double>::infinity();  // grazing: fully masked
    double tan2 = std::max(0.0, 1.0 - cos2) / cos2;
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

/// Fraction of facets (of normals visible from w's side) not masked from w.
inline double G1(const Vec3& w, double alpha) {
    return 1.0 / (1.0 + lambda(w, alpha));
}

/// Height-correlated masking-shadowing of wo and wi.
inline double G2(const Vec3& wo, const Vec3& wi, double alpha) {
    return 1.0 / (1.0 + lambda(wo, alpha) + lambda(wi, alpha));
}

/// A half vector m drawn from the visible normals D_wo (wo.z > 0), u in
/// [0, 1)^2, for roughness ax along x and ay along y (anisotropic GGX,
/// microfacet_distribution.h; ax = ay is the isotropic case).
inline Vec3 sample_visible_normal(const Vec3& wo, double ax, double ay, Vec2 u) {
    // 1. Stretch wo to the alpha = 1 configuration, where visible normals
    //    are the hemisphere's projected onto the plane perpendicular to wo.
    Vec3 v = Vec3(ax * wo.x, ay * wo.y, wo.z).unit();
    // 2. An orthonormal basis (t1, t2, v); t1 is horizontal.
    double len2 = v.x * v.x + v.y * v.y;
    Vec3 t1 = len2 > 0 ? Vec3(-v.y, v.x, 0) / std::sqrt(len2) : Vec3(1, 0, 0);
    Vec3 t2 = cross(v, t1);
    // 3. A uniform point of the unit disk, its second coordinate squeezed
    //    onto the part of the disk that is the projection of the visible
    //    hemisphere (half a disk plus half an ellipse).
    double r = std::sqrt(u.x), phi = kTwoPi * u.y;
    double p1 = r * std::cos(phi), p2 = r * std::sin(phi);
    double s = 0.5 * (1.0 + v.z);
    p2 = (1.0 - s) * safe_sqrt(1.0 - p1 * p1) + s * p2;
    // 4. Lift onto the hemisphere about v, then unstretch.
    Vec3 n = p1 * t1 + p2 * t2 + safe_sqrt(1.0 - p1 * p1 - p2 * p2) * v;
    return Vec3(ax * n.x, ay * n.y, std::max(0.0, n.z)).unit();
}
inline Vec3 sample_visible_normal(const Vec3& wo, double alpha, Vec2 u) {
    return sample_visible_normal(wo, alpha, alpha, u);
}

/// Solid-angle density of wi = reflect(wo, m) when m is drawn by
/// sample_visible_normal: G1(wo) D(m) / (4 cos(theta_o)); 0 when wo or wi
/// is below the surface.
inline double reflection_pdf(const Vec3& wo, const Vec3& wi, double alpha) {
    if (wo.z <= 0 || wi.z <= 0) return 0.0;
    Vec3 h = wo + wi;
    double len = h.norm();
    if (!(len > 0)) return 0.0;
    Vec3 m = h / len;
    if (dot(wo, m) <= 0) return 0.0;
    return G1(wo, alpha) * D(m, alpha) / (4.0 * wo.z);
}

/// wo mirrored about the unit normal m: 2 (wo . m) m - wo.
inline Vec3 reflect(const Vec3& wo, const Vec3& m) {
    return 2.0 * dot(wo, m) * m - wo;
}

}  // namespace pt::ggx
