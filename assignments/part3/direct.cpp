// Part 3, tasks 3 to 6: emission and direct lighting. Read
// assignments/part3/README.md first; the contract of each function is in
// src/stages/direct.h.
//
// What you have (see the README for a worked example of each):
//   context.bsdf_at(isect)           the BSDF at the hit; bsdf.to_local / to_world
//                                    move directions to and from its frame (normal = +z)
//   context.intersect(ray)           the closest hit, or std::nullopt
//   context.occluded(ray)            whether anything blocks a shadow ray
//   isect.spawn_ray(w)               a ray leaving the surface in world direction w
//   isect.spawn_ray_to(p)            a shadow ray from the surface that stops just before p
//   context.lights.all()             every light; light->sample_Li(ref, u) picks a
//                                    direction towards it (scene/light_set.h)
//   context.lights.environment_radiance(d)   what a ray that leaves the scene sees
//   context.settings.light_samples   -l; context.settings.direct: -H / --direct
#include <algorithm>

#include "core/error.h"
#include "core/math.h"
#include "core/sampling.h"
#include "stages/mis.h"
#include "stages/render_context.h"
#include "stages/direct.h"

namespace pt::student {

Color zero_bounce_radiance(const RenderContext& context, const Ray& ray,
                           const SurfaceInteraction& isect) {
    // TODO(part3.3): zero_bounce_radiance, as src/stages/direct.h states its contract.
    // [guided]
    // the light emitted by the surface towards the camera:
    // isect.material->emission when isect.wo is on the front side of the
    // geometric normal (dot(isect.ng, isect.wo) > 0), black otherwise
    // (lights emit on one side only).
    // [/guided]
    (void)context, (void)ray, (void)isect;
    throw NotImplemented(3, "3", "zero_bounce_radiance");
}

Color estimate_direct_lighting_hemisphere(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng) {
    // TODO(part3.4): estimate_direct_lighting_hemisphere, as src/stages/direct.h states its contract.
    // [guided]
    // uniform hemisphere sampling. With the BSDF from
    // context.bsdf_at(isect) (return black if bsdf.is_delta()), take
    // N = context.settings.light_samples * context.lights.non_delta_count()
    // directions (return black if N is 0: no light can be hit) wi =
    // sample_uniform_hemisphere(rng.next_2d()) (local frame, pdf =
    // uniform_hemisphere_pdf()). For each, trace isect.spawn_ray of its
    // world direction; the light arriving is the emission of what it hits,
    // context.stages.direct.zero_bounce_radiance(context, bounce, *hit)
    // (through the stage table, as Part 4 calls it, so that your estimator
    // is graded with the reference's emission and a bug in task 3.3 costs
    // task 3.3 alone), or context.lights.environment_radiance on a miss.
    // Return 1/N sum f(wo, wi) Li cos(theta) / pdf.
    // [/guided]
    (void)context, (void)ray, (void)isect, (void)rng;
    throw NotImplemented(3, "4", "estimate_direct_lighting_hemisphere");
}

Color estimate_direct_lighting_importance(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng) {
    // TODO(part3.5): estimate_direct_lighting_importance, as src/stages/direct.h states its contract.
    // [guided]
    // light (importance) sampling. With the BSDF (black if
    // bsdf.is_delta()) and LightSampleContext ref{isect.p, bsdf.frame().n},
    // for every light take n = light->sample_count(context.settings.light_samples)
    // samples s = light->sample_Li(ref, rng.next_2d()). Skip a sample that
    // is invalid, below the surface (local wi.z <= 0), or blocked
    // (context.occluded(isect.spawn_ray_to(s.p))); else add
    // f(wo, wi) s.L cos(theta) / s.pdf. Average per light, sum over lights.
    // [/guided]
    (void)context, (void)ray, (void)isect, (void)rng;
    throw NotImplemented(3, "5", "estimate_direct_lighting_importance");
}

Color one_bounce_radiance(const RenderContext& context, const Ray& ray,
                          const SurfaceInteraction& isect, Rng& rng) {
    // TODO(part3.6): one_bounce_radiance, as src/stages/direct.h states its contract.
    // [guided]
    // pick the estimator by context.settings.direct:
    // DirectStrategy::hemisphere (-H) -> estimate_direct_lighting_hemisphere,
    // DirectStrategy::light -> estimate_direct_lighting_importance,
    // DirectStrategy::mis -> estimate_direct_lighting_mis (task 3.8, mis.cpp).
    // [/guided]
    (void)context, (void)ray, (void)isect, (void)rng;
    throw NotImplemented(3, "6", "one_bounce_radiance");
}

}  // namespace pt::student
