#include "stages/mis.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"
#include "stages/direct.h"
#include "stages/render_context.h"

namespace pt {

double mis_weight(const RenderContext& context, double nf, double f_pdf, double ng, double g_pdf) {
    const DirectStage& stage = context.stages.direct;
    return context.settings.mis_heuristic == MisHeuristic::balance
               ? stage.balance_heuristic(nf, f_pdf, ng, g_pdf)
               : stage.power_heuristic(nf, f_pdf, ng, g_pdf);
}

LightSampleContext light_sample_context(const SurfaceInteraction& isect, const BSDF& bsdf) {
    return {isect.p, bsdf.is_transmissive() ? Vec3(0, 0, 0) : bsdf.frame().n};
}

Color sample_lights_mis(const RenderContext& context, const SurfaceInteraction& isect,
                        const BSDF& bsdf, const Vec3& wo, int bsdf_samples, Rng& rng) {
    LightSampleContext ref = light_sample_context(isect, bsdf);
    const bool both_sides = bsdf.is_transmissive();
    rng.seek(isect.depth, SampleSlot::light);  // the sampler's dimensions of light samples (core/sampler.h)
    Color L;
    for (const std::unique_ptr<Light>& light : context.lights.all()) {
        int n = light->sample_count(context.settings.light_samples);
        Color sum;
        for (int i = 0; i < n; ++i) {
            LightSample s = light->sample_Li(ref, rng.next_2d());
            if (!s.valid() || s.L.is_black()) continue;
            Vec3 wi = bsdf.to_local(s.wi);
            const double cos_i = both_sides ? std::fabs(wi.z) : wi.z;
            if (!(cos_i > 0)) continue;  // below the shading hemisphere: cos <= 0
            Color f = bsdf.f(wo, wi);
            if (f.is_black()) continue;
            // The shadow ray last: it is the expensive part.
            if (context.occluded(isect.spawn_ray_to(s.p))) continue;
            // No BSDF sample can find a delta light; without BSDF samples the weight is 1.
            double weight = s.is_delta || bsdf_samples == 0
                                ? 1.0
                                : mis_weight(context, n, s.pdf, bsdf_samples, bsdf.pdf(wo, wi));
            sum += f * s.L * (weight * cos_i / s.pdf);
        }
        L += sum / double(n);
    }
    return L;
}

double bsdf_sample_mis_weight(const RenderContext& context, const LightSampleContext& ref,
                              const Vec3& wi, const std::optional<SurfaceInteraction>& hit,
                              double bsdf_pdf, int bsdf_samples) {
    const Light* light =
        hit ? context.lights.light_of_primitive(hit->primitive) : context.lights.environment();
    if (!light) return 1.0;
    double light_pdf =
        hit ? light->pdf_Li(ref, wi, hit->p, hit->ng) : light->pdf_Li(ref, wi, {}, {});
    int n = light->sample_count(context.settings.light_samples);
    return mis_weight(context, bsdf_samples, bsdf_pdf, n, light_pdf);
}

namespace reference {

double power_heuristic(double nf, double f_pdf, double ng, double g_pdf) {
    return pt::power_heuristic(nf, f_pdf, ng, g_pdf);
}

double balance_heuristic(double nf, double f_pdf, double ng, double g_pdf) {
    return pt::balance_heuristic(nf, f_pdf, ng, g_pdf);
}

Color estimate_direct_lighting_mis(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, Rng& rng) {
    (void)ray;
    BSDF bsdf = context.bsdf_at(isect);
    if (bsdf.is_delta()) return Color(0);
    Vec3 wo = bsdf.to_local(isect.wo);
    const int n_bsdf = std::max(1, context.settings.light_samples);
    Color L = sample_lights_mis(context, isect, bsdf, wo, n_bsdf, rng);
    // No BSDF sample can hit a delta light: without area or environment
    // lights the rays below would find nothing.
    if (context.lights.non_delta_count() == 0) return L;

    LightSampleContext ref = light_sample_context(isect, bsdf);
    rng.seek(isect.depth, SampleSlot::bsdf);
    Color sum;
    for (int i = 0; i < n_bsdf; ++i) {
        BSDFSample bs = bsdf.sample_f(wo, rng.next_2d());
        if (!bs.valid() || bs.f.is_black()) continue;
        Vec3 wi = bsdf.to_world(bs.wi);
        Ray bounce = isect.spawn_ray(wi);
        std::optional<SurfaceInteraction> hit = context.intersect(bounce);
        Color Le = hit ? context.stages.direct.zero_bounce_radiance(context, bounce, *hit)
                       : context.lights.environment_radiance(wi);
        if (Le.is_black()) continue;
        double weight = bsdf_sample_mis_weight(context, ref, wi, hit, bs.pdf, n_bsdf);
        sum += bs.f * Le * (weight * std::fabs(bs.wi.z) / bs.pdf);
    }
    return L + sum / double(n_bsdf);
}

}  // namespace reference

}  // namespace pt
