// Reference implementation of stage `direct`. See stages/direct.h.
#include "stages/direct.h"

#include <algorithm>

#include "core/math.h"
#include "core/sampling.h"
#include "stages/mis.h"
#include "stages/render_context.h"

namespace pt::reference {

Color diffuse_f(const Color& albedo, const Vec3& wo, const Vec3& wi) {
    // A Lambertian surface scatters equally into every direction, and
    // integral_H f cos dw = albedo for f = albedo / pi: energy is conserved.
    // wo is not needed; the frame already faces the side that wo is on.
    (void)wo;
    return wi.z > 0 ? albedo * kInvPi : Color(0);
}

BSDFSample diffuse_sample_f(const Color& albedo, const Vec3& wo, Vec2 u) {
    (void)wo;
    BSDFSample s;
    // Cosine weighting makes f cos / pdf = albedo constant: the estimator's
    // only noise is then what the light contributes.
    s.wi = sample_cosine_hemisphere(u);
    s.pdf = cosine_hemisphere_pdf(s.wi.z);
    if (!(s.pdf > 0)) return {};  // on the horizon: cos = 0, nothing to carry
    s.f = albedo * kInvPi;
    return s;
}

Color zero_bounce_radiance(const RenderContext& context, const Ray& ray,
                           const SurfaceInteraction& isect) {
    (void)context, (void)ray;
    // Area lights are one-sided: they emit on the side of their geometric normal.
    return dot(isect.ng, isect.wo) > 0 ? isect.material->emission : Color(0);
}

Color estimate_direct_lighting_hemisphere(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng) {
    (void)ray;
    BSDF bsdf = context.bsdf_at(isect);
    // A delta BSDF reflects no sampled direction; a scene of delta lights
    // only has nothing a ray could hit.
    if (bsdf.is_delta() || context.lights.non_delta_count() == 0) return Color(0);
    Vec3 wo = bsdf.to_local(isect.wo);
    const int n = std::max(1, context.settings.light_samples) * context.lights.non_delta_count();
    const double pdf = uniform_hemisphere_pdf();
    rng.seek(isect.depth, SampleSlot::bsdf);  // the sampler's dimensions of BSDF-side draws (core/sampler.h)
    Color sum;
    for (int i = 0; i < n; ++i) {
        Vec3 wi = sample_uniform_hemisphere(rng.next_2d());
        Ray bounce = isect.spawn_ray(bsdf.to_world(wi));
        std::optional<SurfaceInteraction> hit = context.intersect(bounce);
        // Direct light only: what the ray sees is emission (or the sky), not
        // light reflected there.
        Color Li = hit ? zero_bounce_radiance(context, bounce, *hit)
                       : context.lights.environment_radiance(bounce.d);
        if (Li.is_black()) continue;
        sum += bsdf.f(wo, wi) * Li * (wi.z / pdf);
    }
    return sum / double(n);
}

Color estimate_direct_lighting_importance(const RenderContext& context, const Ray& ray,
                                          const SurfaceInteraction& isect, Rng& rng) {
    (void)ray;
    BSDF bsdf = context.bsdf_at(isect);
    if (bsdf.is_delta()) return Color(0);  // f is zero towards every light sample
    // Plain light sampling is MIS with no BSDF samples: every weight is 1.
    return sample_lights_mis(context, isect, bsdf, bsdf.to_local(isect.wo), 0, rng);
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

}  // namespace pt::reference
