// Microfacet distributions: the statistics of a rough surface's facet
// normals m, in the local shading frame (macro normal +z), for the rough
// conductor and the rough dielectric (microfacet_bsdf.h). Three models, all
// normalised so that integral D(m) cos(theta_m) dm = 1 over the hemisphere
// (the facets' projected area is the surface's), all after Walter, Marschner,
// Li and Torrance, "Microfacet Models for Refraction through Rough Surfaces"
// (EGSR 2007), section 5:
//
//   ggx          D = 1 / (pi ax ay (x^2/ax^2 + y^2/ay^2 + z^2)^2)   (Trowbridge-Reitz)
//                Lambda(w) = (sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2) - 1) / 2
//                sampled by the normals visible from wo (Heitz, "Sampling the
//                GGX Distribution of Visible Normals", JCGT 2018); isotropic
//                GGX is exactly scene/microfacet.h's, so its images do not move.
//   beckmann     D = exp(-(x^2/ax^2 + y^2/ay^2) / z^2) / (pi ax ay z^4)
//                Lambda(w) = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)),
//                a = wz / sqrt(ax^2 wx^2 + ay^2 wy^2)
//                sampled by D(m) cos(theta_m) (Walter eq. 28; anisotropic as
//                in pbrt-v3 section 8.4.3).
//   blinn_phong  D = (e + 2) / (2 pi) cos^e(theta_m), the normalised Blinn-Phong
//                lobe of exponent e (Walter eq. 30); isotropic. Smith's Lambda
//                exactly, through the incomplete beta function (derived in
//                the .cpp; Walter's stand-in, Beckmann's Lambda at alpha =
//                sqrt(2 / (e + 2)), gains energy at low exponents). Sampled by
//                D(m) cos(theta_m): cos(theta_m) = u1^(1 / (e + 2)), phi = 2 pi u2
//                (Walter eq. 33).
//
// Anisotropic roughness (ax != ay) stretches the lobe along the shading
// frame's first tangent (x) and second (y); the renderer builds that frame
// from the surface's parameterisation (RenderContext::bsdf_at).
//
// Masking-shadowing is Smith's height-correlated form for all three:
//   G1(w) = 1 / (1 + Lambda(w)),  G2(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi))
// (Heitz, "Understanding the Masking-Shadowing Function", JCGT 2014).
//
// Tests: tests/unit/test_microfacet_models.cpp (D normalised, Lambda against
// numerical integration of the Smith integral, sampling pdf normalised),
// tests/statistical/test_glossy_sampling.cpp (chi-square of every model).
#pragma once

#include "core/vec3.h"

namespace pt {

enum class MicrofacetModel { ggx, beckmann, blinn_phong };

const char* to_string(MicrofacetModel model);

class MicrofacetDistribution {
  public:
    /// GGX or Beckmann with roughness alpha along x and y (each clamped to
    /// at least ggx::kMinAlpha).
    MicrofacetDistribution(MicrofacetModel model, double alpha_x, double alpha_y);
    /// Blinn-Phong with exponent e >= 0.
    static MicrofacetDistribution blinn_phong(double exponent);

    MicrofacetModel model() const { return model_; }
    double alpha_x() const { return alpha_x_; }
    double alpha_y() const { return alpha_y_; }
    bool is_isotropic() const { return alpha_x_ == alpha_y_; }

    /// Density of facet normals per unit solid angle; 0 below the horizon.
    double D(const Vec3& m) const;
    /// Smith's Lambda of direction w (either hemisphere: only |w.z| matters).
    double lambda(const Vec3& w) const;
    double G1(const Vec3& w) const { return 1.0 / (1.0 + lambda(w)); }
    double G2(const Vec3& wo, const Vec3& wi) const { return 1.0 / (1.0 + lambda(wo) + lambda(wi)); }

    /// A facet normal m in the upper hemisphere for light leaving along wo
    /// (wo may be below the surface: the facets seen from below are then the
    /// ones sampled), u in [0, 1)^2.
    Vec3 sample_normal(const Vec3& wo, Vec2 u) const;
    /// The density per unit solid angle with which sample_normal(wo, .)
    /// draws m: G1(wo) |wo . m| D(m) / |wo.z| (visible normals, GGX, 0 for a
    /// facet that faces away from wo) or D(m) cos(theta_m) (the others).
    double normal_pdf(const Vec3& wo, const Vec3& m) const;

  private:
    MicrofacetDistribution(MicrofacetModel model, double alpha_x, double alpha_y, double exponent);

    MicrofacetModel model_;
    double alpha_x_, alpha_y_;  ///< roughness along x and y (Blinn-Phong: Walter's matching alpha)
    double exponent_ = 0;       ///< Blinn-Phong exponent e
};

}  // namespace pt
