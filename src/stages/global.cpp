// Reference implementation of stage `global`: the path tracer. See
// stages/global.h for the equations, the depth convention and Russian
// roulette.
//
// Iterative rather than recursive (a path may be thousands of bounces long
// with -m large and roulette off), with one weight `beta` per path. How
// direct light is estimated at each vertex follows --direct:
//
//   light (default)  next-event estimation by light sampling; emission found
//                    by BSDF-sampled rays counts only after delta bounces
//   mis              light samples and the path's own BSDF sample, weighted
//                    by the power heuristic (stages/mis.h): the continuation
//                    ray doubles as the BSDF half of MIS
//   hemisphere       no light sampling: every BSDF-sampled ray that finds an
//                    emitter counts it (the naive path tracer; point and
//                    directional lights are never found)
//
// When `direct` is a student stage (part3 with -m >= 2), direct light at
// every vertex is the student's one_bounce_radiance and emission counts
// only after delta bounces, CS184's structure: the student's Part 3 code
// runs at every vertex of the global illumination image.
#include "stages/global.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "stages/mis.h"
#include "stages/render_context.h"

namespace pt::reference {

Color at_least_one_bounce_radiance(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, const Color& throughput,
                                   Rng& rng) {
    const RenderSettings& settings = context.settings;
    const CodePaths& paths = context.code_paths;
    const DirectStage& direct = context.stages.direct;
    const bool course_structure = context.stages.is_student(Stage::direct);
    const bool mis = !course_structure && settings.direct == DirectStrategy::mis;
    const bool light_sampling =
        paths.light_sampling && (course_structure || settings.direct != DirectStrategy::hemisphere);
    // Emission found by a BSDF-sampled ray from a non-delta vertex: counted
    // by MIS (weighted) and by hemisphere sampling (weight 1); by nothing
    // else, since next-event estimation has counted it already.
    const bool bsdf_emission = !course_structure && settings.direct != DirectStrategy::light;

    Color L;
    Color beta(1.0);         // the path's weight from isect to the current vertex
    double eta_scale = 1.0;  // product of eta^2 of refractions: kept out of roulette
    Ray r = ray;
    SurfaceInteraction x = isect;
    for (;;) {
        const int bounces = x.depth + 1;  // of light that x scatters towards the camera
        const bool counted = settings.accumulate_bounces || bounces == settings.max_depth;
        BSDF bsdf = context.bsdf_at(x);
        const Vec3 wo = bsdf.to_local(x.wo);

        // 1. Next-event estimation: light arriving at x straight from a light.
        if (light_sampling && counted && !bsdf.is_delta()) {
            if (course_structure)
                L += beta * direct.one_bounce_radiance(context, r, x, rng);
            else
                L += beta * sample_lights_mis(context, x, bsdf, wo, mis ? 1 : 0, rng);
        }

        // 2. The next ray: to continue the path, or (at the last bounce) only
        //    for the emission it finds, which has `bounces` bounces too.
        const bool continues = bounces < settings.max_depth;
        const bool find_emission = counted && paths.emission && (bsdf.is_delta() || bsdf_emission);
        if (!continues && !find_emission) break;
        rng.seek(x.depth, SampleSlot::bsdf);  // the sampler's dimensions of this decision (core/sampler.h)
        BSDFSample bs = bsdf.sample_f(wo, rng.next_2d());
        if (!bs.valid() || bs.f.is_black()) break;
        Color weight = bs.f * (std::fabs(bs.wi.z) / bs.pdf);
        if (paths.refraction) eta_scale *= bs.eta * bs.eta;

        // 3. Russian roulette, after rr_depth bounces: survive with q, weigh by 1 / q.
        if (settings.russian_roulette && bounces > settings.rr_depth) {
            double q = std::min(kMaxSurvivalProbability,
                                (throughput * beta * weight).max_component() * eta_scale);
            rng.seek(x.depth, SampleSlot::roulette);
            if (rng.next_1d() >= q) break;
            weight /= q;
        }
        beta *= weight;

        const Vec3 wi = bsdf.to_world(bs.wi);
        Ray next = x.spawn_ray(wi);
        std::optional<SurfaceInteraction> hit = context.intersect(next);
        if (find_emission) {
            Color Le = hit ? direct.zero_bounce_radiance(context, next, *hit)
                           : context.lights.environment_radiance(wi);
            if (!Le.is_black()) {
                // After a delta bounce no light sample could have found this
                // path: weight 1. Else MIS against light sampling, or 1.
                double w = 1.0;
                if (mis && !bs.is_delta)
                    w = bsdf_sample_mis_weight(context, light_sample_context(x, bsdf), wi, hit, bs.pdf, 1);
                L += beta * Le * w;
            }
        }
        if (!hit || !continues) break;
        r = next;
        x = *hit;
    }
    return L;
}

Color est_radiance_global_illumination(const RenderContext& context, const Ray& ray, Rng& rng) {
    const RenderSettings& settings = context.settings;
    const bool zero_bounce = settings.accumulate_bounces || settings.max_depth == 0;
    std::optional<SurfaceInteraction> isect = context.intersect(ray);
    if (!isect) return zero_bounce ? context.lights.environment_radiance(ray.d) : Color(0);
    Color L;
    if (zero_bounce) L += context.stages.direct.zero_bounce_radiance(context, ray, *isect);
    // Through the table, so that a grader can pair this function with a
    // student's at_least_one_bounce_radiance (and the other way round).
    if (settings.max_depth >= 1)
        L += context.stages.global.at_least_one_bounce_radiance(context, ray, *isect, Color(1.0),
                                                                rng);
    return L;
}

}  // namespace pt::reference
