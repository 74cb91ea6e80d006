// Stage `media` (Part 9): light in participating media.
//
// Along a ray x(t) = o + t d through a medium, light is absorbed (sigma_a),
// scattered away (out-scattering, sigma_s) and scattered into the ray from
// other directions (in-scattering); sigma_t = sigma_a + sigma_s is the
// extinction, per unit length. The radiance arriving at o is the volume
// rendering equation (Kajiya and Von Herzen 1984; pbrt-v3 section 15.1,
// pbrt-v4 section 14.1):
//
//     L(o, -d) = T(0, s) L_surface(x(s), -d)
//              + integral_0^s T(0, t) sigma_s(x(t)) L_s(x(t), -d) dt
//     L_s(x, wo) = integral over the sphere of p(wo, wi) L(x, wi) dwi
//     T(0, t) = exp(-integral_0^t sigma_t(x(t')) dt')      (Beer-Lambert)
//
// with s the distance to the first surface, T the transmittance, p the
// phase function (a density over directions: it integrates to 1) and L_s
// the in-scattered radiance. In a homogeneous medium T(0, t) = e^(-sigma_t t).
//
// Free-flight sampling: draw the distance t to the next collision with the
// density sigma_t e^(-sigma_t t) (by inversion, t = -ln(1 - u) / sigma_t).
// If t < s the path scatters at x(t), and the estimator of the integral is
// T sigma_s L_s / pdf = (sigma_s / sigma_t) L_s: the albedo. Otherwise it
// reaches the surface, which happens with probability e^(-sigma_t s) = T(0, s),
// and the weight of L_surface is T / P = 1 (pbrt-v3 section 15.2).
//
// Henyey-Greenstein phase function (Henyey and Greenstein 1941), with cos
// theta the cosine between the direction light travelled before (-wi) and
// after (wo) the scattering, so g > 0 scatters forward:
//
//     p_HG(cos theta) = (1 / 4 pi) (1 - g^2) / (1 + g^2 - 2 g cos theta)^(3/2)
//
// sampled exactly by inverting its cdf in cos theta:
//     cos theta = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g u))^2) / (2 g)   (g != 0)
// and phi uniform (pbrt-v3 section 15.2.3, with its sign convention made
// explicit above).
//
// Single scattering: with light sampling for L_s at the collision, one
// free flight per camera ray estimates the integral above for light that
// scattered once (-m 1): (sigma_s / sigma_t) L_s(x(t), -d) per collision.
//
// The volume path tracer (render/volpath_integrator.cpp, `--integrator
// volpath`) calls these functions through the stage table; its chromatic
// and heterogeneous machinery (stages/medium_tracking.h) is reference only.
// With `--student media` (part9), next-event estimation at every medium
// collision is in_scattered_radiance (light sampling, no MIS there).
//
// Tests: tests/statistical/test_media_sampling.cpp (chi-square of HG
// sampling for g in {-0.9, -0.3, 0, 0.5, 0.95} and of distance sampling),
// tests/unit/test_transmittance.cpp (closed forms, HG normalisation).
#pragma once

#include "core/color.h"
#include "core/rng.h"
#include "core/vec3.h"

namespace pt {

struct RenderContext;

/// What sample_distance draws: where the next collision is, or that there
/// is none before the surface.
struct DistanceSample {
    double t = 0;            ///< distance along the ray to the collision; t_max when it passed
    double pdf = 0;          ///< scattered: the density of t, sigma_t e^(-sigma_t t), per unit length;
                             ///< passed: the probability of passing, e^(-sigma_t t_max)
    bool scattered = false;  ///< true: a collision at t < t_max; false: no collision before t_max
};

using HomogeneousTransmittanceFn = Color (*)(const Color& sigma_t, double distance);
using SampleDistanceFn = DistanceSample (*)(double sigma_t, double t_max, double u);
using HgPhaseFn = double (*)(double cos_theta, double g);
using SampleHgFn = Vec3 (*)(const Vec3& wo, double g, Vec2 u);
using InScatteredRadianceFn = Color (*)(const RenderContext& context, const Vec3& p, const Vec3& wo, int medium,
                                        Rng& rng);

struct MediaStage {
    /// e^(-sigma_t distance) per channel: the fraction of light that crosses
    /// `distance` scene units (>= 0, may be infinite) of a homogeneous
    /// medium of extinction sigma_t (per scene unit, >= 0). Never NaN: a
    /// channel with sigma_t = 0 transmits 1 at any distance.
    HomogeneousTransmittanceFn homogeneous_transmittance;
    /// A free-flight distance for extinction sigma_t >= 0 (per unit) with u
    /// in [0, 1): a collision at t = -ln(1 - u) / sigma_t when that is below
    /// t_max (> 0, may be infinite), with its density; else "passed" at
    /// t_max with the probability of passing. sigma_t = 0 always passes.
    SampleDistanceFn sample_distance;
    /// p_HG(cos theta) for g in (-1, 1), 1/sr (see the file comment for cos theta).
    HgPhaseFn hg_phase;
    /// A unit direction wi drawn with density p_HG(-dot(wo, wi)) from the
    /// unit direction wo (pointing back along the path) and u in [0, 1)^2.
    SampleHgFn sample_hg;
    /// The in-scattered radiance from the lights, L_s(p, wo) = integral of
    /// p_HG(wo, wi) L_direct(p, wi) dwi, at the point p inside medium
    /// `medium` (an index into context.scene.media, >= 0), towards the unit
    /// direction wo, by light sampling: for every light, -l samples (one for
    /// a delta light) from Light::sample_Li with a context of no normal,
    /// each weighted by the phase function and by the transmittance of its
    /// shadow ray (shadow_transmittance, stages/medium_tracking.h), averaged
    /// per light and summed. Not multiplied by sigma_s: the free flight that
    /// found p has weighed it in.
    InScatteredRadianceFn in_scattered_radiance;
};

namespace reference {
Color homogeneous_transmittance(const Color& sigma_t, double distance);
DistanceSample sample_distance(double sigma_t, double t_max, double u);
double hg_phase(double cos_theta, double g);
Vec3 sample_hg(const Vec3& wo, double g, Vec2 u);
Color in_scattered_radiance(const RenderContext& context, const Vec3& p, const Vec3& wo, int medium, Rng& rng);
}  // namespace reference

namespace student {
Color homogeneous_transmittance(const Color& sigma_t, double distance);
DistanceSample sample_distance(double sigma_t, double t_max, double u);
double hg_phase(double cos_theta, double g);
Vec3 sample_hg(const Vec3& wo, double g, Vec2 u);
Color in_scattered_radiance(const RenderContext& context, const Vec3& p, const Vec3& wo, int medium, Rng& rng);
}  // namespace student

}  // namespace pt
