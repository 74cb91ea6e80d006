#include "scene/microfacet_bsdf.h"

#include <cmath>

#include "core/math.h"
#include "core/rng.h"
#include "scene/fresnel.h"
#include "scene/material.h"
#include "scene/microfacet.h"

namespace pt {
namespace {

bool is_isotropic_ggx(const MicrofacetDistribution& d) {
    return d.model() == MicrofacetModel::ggx && d.is_isotropic();
}

/// The facet normal that turns wo into wi, facing +z, and eta = n(wi side)
/// / n(wo side) (1 for reflection); false for a degenerate pair or when the
/// facet faces away from wo or wi (it could not be what joined them).
bool half_vector(const Vec3& wo, const Vec3& wi, double ior, Vec3* m, double* eta) {
    const bool reflection = wo.z * wi.z > 0;
    *eta = reflection ? 1.0 : (wo.z > 0 ? ior : 1.0 / ior);
    Vec3 h = wi * *eta + wo;
    double len = h.norm();
    if (!(len > 0) || wo.z == 0 || wi.z == 0) return false;
    *m = h / len;
    if (m->z < 0) *m = -*m;
    // Back-facing facets: the facet must face wo from wo's side and wi from wi's.
    return dot(*m, wi) * wi.z > 0 && dot(*m, wo) * wo.z > 0;
}

/// Snell's law through a facet with unit normal m: the direction wi for
/// wo, eta = n(wi side) / n(wo side); false under total internal reflection.
bool refract(const Vec3& wo, const Vec3& m, double eta, Vec3* wi) {
    double cos_o = dot(wo, m);
    Vec3 n = cos_o > 0 ? m : -m;  // the facet normal on wo's side
    cos_o = std::fabs(cos_o);
    double sin2_t = std::max(0.0, 1.0 - cos_o * cos_o) / (eta * eta);
    if (sin2_t >= 1.0) return false;
    double cos_t = safe_sqrt(1.0 - sin2_t);
    *wi = -wo / eta + (cos_o / eta - cos_t) * n;
    return true;
}

}  // namespace

MicrofacetDistribution distribution_of(const Material& m) {
    if (m.distribution == MicrofacetModel::blinn_phong) return MicrofacetDistribution::blinn_phong(m.exponent);
    return MicrofacetDistribution(m.distribution, m.roughness, m.roughness_y < 0 ? m.roughness : m.roughness_y);
}

// --- Rough conductor ---------------------------------------------------------

Color rough_conductor_f(const Material& material, const Vec3& wo, const Vec3& wi) {
    if (wo.z <= 0 || wi.z <= 0) return Color(0);
    Vec3 h = wo + wi;
    double len = h.norm();
    if (!(len > 0)) return Color(0);
    Vec3 half = h / len;
    MicrofacetDistribution d = distribution_of(material);
    double d_g = d.D(half) * d.G2(wo, wi);
    if (!(d_g > 0)) return Color(0);
    return fresnel_conductor(dot(wo, half), material.eta, material.k) * (d_g / (4.0 * wo.z * wi.z));
}

BSDFSample rough_conductor_sample_f(const Material& material, const Vec3& wo, Vec2 u) {
    BSDFSample s;
    if (wo.z <= 0) return s;
    Vec3 half = distribution_of(material).sample_normal(wo, u);
    s.wi = ggx::reflect(wo, half);
    // Reflected below the surface: the facet is hidden from wi (no sample).
    if (s.wi.z <= 0) return {};
    s.wi = s.wi.unit();
    s.pdf = rough_conductor_pdf(material, wo, s.wi);
    if (!(s.pdf > 0) || !std::isfinite(s.pdf)) return {};
    s.f = rough_conductor_f(material, wo, s.wi);
    return s;
}

double rough_conductor_pdf(const Material& material, const Vec3& wo, const Vec3& wi) {
    MicrofacetDistribution d = distribution_of(material);
    if (is_isotropic_ggx(d)) return ggx::reflection_pdf(wo, wi, d.alpha_x());  // Part 4's, unchanged
    if (wo.z <= 0 || wi.z <= 0) return 0.0;
    Vec3 h = wo + wi;
    double len = h.norm();
    if (!(len > 0)) return 0.0;
    Vec3 m = h / len;
    double cos_om = dot(wo, m);
    if (cos_om <= 0) return 0.0;
    return d.normal_pdf(wo, m) / (4.0 * cos_om);
}

// --- Rough dielectric --------------------------------------------------------

Color rough_dielectric_f(const Material& material, const Vec3& wo, const Vec3& wi) {
    Vec3 m;
    double eta;
    if (!half_vector(wo, wi, material.ior, &m, &eta)) return Color(0);
    MicrofacetDistribution d = distribution_of(material);
    double F = fresnel_dielectric(dot(wo, m), material.ior);
    double dg = d.D(m) * d.G2(wo, wi);
    if (!(dg > 0)) return Color(0);
    if (eta == 1.0 && wo.z * wi.z > 0)
        return material.reflectance * (F * dg / (4.0 * std::fabs(wo.z * wi.z)));
    double denom = sqr(dot(wi, m) + dot(wo, m) / eta);
    double ft = (1.0 - F) * dg * std::fabs(dot(wi, m) * dot(wo, m) / (wo.z * wi.z * denom)) / (eta * eta);
    return material.transmittance * ft;
}

BSDFSample rough_dielectric_sample_f(const Material& material, const Vec3& wo, Vec2 u, double uc) {
    if (wo.z == 0) return {};
    MicrofacetDistribution d = distribution_of(material);
    Vec3 m = d.sample_normal(wo, u);
    double cos_om = dot(wo, m);
    if (cos_om * wo.z <= 0) return {};  // a facet facing away from wo (Beckmann and Blinn-Phong draw them)
    double F = fresnel_dielectric(cos_om, material.ior);
    BSDFSample s;
    if (uc < F) {
        s.wi = ggx::reflect(wo, m);
        if (s.wi.z * wo.z <= 0) return {};  // reflected through the macro surface
    } else {
        double eta = cos_om > 0 ? material.ior : 1.0 / material.ior;
        if (!refract(wo, m, eta, &s.wi) || s.wi.z * wo.z >= 0) return {};
        s.eta = eta;
    }
    s.wi = s.wi.unit();
    s.pdf = rough_dielectric_pdf(material, wo, s.wi);
    if (!(s.pdf > 0) || !std::isfinite(s.pdf)) return {};
    s.f = rough_dielectric_f(material, wo, s.wi);
    return s;
}

double rough_dielectric_pdf(const Material& material, const Vec3& wo, const Vec3& wi) {
    Vec3 m;
    double eta;
    if (!half_vector(wo, wi, material.ior, &m, &eta)) return 0.0;
    MicrofacetDistribution d = distribution_of(material);
    double pdf_m = d.normal_pdf(wo, m);
    double F = fresnel_dielectric(dot(wo, m), material.ior);
    if (wo.z * wi.z > 0) return pdf_m * F / (4.0 * std::fabs(dot(wo, m)));
    // The Jacobian of the refracted direction with respect to the facet normal (Walter eq. 17).
    double denom = sqr(dot(wi, m) + dot(wo, m) / eta);
    return pdf_m * (1.0 - F) * std::fabs(dot(wi, m)) / denom;
}

AlbedoEstimate rough_albedo(const Material& material, const Vec3& wo, int n, uint64_t seed) {
    Rng rng(seed);
    double s1 = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        Vec2 u = rng.next_2d();
        BSDFSample s = material.type == MaterialType::rough_dielectric
                           ? rough_dielectric_sample_f(material, wo, u, rng.next_1d())
                           : rough_conductor_sample_f(material, wo, u);
        double w = s.valid() ? s.f.g * std::fabs(s.wi.z) / s.pdf * s.eta * s.eta : 0.0;
        s1 += w;
        s2 += w * w;
    }
    double mean = s1 / n;
    return {mean, std::sqrt(std::max(0.0, s2 / n - mean * mean) / n)};
}

}  // namespace pt
