// Part 4, tasks 1 and 2: global illumination by path tracing (CS184's
// at_least_one_bounce_radiance and est_radiance_global_illumination).
// Read assignments/part4/README.md first; the contract of each function,
// the depth convention and the Russian roulette rule are in
// src/stages/global.h.
//
// What you have, besides Part 3's (see assignments/part3/direct.cpp):
//   context.stages.direct.one_bounce_radiance(context, ray, isect, rng)
//                                    direct light at isect (Part 3, -l, -H, --direct)
//   context.stages.direct.zero_bounce_radiance(context, ray, isect)
//                                    emission of isect towards the ray's origin
//   bsdf.sample_f(wo, rng.next_2d()) a direction wi with f and pdf (local frame);
//                                    bs.is_delta for mirror and glass
//   isect.depth                      bounces before isect: isect.depth + 1 for
//                                    light it scatters towards the camera
//   context.settings.max_depth (-m), accumulate_bounces (-o), russian_roulette,
//   rr_depth (--rr-depth); kMaxSurvivalProbability (0.95, stages/global.h)
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.h"
#include "stages/render_context.h"
#include "stages/global.h"

namespace pt::student {

Color at_least_one_bounce_radiance(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, const Color& throughput,
                                   Rng& rng) {
    // TODO(part4.1): at_least_one_bounce_radiance, as src/stages/global.h states its contract.
    // [guided]
    // the light leaving isect towards the camera after at
    // least one bounce, recursively. With bsdf = context.bsdf_at(isect),
    // wo = bsdf.to_local(isect.wo), bounces = isect.depth + 1, m =
    // context.settings.max_depth and counted = context.settings.accumulate_bounces
    // || bounces == m (with -o 0 only the m-th bounce counts):
    //  1. Direct light: if counted and !bsdf.is_delta(), L =
    //     context.stages.direct.one_bounce_radiance(context, ray, isect, rng).
    //  2. The cap: if bounces == m, return L, unless bsdf.is_delta() and
    //     counted (then the next ray is still needed for the emission it
    //     finds, which has `bounces` bounces: light sampling cannot see
    //     through mirrors and glass).
    //  3. bs = bsdf.sample_f(wo, rng.next_2d()); return L if !bs.valid() or
    //     bs.f is black. weight = bs.f * |bs.wi.z| / bs.pdf.
    //  4. Russian roulette: if context.settings.russian_roulette and bounces >
    //     context.settings.rr_depth, q = min(kMaxSurvivalProbability,
    //     (throughput * weight).max_component()); return L if rng.next_1d() >= q,
    //     else weight /= q.
    //  5. next = isect.spawn_ray(bsdf.to_world(bs.wi)), hit = context.intersect(next).
    //  6. If bs.is_delta and counted: L += weight * (zero_bounce_radiance of the
    //     hit, or context.lights.environment_radiance(next.d) on a miss).
    //  7. If hit and bounces < m: L += weight * at_least_one_bounce_radiance(
    //     context, next, *hit, throughput * weight, rng).
    // Return L.
    // [/guided]
    (void)context, (void)ray, (void)isect, (void)throughput, (void)rng;
    throw NotImplemented(4, "1", "at_least_one_bounce_radiance");
}

Color est_radiance_global_illumination(const RenderContext& context, const Ray& ray, Rng& rng) {
    // TODO(part4.2): est_radiance_global_illumination, as src/stages/global.h states its contract.
    // [guided]
    // the radiance arriving along the camera ray. With
    // zero = context.settings.accumulate_bounces || context.settings.max_depth == 0
    // and isect = context.intersect(ray):
    //  - on a miss: context.lights.environment_radiance(ray.d) if zero, else black;
    //  - on a hit: context.stages.direct.zero_bounce_radiance(context, ray, *isect)
    //    if zero, plus context.stages.global.at_least_one_bounce_radiance(
    //    context, ray, *isect, Color(1.0), rng) if max_depth >= 1 (through
    //    the stage table, so that each task can be graded on its own).
    // [/guided]
    (void)context, (void)ray, (void)rng;
    throw NotImplemented(4, "2", "est_radiance_global_illumination");
}

}  // namespace pt::student
