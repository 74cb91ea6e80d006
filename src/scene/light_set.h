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
// Emission (for light subpaths, Part 7, and photons, Part 8): sample_Le
// draws a ray *leaving* the light, pdf_Le gives the densities of any such
// ray, power() the light's total flux (Veach 1997 section 10.2; pbrt-v3
// section 16.1.2, "Sampling Light Rays"):
//
//   light          origin p, density pdf_pos                    direction w, density pdf_dir
//   area           uniform on the light, 1 / A                   cosine about the emitting normal, cos / pi
//   point          its position (a delta: 1)                     uniform on the sphere, 1 / (4 pi)
//   directional    uniform on a disk of radius R facing w,       its direction (a delta: 1)
//                  outside the scene's bounding sphere, 1/(pi R^2)
//   environment    the same disk, across the sampled direction   by the map (or uniform), as sample_Li
//
// R is the radius of the scene's bounding sphere: every ray from the disk
// crosses the whole scene, so parallel light at infinity is sampled with
// a uniform density over any surface it reaches (pdf_pos |cos|).
// The flux a sampled ray carries is Le |cos theta| / (pdf_pos pdf_dir)
// (LightEmission::flux); its mean is power().
//
// Tests: tests/statistical/test_light_sampling.cpp (chi-square of sample_Li
// against pdf_Li for each light type), tests/statistical/test_light_emission.cpp
// (chi-square of sample_Le's origins and directions against pdf_Le, and the
// mean flux against power() and the closed forms), tests/analytic (renders
// against closed forms).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/color.h"
#include "core/ray.h"
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

/// What a light is, for the code that must treat them differently
/// (light subpaths start at infinity, deltas cannot be hit).
enum class LightKind { area, point, directional, environment };

/// A ray leaving a light, drawn by Light::sample_Le (see the file comment).
struct LightEmission {
    Vec3 p;          ///< origin: on the light (area), its position (point), or on the disk
                     ///< outside the scene (lights at infinity)
    Vec3 p_error;    ///< bound on the rounding error of p (area lights; 0 otherwise)
    Vec3 n;          ///< unit normal at p: the emitting side (area), w (the disk, lights
                     ///< at infinity), or (0, 0, 0) for a point light
    Vec3 w;          ///< unit direction of travel, away from the light
    Color Le;        ///< radiance along the ray (area, environment); intensity, W/sr
                     ///< (point); irradiance, W/m^2 (directional)
    double pdf_pos = 0;  ///< density of p per unit area of the light or disk; 1 for a point light
    double pdf_dir = 0;  ///< density of w given p per unit solid angle; 1 for a directional light

    bool valid() const { return pdf_pos > 0 && pdf_dir > 0; }
    /// The flux the ray carries as a Monte Carlo sample of the light's
    /// power: Le |cos theta| / (pdf_pos pdf_dir), cos = 1 without a surface.
    Color flux() const {
        double cos = n.norm2() > 0 ? std::fabs(dot(n, w)) : 1.0;
        return Le * (cos / (pdf_pos * pdf_dir));
    }
    /// The ray itself, its origin moved off the light's surface.
    Ray ray() const;
};

/// The densities with which sample_Le draws a given ray (Light::pdf_Le).
struct LightEmissionPdf {
    double pos = 0;  ///< per unit area of the light or disk (0 for a point light: no surface)
    double dir = 0;  ///< per unit solid angle (0 for a directional light: a delta)
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
    virtual LightKind kind() const = 0;
    /// Directional and environment lights: their "points" are directions.
    bool at_infinity() const {
        return kind() == LightKind::directional || kind() == LightKind::environment;
    }

    /// A ray leaving the light, its origin drawn with u_pos and its direction
    /// with u_dir (both in [0, 1)^2); invalid (pdf 0) when there is none.
    virtual LightEmission sample_Le(Vec2 u_pos, Vec2 u_dir) const = 0;
    /// The densities of sample_Le for the ray leaving p (with the light's
    /// normal n there; both ignored by lights at infinity) in unit direction w.
    virtual LightEmissionPdf pdf_Le(const Vec3& p, const Vec3& n, const Vec3& w) const = 0;
    /// Total emitted flux, W (per colour channel): pi Le A for an area light,
    /// 4 pi I for a point light, pi R^2 E for a directional light, and
    /// pi R^2 times the integral of Le over the sphere for the environment.
    virtual Color power() const = 0;
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

    /// One light chosen with probability proportional to the luminance of
    /// its power (uniformly if every light is dark), as light subpaths and
    /// photons start from; `probability` receives the chance of that light.
    const Light* sample_by_power(double u, double* probability) const;
    /// The probability that sample_by_power picks `light` (0 for a light not in the set).
    double power_probability(const Light* light) const;

  private:
    std::vector<std::unique_ptr<Light>> lights_;
    std::vector<int32_t> light_of_primitive_;  ///< per primitive id: index into lights_, or -1
    const Light* environment_ = nullptr;       ///< one of lights_, or null
    int non_delta_count_ = 0;
    std::vector<double> power_probability_;    ///< per light, by the luminance of its power
    std::vector<double> power_cdf_;            ///< running sums of power_probability_; last = 1
    std::unordered_map<const Light*, size_t> index_;  ///< position of each light in lights_
};

}  // namespace pt
