// Part 3, tasks 7 and 8, written from the TODO steps and the contracts of
// src/stages/direct.h (Veach 1997, sections 9.2.2 and 9.2.4).
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/math.h"
#include "stages/direct.h"
#include "stages/mis.h"
#include "stages/render_context.h"

namespace pt::student {

double power_heuristic(double nf, double f_pdf, double ng, double g_pdf) {
    const double a = nf * f_pdf, b = ng * g_pdf;
    if (a == 0) return 0;
    if (std::isinf(a)) return std::isinf(b) ? 0.5 : 1;
    // Divide before squaring: (b / a)^2 cannot overflow into inf / inf.
    const double r = b / a;
    return 1 / (1 + r * r);
}

double balance_heuristic(double nf, double f_pdf, double ng, double g_pdf) {
    const double a = nf * f_pdf, b = ng * g_pdf;
    if (a == 0) return 0;
    if (std::isinf(a)) return std::isinf(b) ? 0.5 : 1;
    return 1 / (1 + b / a);
}

Color estimate_direct_lighting_mis(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, Rng& rng) {
    (void)ray;
    BSDF bsdf = context.bsdf_at(isect);
    if (bsdf.is_delta()) return Color(0);
    const Vec3 wo = bsdf.to_local(isect.wo);
    const LightSampleContext ref = light_sample_context(isect, bsdf);
    const bool both_sides = bsdf.is_transmissive();
    const int l = context.settings.light_samples;
    const int nb = std::max(1, l);
    Color L;
    // 1. Light samples, weighted against the nb BSDF samples.
    for (const auto& light : context.lights.all()) {
        const int n = light->sample_count(l);
        Color sum;
        for (int i = 0; i < n; ++i) {
            LightSample s = light->sample_Li(ref, rng.next_2d());
            if (!s.valid()) continue;
            const Vec3 wi = bsdf.to_local(s.wi);
            const double cos = both_sides ? std::fabs(wi.z) : wi.z;
            if (cos <= 0) continue;
            if (context.occluded(isect.spawn_ray_to(s.p))) continue;
            const double w = s.is_delta ? 1.0 : mis_weight(context, n, s.pdf, nb, bsdf.pdf(wo, wi));
            sum += bsdf.f(wo, wi) * s.L * (cos / s.pdf * w);
        }
        L += sum / double(n);
    }
    // 2. BSDF samples, weighted against the light they find.
    Color from_bsdf;
    for (int j = 0; j < nb; ++j) {
        BSDFSample bs = bsdf.sample_f(wo, rng.next_2d());
        if (!bs.valid()) continue;
        // A valid sample of a BSDF that only reflects lies above the surface.
        const double cos = both_sides ? std::fabs(bs.wi.z) : bs.wi.z;
        const Vec3 wi = bsdf.to_world(bs.wi);
        const Ray bounce = isect.spawn_ray(wi);
        std::optional<SurfaceInteraction> hit = context.intersect(bounce);
        const Light* light = nullptr;
        Color Le;
        double light_pdf = 0;
        if (hit) {
            Le = context.stages.direct.zero_bounce_radiance(context, bounce, *hit);
            light = context.lights.light_of_primitive(hit->primitive);
            if (light) light_pdf = light->pdf_Li(ref, wi, hit->p, hit->ng);
        } else {
            light = context.lights.environment();
            if (light) {
                Le = light->Le(wi);
                light_pdf = light->pdf_Li(ref, wi, {}, {});
            }
        }
        const double w = light ? mis_weight(context, nb, bs.pdf, light->sample_count(l), light_pdf) : 1.0;
        from_bsdf += Le * bs.f * (cos / bs.pdf * w);
    }
    return L + from_bsdf / double(nb);
}

}  // namespace pt::student
