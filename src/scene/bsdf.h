// BSDF: how a surface scatters light, at one shading point, in the local
// shading frame where the normal is +z (so cos theta = w.z). Directions wo
// and wi both point away from the surface (STYLE.md: `wo`, `wi`); wo leads
// back along the ray that arrived, wi towards where light comes from.
//
// The interface is the one every later material keeps (pbrt-v3 chapter 8,
// CS184's BSDF):
//   f(wo, wi)          the BSDF value, 1/sr
//   sample_f(wo, u)    a direction wi drawn with a known solid-angle pdf,
//                      with f(wo, wi) and the pdf, so that a Monte Carlo
//                      estimator can weight it by f cos / pdf
//   pdf(wo, wi)        the density sample_f draws wi with (for MIS)
//   is_delta()         whether the BSDF is a Dirac delta (mirror, glass):
//                      f and pdf are 0 for every direction given, only
//                      sample_f finds the one direction that scatters.
//
// One BSDF is built per hit, from the Material and the shading frame, by
// RenderContext::bsdf_at (render/render_context.h), which also decides on
// which side of the surface the frame's +z lies (two-sided diffuse).
// Materials are a closed set (material.h), so the BSDF switches on the
// type instead of allocating a virtual object per hit.
//
// Part 3 implements the Lambertian (diffuse) BSDF; its two functions are
// staged (stages/direct.h) and reach the BSDF through DiffuseRoutines, so
// the student's code runs here when `direct` is a student stage. Mirror and
// glass arrive with Part 4; until then they scatter nothing, which is what
// direct lighting from area lights gives a delta BSDF anyway.
//
// Tests: tests/unit/test_bsdf.cpp (values, reciprocity, energy),
// tests/statistical/test_bsdf_sampling.cpp (chi-square of sample_f against pdf).
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
    double pdf = 0;  ///< solid-angle density of wi; 0 means "no sample" (ignore it)
    bool is_delta = false;  ///< drawn from a Dirac delta lobe (pdf is then 1 by convention)

    bool valid() const { return pdf > 0; }
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
    BSDF(const Material& material, const Frame& frame, DiffuseRoutines diffuse)
        : material_(&material), frame_(frame), diffuse_(diffuse) {}

    /// World-space direction to the local frame, and back.
    Vec3 to_local(const Vec3& w) const { return frame_.to_local(w); }
    Vec3 to_world(const Vec3& w) const { return frame_.to_world(w); }
    const Frame& frame() const { return frame_; }
    const Material& material() const { return *material_; }

    /// f(wo, wi) for unit local directions; 0 for a delta BSDF.
    Color f(const Vec3& wo, const Vec3& wi) const;
    /// A direction wi for wo, drawn with u in [0, 1)^2 (see the file comment).
    BSDFSample sample_f(const Vec3& wo, Vec2 u) const;
    /// The density with which sample_f(wo, .) draws wi; 0 for a delta BSDF.
    double pdf(const Vec3& wo, const Vec3& wi) const;
    /// Whether the BSDF is a Dirac delta (mirror, glass): no light sample can reach it.
    bool is_delta() const;

  private:
    const Material* material_;  ///< never null
    Frame frame_;               ///< local shading frame; +z is the (oriented) shading normal
    DiffuseRoutines diffuse_;   ///< student or reference Lambertian routines
};

}  // namespace pt
