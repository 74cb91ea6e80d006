// Part 4, written from the TODO steps (recursive).
#include <algorithm>
#include <cmath>
#include <optional>

#include "stages/global.h"
#include "stages/render_context.h"

namespace pt::student {

Color at_least_one_bounce_radiance(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, const Color& throughput,
                                   Rng& rng) {
    const RenderSettings& settings = context.settings;
    BSDF bsdf = context.bsdf_at(isect);
    Vec3 wo = bsdf.to_local(isect.wo);
    const int bounces = isect.depth + 1, m = settings.max_depth;
    const bool counted = settings.accumulate_bounces || bounces == m;
    Color L;
    if (counted && !bsdf.is_delta())  // 1.
        L = context.stages.direct.one_bounce_radiance(context, ray, isect, rng);
    if (bounces == m && !(bsdf.is_delta() && counted)) return L;  // 2.
    BSDFSample bs = bsdf.sample_f(wo, rng.next_2d());             // 3.
    if (!bs.valid() || bs.f.is_black()) return L;
    Color weight = bs.f * std::fabs(bs.wi.z) / bs.pdf;
    if (settings.russian_roulette && bounces > settings.rr_depth) {  // 4.
        double q = std::min(kMaxSurvivalProbability, (throughput * weight).max_component());
        if (rng.next_1d() >= q) return L;
        weight /= q;
    }
    Ray next = isect.spawn_ray(bsdf.to_world(bs.wi));  // 5.
    std::optional<SurfaceInteraction> hit = context.intersect(next);
    if (bs.is_delta && counted) {  // 6.
        if (hit)
            L += weight * context.stages.direct.zero_bounce_radiance(context, next, *hit);
        else
            L += weight * context.lights.environment_radiance(next.d);
    }
    if (hit && bounces < m)  // 7.
        L += weight * at_least_one_bounce_radiance(context, next, *hit, throughput * weight, rng);
    return L;
}

Color est_radiance_global_illumination(const RenderContext& context, const Ray& ray, Rng& rng) {
    const RenderSettings& settings = context.settings;
    const bool zero = settings.accumulate_bounces || settings.max_depth == 0;
    std::optional<SurfaceInteraction> isect = context.intersect(ray);
    if (!isect) {
        if (zero) return context.lights.environment_radiance(ray.d);
        return Color(0);
    }
    Color L;
    if (zero) L += context.stages.direct.zero_bounce_radiance(context, ray, *isect);
    if (settings.max_depth >= 1)
        L += context.stages.global.at_least_one_bounce_radiance(context, ray, *isect, Color(1.0),
                                                                rng);
    return L;
}

}  // namespace pt::student
