#include "scene/bsdf.h"

#include <cmath>

#include "core/sampling.h"
#include "scene/fresnel.h"
#include "scene/material.h"
#include "scene/microfacet_bsdf.h"

namespace pt {
namespace {

/// Below this |cos theta_i| a delta sample is dropped: 1 / cos must stay far
/// from overflow, and a lobe this close to the tangent plane carries a
/// vanishing share of light (measure zero for wo drawn at random).
constexpr double kMinDeltaCosine = 1e-12;

/// A third uniform number from the low-order digits of u: u = (i + f) / 2^16
/// with f uniform and independent of i, and sampling that depends on u only
/// through i to within 2^-16. The rough dielectric needs three numbers (two
/// for the facet, one for reflect-or-refract) where sample_f's contract,
/// which students call, has two; PCG32's 32-bit numbers leave 16 bits for f.
double low_digits(double u) {
    double v = u * 65536.0;
    return v - std::floor(v);
}

}  // namespace

BSDF::BSDF(const Material& material, const Frame& frame, DiffuseRoutines diffuse)
    : material_(&material), frame_(frame), diffuse_(diffuse), albedo_(material.albedo) {}

Color BSDF::f(const Vec3& wo, const Vec3& wi) const {
    switch (material_->type) {
        case MaterialType::diffuse:
            return diffuse_.f(albedo_, wo, wi);
        case MaterialType::microfacet:
            return rough_conductor_f(*material_, wo, wi);
        case MaterialType::rough_dielectric:
            return rough_dielectric_f(*material_, wo, wi);
        case MaterialType::mirror:
        case MaterialType::glass:
        case MaterialType::null:
            break;  // deltas: f is zero for every given pair
    }
    return Color(0);
}

int BSDF::delta_lobes(const Vec3& wo, DeltaLobe lobes[2]) const {
    const Material& m = *material_;
    if (m.type == MaterialType::mirror) {
        lobes[0] = {Vec3(-wo.x, -wo.y, wo.z), m.reflectance, 1.0, 1.0};
        return 1;
    }
    if (m.type == MaterialType::null) {
        // No surface: the light goes on as if nothing were there.
        lobes[0] = {-wo, Color(1.0), 1.0, 1.0};
        return 1;
    }
    if (m.type != MaterialType::glass) return 0;
    // Entering when wo is on the side of the stored normal (the outside);
    // eta = n(wi side) / n(wo side) for the refracted direction.
    const double cos_o = wo.z;
    const bool entering = cos_o > 0;
    const double eta = entering ? m.ior : 1.0 / m.ior;
    const double F = fresnel_dielectric(cos_o, m.ior);
    const Vec3 reflected(-wo.x, -wo.y, wo.z);
    if (F >= 1.0) {  // total internal reflection: everything is reflected
        lobes[0] = {reflected, m.reflectance, 1.0, 1.0};
        return 1;
    }
    int n = 0;
    if (F > 0) lobes[n++] = {reflected, m.reflectance * F, F, 1.0};
    // Snell's law: wi = -wo / eta + (cos_o / eta - cos_t) n, with n = +-z
    // on wo's side and cos_t = sqrt(1 - sin^2(theta_o) / eta^2).
    double sin2_t = std::max(0.0, 1.0 - cos_o * cos_o) / (eta * eta);
    double cos_t = safe_sqrt(1.0 - sin2_t);
    Vec3 refracted(-wo.x / eta, -wo.y / eta, entering ? -cos_t : cos_t);
    // Radiance is (n_wi / n_wo)^2 denser on the far side: divide by eta^2.
    lobes[n++] = {refracted, m.transmittance * ((1.0 - F) / (eta * eta)), 1.0 - F, eta};
    return n;
}

BSDFSample BSDF::sample_f(const Vec3& wo, Vec2 u) const {
    return sample_f(wo, u, low_digits(u.y));
}

BSDFSample BSDF::sample_f(const Vec3& wo, Vec2 u, double uc) const {
    switch (material_->type) {
        case MaterialType::diffuse:
            return diffuse_.sample_f(albedo_, wo, u);
        case MaterialType::microfacet:
            return rough_conductor_sample_f(*material_, wo, u);
        case MaterialType::rough_dielectric:
            return rough_dielectric_sample_f(*material_, wo, u, uc);
        case MaterialType::mirror:
        case MaterialType::glass:
        case MaterialType::null:
            break;
    }
    // A delta: pick one lobe with its probability; f |cos| / pdf is then
    // the lobe's weight divided by its probability.
    DeltaLobe lobes[2];
    int n = delta_lobes(wo, lobes);
    BSDFSample s;
    s.is_delta = true;
    if (n == 0) return s;
    const DeltaLobe& lobe = (n == 2 && u.x >= lobes[0].probability) ? lobes[1] : lobes[0];
    double cos_i = std::fabs(lobe.wi.z);
    // Grazing: carries nothing. The bound is not 0: weight / 1e-310 is Inf,
    // and Inf * 0 in an estimator is NaN (docs/numerics.md, case 39).
    if (!(cos_i > kMinDeltaCosine)) return s;
    s.wi = lobe.wi;
    s.f = lobe.weight / cos_i;
    s.pdf = lobe.probability;
    s.eta = lobe.eta;
    return s;
}

double BSDF::pdf(const Vec3& wo, const Vec3& wi) const {
    switch (material_->type) {
        // The density of cosine-weighted sampling, which the Lambertian
        // sample_f contract prescribes (stages/direct.h).
        case MaterialType::diffuse:
            return wi.z > 0 ? cosine_hemisphere_pdf(wi.z) : 0.0;
        case MaterialType::microfacet:
            return rough_conductor_pdf(*material_, wo, wi);
        case MaterialType::rough_dielectric:
            return rough_dielectric_pdf(*material_, wo, wi);
        case MaterialType::mirror:
        case MaterialType::glass:
        case MaterialType::null:
            break;
    }
    return 0.0;
}

bool BSDF::is_transmissive() const { return material_->type == MaterialType::rough_dielectric; }

bool BSDF::is_delta() const {
    return material_->type == MaterialType::mirror || material_->type == MaterialType::glass ||
           material_->type == MaterialType::null;
}

}  // namespace pt
