// Stage `direct` (Part 3): emission and direct illumination.
//
// The reflection equation gives the radiance leaving a surface point p in
// direction wo as emission plus the light arriving over the hemisphere H of
// directions around the normal n, weighted by the BSDF and the cosine:
//
//     Lo(p, wo) = Le(p, wo) + integral_H f(p, wo, wi) Li(p, wi) cos(theta_i) dwi
//
// zero_bounce_radiance is the first term (emission seen directly);
// one_bounce_radiance estimates the integral when Li counts only light that
// comes straight from an emitter (direct illumination, `-m 1`).
//
// The Monte Carlo estimator: with N directions wi_j drawn with density pdf,
//
//     integral ~ 1/N sum_j f(p, wo, wi_j) Li(p, wi_j) cos(theta_j) / pdf(wi_j)
//
// is unbiased for any pdf that is non-zero wherever the integrand is. Two
// choices of pdf make the two course estimators:
//   - estimate_direct_lighting_hemisphere: wi uniform on the hemisphere,
//     pdf = 1 / (2 pi); Li is what the ray along wi hits (emission only).
//     Simple, but small lights are rarely hit: noisy.
//   - estimate_direct_lighting_importance: wi towards a point sampled on
//     each light (light sampling), with one shadow ray to see if it is
//     blocked. A point p' drawn on a light with area density pdf_A is a
//     direction with solid-angle density (pbrt-v3 section 14.2.1)
//
//         pdf_omega = pdf_A * |p' - p|^2 / |cos theta'|
//
//     where theta' is the angle between the light's normal at p' and the
//     direction back to p. Light::sample_Li (scene/light_set.h) returns it.
// A third, task 3.8: estimate_direct_lighting_mis combines light samples and
// BSDF samples, each weighted by a heuristic of task 3.7 (Veach 1997,
// chapter 9; the file comment of stages/mis.h has the estimator), robust for
// both small and large lights. --mis-heuristic picks power or balance.
//
// Sources: pbrt-v3 (Pharr, Jakob, Humphreys) chapters 13 (Monte Carlo, warps)
// and 14 (light transport I: direct lighting, section 14.3); Veach, "Robust
// Monte Carlo Methods for Light Transport Simulation", PhD thesis 1997,
// chapter 9 (multiple importance sampling); CS184 PathTracer Part 3.
//
// Tests that prove it: tests/statistical (chi-square of every warp, of every
// light's sample_Li against pdf_Li and of the diffuse sample_f against its
// pdf) and tests/analytic (tiny renders within 4 standard errors of closed
// forms: furnace, rectangle light by Lambert's polygon formula, point light
// inverse square, sphere light by hemisphere, light and MIS sampling).
#pragma once

#include "core/color.h"
#include "core/ray.h"
#include "core/rng.h"
#include "core/vec3.h"
#include "scene/bsdf.h"

