// Light sampling: every light of a scene behind one interface, so that a
// direct-lighting estimator can ask any light for a direction to sample
// (sample_Li) and for the density of a direction found otherwise (pdf_Li,
// for multiple importance sampling). pbrt-v3 chapter 12 and section 14.2.
//
//   light                 sample_Li draws                          samples per shading point
//   area (triangles)      a point uniform in area, pdf_A = 1 / A   -l N
//   area (sphere)         a direction uniform in the visible cone  -l N
//   point (W/sr)          its position (a delta)                   1
//   directional           its direction (a delta)                  1
//   constant environment  a cosine-weighted direction about n      -l N
//   environment map       a direction by luminance x sin(theta)    -l N
//                         (2D piecewise-constant, environment_map.h)
//
// The change of variables from area to solid angle: a point p' on a light,
// at distance r from the shading point p, seen at angle theta' from the
// light's normal, has solid-angle density
//     pdf_omega = pdf_A * r^2 / |cos theta'|
// (pbrt-v3 section 14.2.1), so sample_Li always returns solid-angle pdfs
// and every estimator divides by pdf_omega. For delta lights pdf is 1 by
// convention and L is what arrives (I / r^2 for a point light).
//
// Area lights: DESIGN.md makes every primitive whose material emits a
// light, one-sided (emitting on the side of its geometric normal; spheres
// outward). A light here is one sphere, or a maximal run of consecutive
// emissive triangles with the same material that each share a vertex with
// the one before (a quad, a lamp mesh), sampled as a whole, so `-l N`
// means N samples for the Cornell box's lamp quad, not N per triangle.
//
// Tests: tests/statistical/test_light_sampling.cpp (chi-square of sample_Li
// against pdf_Li for each light type), tests/analytic (renders against
// closed forms).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/color.h"
#include "core/vec3.h"

namespace pt {

struct Scene;

/// The shading point a light is sampled from.
struct LightSampleContext {
    Vec3 p;  ///< the point, world space
    Vec3 n;  ///< unit shading normal oriented to the side being lit, or (0, 0, 0) for "no surface"
};

/// A direction towards a light, from LightSampleContext::p.
struct LightSample {
    Color L;         ///< radiance arriving along wi if nothing blocks it; for delta lights,
                     ///< the irradiance at normal incidence (I / r^2, or E)
    Vec3 wi;         ///< unit direction from the shading point towards the light, world space
    double pdf = 0;  ///< solid-angle density of wi (1 for delta lights); 0 means "no sample"
    Vec3 p;          ///< where the shadow ray ends: the light point, moved off the light's
                     ///< surface towards the shading point (or far outside the scene for
                     ///< lights at infinity), so `isect.spawn_ray_to(p)` never hits the light
    bool is_delta = false;  ///< from a point or directional light

    bool valid() const { return pdf > 0; }
};

class Light {
  public:
    virtual ~Light() = default;
    /// A direction towards the light drawn with u in [0, 1)^2; invalid
    /// (pdf 0) when the light cannot reach ref.p (behind it, inside it).
    virtual LightSample sample_Li(const LightSampleContext& ref, Vec2 u) const = 0;
    /// The solid-angle density with which sample_Li draws the unit direction
    /// wi from ref, where the ray ref.p + t wi first meets the light at
    /// p_light with geometric normal n_light (both ignored by lights at
    /// infinity). 0 for delta lights and for directions the light is not seen in.
    virtual double pdf_Li(const LightSampleContext& ref, const Vec3& wi, const Vec3& p_light,
                          const Vec3& n_light) const = 0;
    /// Radiance a light at infinity sends along a ray that leaves the scene
    /// in `direction` (any length); black for every other light.
    virtual Color Le(const Vec3& direction) const {
        (void)direction;
        return Color(0);
    }
    /// A point or directional light: one sample is exact, and no ray can hit it.
    virtual bool is_delta() const { return false; }
    /// Samples per shading point when the user asks for `light_samples` (-l).
    int sample_count(int light_samples) const {
        return is_delta() ? 1 : std::max(1, light_samples);
    }
};

/// Every light of a scene, built once before rendering; read-only afterwards.
class LightSet {
  public:
    /// Builds the lights of `scene` (which must be finalized: Scene::emitters).
    explicit LightSet(const Scene& scene);

    const std::vector<std::unique_ptr<Light>>& all() const { return lights_; }
    bool empty() const { return lights_.empty(); }
    /// Lights that are not deltas (area and environment lights).
    int non_delta_count() const { return non_delta_count_; }

    /// The area light made of primitive `prim`, or null when it does not emit.
    const Light* light_of_primitive(uint32_t prim) const;
    /// The environment light, or null.
    const Light* environment() const { return environment_; }
    /// Radiance from the environment along a ray that leaves the scene in
    /// `direction` (any length); black without an environment light.
    Color environment_radiance(const Vec3& direction) const;

  private:
    std::vector<std::unique_ptr<Light>> lights_;
    std::vector<int32_t> light_of_primitive_;  ///< per primitive id: index into lights_, or -1
    const Light* environment_ = nullptr;       ///< one of lights_, or null
    int non_delta_count_ = 0;
};

}  // namespace pt
