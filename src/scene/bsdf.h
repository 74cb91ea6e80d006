// BSDF: how a surface scatters light, at one shading point, in the local
// shading frame where the normal is +z (so cos theta = w.z). Directions wo
// and wi both point away from the surface (STYLE.md: `wo`, `wi`); wo leads
// back along the ray that arrived, wi towards where light comes from.
//
// The interface is the one every material keeps (pbrt-v3 chapter 8,
// CS184's BSDF):
//   f(wo, wi)          the BSDF value, 1/sr
//   sample_f(wo, u)    a direction wi drawn with a known pdf, with f(wo, wi)
//                      and the pdf, so that a Monte Carlo estimator can
//                      weight it by f cos / pdf
//   pdf(wo, wi)        the density sample_f draws wi with (for MIS)
//   is_delta()         whether the BSDF is a Dirac delta (mirror, glass):
//                      f and pdf are 0 for every direction given, only
//                      sample_f (or delta_lobes) finds the directions that scatter.
//
// The materials (material.h):
//   diffuse     Lambertian, albedo / pi; cosine-weighted sampling. Its two
//               functions are staged (stages/direct.h, Part 3) and reached
//               through DiffuseRoutines, so a student's code runs here.
//   mirror      perfect specular reflection wi = (-wo.x, -wo.y, wo.z), weight
//               `reflectance` (a delta).
//   glass       smooth dielectric (a delta with two lobes): reflection with
//               Fresnel probability F (fresnel.h), refraction by Snell's law
//               with probability 1 - F; F = 1 beyond the critical angle (total
//               internal reflection). The frame keeps the stored normal, so
//               the sign of cos(theta_o) = wo.z tells entering (wo.z > 0,
//               outside) from leaving. Refracted radiance is scaled by
//               (n_o / n_i)^2, n_o and n_i the indices on wo's and wi's sides
//               (radiance is compressed into the denser medium; pbrt-v3
//               section 8.2.3, Veach 1997 section 5.2).
//   microfacet  rough conductor: GGX (sampled by visible normals), Beckmann
//               or normalised Blinn-Phong facets, anisotropic roughness,
//               height-correlated Smith shadowing, conductor Fresnel
//               (microfacet_distribution.h, microfacet_bsdf.h). Reflection only.
//   rough_dielectric  rough glass (Walter et al. 2007): reflection and
//               refraction through the facets, any of the three
//               distributions; keeps the stored normal, like glass.
//   null        no surface (a medium's invisible boundary): one delta lobe
//               wi = -wo of weight 1. The path tracer counts crossing it as a
//               bounce; the volume path tracer (Part 9) does not.
//
// One BSDF is built per hit, from the Material and the shading frame, by
// RenderContext::bsdf_at (stages/render_context.h), which also decides on
// which side of the surface the frame's +z lies (two-sided for all but glass).
// Materials are a closed set (material.h), so the BSDF switches on the
// type instead of allocating a virtual object per hit.
//
// Tests: tests/unit/test_bsdf.cpp and test_materials.cpp (values,
// reciprocity, energy, mirror direction, Fresnel, total internal
// reflection), tests/statistical/test_bsdf_sampling.cpp (chi-square of
// sample_f against pdf for the diffuse and microfacet lobes; the discrete
// check of glass's two directions and their probabilities).
#pragma once

#include "core/color.h"
#include "core/frame.h"
#include "core/vec3.h"

namespace pt {

struct Material;

/// A direction drawn by BSDF::sample_f, in the local shading frame.
struct BSDFSample {
    Vec3 wi;         ///< unit incident direction, local frame (normal = +z)
    Color f;         ///< f(wo, wi), 1/sr; for a delta lobe, its weight divided by |cos theta_i|
    double pdf = 0;  ///< solid-angle density of wi; for a delta lobe the probability of
                     ///< picking that lobe (1 for a mirror, F or 1 - F for glass);
                     ///< 0 means "no sample" (ignore it)
    bool is_delta = false;  ///< drawn from a Dirac delta lobe
    double eta = 1;         ///< n(wi side) / n(wo side) when wi is refracted, else 1 (for
                            ///< Russian roulette, which discounts the (n_o / n_i)^2 in f)