namespace pt {

struct RenderContext;
struct SurfaceInteraction;

using ZeroBounceFn = Color (*)(const RenderContext& context, const Ray& ray,
                               const SurfaceInteraction& isect);
/// A multiple-importance weight (Veach 1997, section 9.2): of a sample drawn
/// from strategy f (nf samples with density f_pdf) that strategy g (ng
/// samples, density g_pdf) could also have drawn.
using MisHeuristicFn = double (*)(double nf, double f_pdf, double ng, double g_pdf);
using DirectEstimateFn = Color (*)(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, Rng& rng);

/// The function table of the stage. Every estimator returns radiance
/// (W/(m^2 sr), linear RGB) leaving isect.p towards the ray's origin, along
/// isect.wo; isect is the closest hit of `ray`. Random numbers come only
/// from `rng`.
struct DirectStage {
    /// Lambertian BSDF value in the local frame (normal = +z): albedo / pi
    /// when wi.z > 0, else black. Units 1/sr.
    DiffuseFFn diffuse_f;
    /// Lambertian sample in the local frame: wi cosine-weighted on the
    /// hemisphere z > 0, f = albedo / pi, pdf = cos(theta_i) / pi; pdf 0
    /// (an invalid sample) when wi.z is 0.
    DiffuseSampleFFn diffuse_sample_f;
    /// Radiance emitted by the surface at isect towards isect.wo: the
    /// material's emission when isect.wo is on the side of the geometric
    /// normal isect.ng (area lights are one-sided), else black.
    ZeroBounceFn zero_bounce_radiance;
    /// Direct light at isect by uniform hemisphere sampling: N = -l times the
    /// number of non-delta lights rays, each adding what it hits (its
    /// zero_bounce_radiance, or the environment on a miss). Delta lights
    /// cannot be hit and add nothing. Black for delta BSDFs.
    DirectEstimateFn estimate_direct_lighting_hemisphere;
    /// Direct light at isect by light sampling: for every light, -l samples
    /// (one for a delta light) from Light::sample_Li, each tested with a
    /// shadow ray, averaged per light and summed over lights. Black for delta BSDFs.
    DirectEstimateFn estimate_direct_lighting_importance;
    /// Direct light at isect by the strategy of context.settings.direct:
    /// hemisphere, light (importance) or mis.
    DirectEstimateFn one_bounce_radiance;
    /// The power heuristic with exponent 2 (Veach 1997, section 9.2.4):
    ///     w_f = (nf f_pdf)^2 / ((nf f_pdf)^2 + (ng g_pdf)^2),
    /// in [0, 1]; 0 when nf f_pdf is 0 (f cannot draw that sample), 1 when
    /// it is infinite (a delta) and ng g_pdf finite, 0.5 for two deltas,
    /// never NaN (densities up to 1e300 each: no overflow to inf / inf), and
    /// w_f(nf, pf, ng, pg) + w_g(ng, pg, nf, pf) = 1 when either is non-zero.
    MisHeuristicFn power_heuristic;
    /// The balance heuristic (Veach 1997, section 9.2.2): w_f = nf f_pdf /
    /// (nf f_pdf + ng g_pdf), with the same limits as power_heuristic.
    MisHeuristicFn balance_heuristic;
    /// Direct light at isect by multiple importance sampling. For every light,
    /// n = light->sample_count(-l) light samples, each (when unblocked and
    /// above the surface) adding f Le cos / pdf_light times its MIS weight
    /// against nb = max(1, -l) BSDF samples (weight 1 for a delta light),
    /// averaged per light and summed over lights; plus nb samples of
    /// BSDF::sample_f, each adding the emission it finds (zero_bounce_radiance
    /// of what it hits, or the environment when it escapes) times f cos /
    /// pdf_bsdf times its weight against that light's n samples of density
    /// pdf_Li, averaged over nb. The weights use power_heuristic or
    /// balance_heuristic as context.settings.mis_heuristic says. Light from
    /// below the surface counts only for a transmissive BSDF (|cos|). Black
    /// for delta BSDFs. Unbiased: same mean as the other two estimators.
    DirectEstimateFn estimate_direct_lighting_mis;
};

namespace reference {
Color diffuse_f(const Color& albedo, const Vec3& wo, const Vec3& wi);
BSDFSample diffuse_sample_f(const Color& albedo, const Vec3& wo, Vec2 u);
Color zero_bounce_radiance(const RenderContext& context, const Ray& ray,
                           const SurfaceInteraction& isect);
Color estimate_direct_lighting_hemisphere(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng);
Color estimate_direct_lighting_importance(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng);
Color one_bounce_radiance(const RenderContext& context, const Ray& ray,
                          const SurfaceInteraction& isect, Rng& rng);
double power_heuristic(double nf, double f_pdf, double ng, double g_pdf);
double balance_heuristic(double nf, double f_pdf, double ng, double g_pdf);
Color estimate_direct_lighting_mis(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, Rng& rng);
}  // namespace reference

namespace student {
Color diffuse_f(const Color& albedo, const Vec3& wo, const Vec3& wi);
BSDFSample diffuse_sample_f(const Color& albedo, const Vec3& wo, Vec2 u);
Color zero_bounce_radiance(const RenderContext& context, const Ray& ray,
                           const SurfaceInteraction& isect);
Color estimate_direct_lighting_hemisphere(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng);
Color estimate_direct_lighting_importance(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng);
Color one_bounce_radiance(const RenderContext& context, const Ray& ray,
                          const SurfaceInteraction& isect, Rng& rng);
double power_heuristic(double nf, double f_pdf, double ng, double g_pdf);
double balance_heuristic(double nf, double f_pdf, double ng, double g_pdf);
Color estimate_direct_lighting_mis(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, Rng& rng);
}  // namespace student

}  // namespace pt
