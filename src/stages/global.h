// Stage `global` (Part 4): global illumination by path tracing.
//
// The rendering equation (Kajiya 1986) says that the radiance leaving a
// point x in direction wo is what x emits plus what it reflects of the
// radiance arriving from every direction, and that arriving radiance is
// itself the radiance leaving the point seen along wi:
//
//     L(x, wo) = Le(x, wo) + integral f(x, wo, wi) L(x'(x, wi), -wi) |cos theta_i| dwi
//
// Write it as L = Le + T L, with T the transport operator (one reflection).
// Its solution is the Neumann series
//
//     L = Le + T Le + T^2 Le + T^3 Le + ...
//
// where T^k Le is the light that reached the camera after exactly k
// reflections (bounces). The series converges because every surface
// reflects less than it receives (||T|| < 1).
//
// The depth convention, as in CS184 and pbrt (-m, -o on the command line):
// a path's bounces are its scattering events between the camera and the
// point that emitted the light. `-m 0` renders emission only (Le), `-m 1`
// adds direct light (T Le), `-m k` the paths of up to k bounces; `-o 1`
// (default) accumulates bounces 0..m, `-o 0` returns only the m-th (T^m Le).
// Mirror and glass bounces count like any other. A SurfaceInteraction found
// by a ray of depth d (the camera ray has depth 0) is the (d+1)-th vertex:
// light it scatters towards the camera has made d + 1 bounces.
//
// Path tracing estimates every term with one random path: at each vertex,
// direct light by next-event estimation (one_bounce_radiance, Part 3), then
// one direction drawn from the BSDF (sample_f) carries the path on with
// weight f |cos| / pdf. Emission that a BSDF-sampled ray finds is counted
// only after a delta (mirror, glass) bounce, which light sampling cannot
// reach; elsewhere next-event estimation has counted it already.
//
// Russian roulette (Arvo and Kirk 1990): after --rr-depth bounces (3 by
// default), a path continues with probability q = min(0.95, max component
// of its throughput) and its weight is divided by q. The estimate is then
// q * (X / q) + (1 - q) * 0 = X on average: unbiased, and long paths of
// little weight stop early. q <= 0.95 makes every path end (after 20 more
// bounces on average), even in a closed box of albedo 1; -m stays a hard cap.
//
// Sources: Kajiya, "The Rendering Equation", SIGGRAPH 1986; Veach 1997,
// chapter 3 (path integral, Neumann series); pbrt-v3 sections 14.4-14.5
// (Russian roulette, the path tracer); CS184 PathTracer Part 4.
//
// Tests that prove it (tests/global/): the interior furnace (a closed box
// whose walls emit Le and reflect rho: Le (1 - rho^(m+1)) / (1 - rho) with
// -o 1, Le rho^m with -o 0, Le / (1 - rho) with roulette and no cap), the
// convex white furnace (diffuse, glass and mirror spheres of albedo 1 under
// a sky of radiance 1 render 1), roulette on and off agreeing, the albedo-1
// box ending in bounded time, total internal reflection in glass.
#pragma once

#include "core/color.h"
#include "core/ray.h"
#include "core/rng.h"

namespace pt {

struct RenderContext;
struct SurfaceInteraction;

/// Russian roulette never lets a path survive with probability above this:
/// every path ends (a box of albedo 1 would otherwise never stop).
constexpr double kMaxSurvivalProbability = 0.95;

using AtLeastOneBounceFn = Color (*)(const RenderContext& context, const Ray& ray,
                                     const SurfaceInteraction& isect, const Color& throughput,
                                     Rng& rng);
using EstRadianceGlobalFn = Color (*)(const RenderContext& context, const Ray& ray, Rng& rng);

/// The function table of the stage. Radiance is W/(m^2 sr), linear RGB;
/// random numbers come only from `rng`; settings from context.settings
/// (max_depth = -m, accumulate_bounces = -o, russian_roulette, rr_depth).
struct GlobalStage {
    /// Radiance leaving isect.p towards the origin of `ray` (along isect.wo)
    /// carried by paths of at least one bounce: direct light at isect (paths
    /// of isect.depth + 1 bounces) plus everything scattered there from
    /// farther vertices, up to -m bounces in all (only the -m-th with -o 0).
    /// isect is the closest hit of `ray`, isect.depth = ray.depth < -m.
    /// `throughput` is the product of the path's weights from the camera to
    /// isect (1 for the camera's first hit): Russian roulette takes its
    /// survival probability from it. Not counted: isect's own emission.
    AtLeastOneBounceFn at_least_one_bounce_radiance;
    /// Radiance arriving at the origin of the camera ray `ray` (depth 0):
    /// emission of its closest hit (zero bounces, when -o 1 or -m 0) plus
    /// at_least_one_bounce_radiance there (when -m >= 1). On a miss: the
    /// environment's radiance when zero bounces are wanted, else black.
    EstRadianceGlobalFn est_radiance_global_illumination;
};

namespace reference {
Color at_least_one_bounce_radiance(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, const Color& throughput,
                                   Rng& rng);
Color est_radiance_global_illumination(const RenderContext& context, const Ray& ray, Rng& rng);
}  // namespace reference

namespace student {
Color at_least_one_bounce_radiance(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, const Color& throughput,
                                   Rng& rng);
Color est_radiance_global_illumination(const RenderContext& context, const Ray& ray, Rng& rng);
}  // namespace student

}  // namespace pt
