// Medium tracking: which medium a ray is in, what fraction of light
// survives a segment, and where a path collides next. The volume path
// tracer (render/volpath_integrator.cpp) and Part 9's single scattering
// build on these; the closed forms they call for homogeneous media are the
// media stage's (stages/media.h), so a student's code runs inside them.
//
// Which medium (docs/media.md): a ray that reflects stays in its medium; a
// ray that crosses a glass, rough_dielectric or null surface whose material
// holds a medium enters it when it crosses against the surface's outward
// geometric normal and is back in the scene's medium when it crosses along
// it. Glass without an interior holds vacuum; a null surface without one
// changes nothing.
//
// Heterogeneous media (a density grid; scene/density_grid.h) are tracked
// against one majorant, sigma_maj = max density x max channel of sigma_t,
// inside the grid's box (density 0 outside):
//
//   ratio tracking (Novak et al. 2014): tentative collisions at rate
//     sigma_maj; the transmittance estimate is the product of the null
//     fractions 1 - sigma_t(x_i) / sigma_maj, per channel. Never 0 by
//     chance: the estimator for shadow rays.
//   delta tracking (Woodcock et al. 1965): at each tentative collision the
//     ray stops with probability sigma_t(x) / sigma_maj (averaged over the
//     channels, the per-channel difference weighted in), else goes on: an
//     estimate of 0 or about 1. Kept for `bench accuracy` to compare.
//   free flights: the same tentative collisions; at each, scatter with
//     probability P_s = mean(sigma_s) / (mean(sigma_s) + mean(sigma_n)),
//     sigma_n = sigma_maj - sigma_t, with weight sigma_s / (sigma_maj P_s),
//     else pass with weight sigma_n / (sigma_maj (1 - P_s)); absorption lives
//     in the weights (pbrt-v4 section 14.2.3 with one majorant for all
//     channels). Unbiased for any sigma_maj >= sigma_t.
//
// Homogeneous media sample the distance with one channel, the path's "hero"
// channel picked uniformly once per camera path, and weight the whole path
// by the balance heuristic over the three channels (one-sample MIS;
// pbrt-v4's spectral MIS, Mitsuba's chromatic media): the path carries its
// throughput divided by the hero's pdf, beta, and the ratios r_c = p_c /
// p_hero of each channel's path pdf to the hero's, and contributes
// beta L / mean_c(r_c). With T = e^(-sigma_t t) per channel and h the hero,
//     scattered at t: beta *= T sigma_s / (sigma_t,h T_h),  r *= sigma_t T / (sigma_t,h T_h)
//     passed (t_max): beta *= T / T_h,                      r *= T / T_h
// r_h stays 1, so mean(r) >= 1/3 and the weight of a whole path is at most
// 3 times its f / p; choosing the channel anew at every collision instead
// would bound each collision's factor by 3, and a path's by 3^k.
//
// Tests: tests/global/test_media_render.cpp (transmittance through slabs and
// spheres, delta against ratio tracking, single scattering against
// quadrature, the medium furnace).
#pragma once

#include "core/color.h"
#include "core/ray.h"
#include "core/rng.h"
#include "scene/interaction.h"
#include "scene/medium.h"

namespace pt {

struct RenderContext;
struct Scene;

/// The medium (index into scene.media, or -1 for vacuum) of a ray leaving
/// `isect` in world direction w, when the ray that arrived travelled in `current`.
int medium_after(const Scene& scene, const SurfaceInteraction& isect, const Vec3& w, int current);

/// The medium around the point p (the camera): walks a ray from p past
/// every surface until one crossing tells inside from outside.
int medium_at(const RenderContext& context, const Vec3& p);

/// How a heterogeneous segment's transmittance is estimated.
enum class TrackingEstimator { ratio, delta };

/// The transmittance of medium m along ray between ray parameters t0 < t1
/// (ray.d of any length; distances are t * |d|): closed form through the
/// media stage when homogeneous, else the tracking estimator (unbiased).
Color segment_transmittance(const RenderContext& context, const Medium& m, const Ray& ray, double t0, double t1,
                            Rng& rng, TrackingEstimator estimator = TrackingEstimator::ratio);

/// The transmittance along the shadow ray `ray` (its whole interval, the
/// origin in medium `medium`): through null surfaces (changing medium as
/// they say), 0 at any other surface. The estimator in density grids is
/// the one --transmittance names (ratio tracking unless told otherwise).
Color shadow_transmittance(const RenderContext& context, Ray ray, int medium, Rng& rng);
Color shadow_transmittance(const RenderContext& context, Ray ray, int medium, Rng& rng,
                           TrackingEstimator estimator);

/// A free flight along a ray with unit direction through medium m, up to
/// t_max (the next surface, or infinity).
struct FreeFlight {
    bool scattered = false;  ///< a real collision (scattering) at t < t_max
    double t = 0;            ///< where: the collision, or t_max
    Color weight{1.0};       ///< what beta is multiplied by (see the file comment)
    Color pdf_ratio{1.0};    ///< what the path's pdf ratios r are multiplied by
};
/// `hero` (0, 1 or 2) is the channel whose distances the path samples.
FreeFlight sample_free_flight(const RenderContext& context, const Medium& m, const Ray& ray, double t_max,
                              int hero, Rng& rng);

}  // namespace pt