    bool valid() const { return pdf > 0; }
};

/// One direction into which a delta BSDF scatters: the whole of its
/// contribution, so that Whitted ray tracing can follow every lobe
/// deterministically, and sample_f can pick one with `probability`.
struct DeltaLobe {
    Vec3 wi;                 ///< unit direction, local frame
    Color weight;            ///< radiance reaching wo per unit radiance arriving along wi
    double probability = 0;  ///< the chance that sample_f picks this lobe (> 0)
    double eta = 1;          ///< n(wi side) / n(wo side): 1 for reflection
};

/// The staged diffuse routines (stages/direct.h) the BSDF calls.
using DiffuseFFn = Color (*)(const Color& albedo, const Vec3& wo, const Vec3& wi);
using DiffuseSampleFFn = BSDFSample (*)(const Color& albedo, const Vec3& wo, Vec2 u);
struct DiffuseRoutines {
    DiffuseFFn f;
    DiffuseSampleFFn sample_f;
};

class BSDF {
  public:
    /// The BSDF of `material` at a point whose local shading frame is `frame`.
    BSDF(const Material& material, const Frame& frame, DiffuseRoutines diffuse);
    /// The same, with the diffuse albedo found at the point (a texture's value).
    BSDF(const Material& material, const Frame& frame, DiffuseRoutines diffuse, const Color& albedo)
        : material_(&material), frame_(frame), diffuse_(diffuse), albedo_(albedo) {}
    /// The BSDF keeps a pointer to its material: a temporary would dangle.
    BSDF(Material&& material, const Frame& frame, DiffuseRoutines diffuse) = delete;
    BSDF(Material&& material, const Frame& frame, DiffuseRoutines diffuse, const Color& albedo) = delete;

    /// World-space direction to the local frame, and back.
    Vec3 to_local(const Vec3& w) const { return frame_.to_local(w); }
    Vec3 to_world(const Vec3& w) const { return frame_.to_world(w); }
    const Frame& frame() const { return frame_; }
    const Material& material() const { return *material_; }

    /// f(wo, wi) for unit local directions; 0 for a delta BSDF.
    Color f(const Vec3& wo, const Vec3& wi) const;
    /// A direction wi for wo, drawn with u in [0, 1)^2 (see the file comment).
    BSDFSample sample_f(const Vec3& wo, Vec2 u) const;
    /// The same with a third uniform number uc for the choice between
    /// reflection and refraction of the rough dielectric (the two-number
    /// form takes it from u's low-order digits; other BSDFs ignore uc).
    BSDFSample sample_f(const Vec3& wo, Vec2 u, double uc) const;
    /// The density with which sample_f(wo, .) draws wi; 0 for a delta BSDF.
    double pdf(const Vec3& wo, const Vec3& wi) const;
    /// Whether the BSDF is a Dirac delta (mirror, glass): no light sample can reach it.
    bool is_delta() const;
    /// Whether a non-delta BSDF also scatters into the lower hemisphere
    /// (rough dielectric): light samples must then come from both sides.
    bool is_transmissive() const;
    /// The directions a delta BSDF scatters wo into, written to `lobes`:
    /// 1 for a mirror, 2 for glass (reflection first, then refraction), 1
    /// for glass under total internal reflection; 0 for a non-delta BSDF.
    int delta_lobes(const Vec3& wo, DeltaLobe lobes[2]) const;

  private:
    const Material* material_;  ///< never null
    Frame frame_;               ///< local shading frame; +z is the (oriented) shading normal
    DiffuseRoutines diffuse_;   ///< student or reference Lambertian routines
    Color albedo_;              ///< diffuse reflectance at this point (the material's, or its texture's)
};

}  // namespace pt
