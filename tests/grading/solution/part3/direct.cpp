// Part 3, tasks 3 to 6, written from the TODO steps.
#include "core/math.h"
#include "core/sampling.h"
#include "stages/direct.h"
#include "stages/mis.h"
#include "stages/render_context.h"

namespace pt::student {

Color zero_bounce_radiance(const RenderContext& context, const Ray& ray,
                           const SurfaceInteraction& isect) {
    (void)context, (void)ray;
    if (dot(isect.ng, isect.wo) > 0) return isect.material->emission;
    return Color(0);
}

Color estimate_direct_lighting_hemisphere(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng) {
    (void)ray;
    BSDF bsdf = context.bsdf_at(isect);
    if (bsdf.is_delta()) return Color(0);
    const int n = context.settings.light_samples * context.lights.non_delta_count();
    if (n == 0) return Color(0);
    Vec3 wo = bsdf.to_local(isect.wo);
    Color sum;
    for (int i = 0; i < n; ++i) {
        Vec3 wi = sample_uniform_hemisphere(rng.next_2d());
        Ray bounce = isect.spawn_ray(bsdf.to_world(wi));
        std::optional<SurfaceInteraction> hit = context.intersect(bounce);
        Color Li;
        if (hit)
            Li = context.stages.direct.zero_bounce_radiance(context, bounce, *hit);
        else
            Li = context.lights.environment_radiance(bounce.d);
        sum += bsdf.f(wo, wi) * Li * (wi.z / uniform_hemisphere_pdf());
    }
    return sum / double(n);
}

Color estimate_direct_lighting_importance(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng) {
    (void)ray;
    BSDF bsdf = context.bsdf_at(isect);
    if (bsdf.is_delta()) return Color(0);
    Vec3 wo = bsdf.to_local(isect.wo);
    LightSampleContext ref{isect.p, bsdf.frame().n};
    Color L;
    for (const auto& light : context.lights.all()) {
        const int n = light->sample_count(context.settings.light_samples);
        Color sum;
        for (int i = 0; i < n; ++i) {
            LightSample s = light->sample_Li(ref, rng.next_2d());
            if (!s.valid()) continue;
            Vec3 wi = bsdf.to_local(s.wi);
            if (wi.z <= 0) continue;
            if (context.occluded(isect.spawn_ray_to(s.p))) continue;
            sum += bsdf.f(wo, wi) * s.L * (wi.z / s.pdf);
        }
        L += sum / double(n);
    }
    return L;
}

Color one_bounce_radiance(const RenderContext& context, const Ray& ray,
                          const SurfaceInteraction& isect, Rng& rng) {
    switch (context.settings.direct) {
        case DirectStrategy::hemisphere:
            return estimate_direct_lighting_hemisphere(context, ray, isect, rng);
        case DirectStrategy::light:
            return estimate_direct_lighting_importance(context, ray, isect, rng);
        case DirectStrategy::mis:
            return estimate_direct_lighting_mis(context, ray, isect, rng);
    }
    return Color(0);
}

}  // namespace pt::student
