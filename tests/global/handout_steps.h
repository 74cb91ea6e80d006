// Part 4 as a student writes it from the TODO steps of
// assignments/part4/global.cpp (recursive), with a switch for each classic
// bug. With Bug::none and CameraBug::none it is a correct solution:
// global/test_student_switch.cpp checks it renders the reference's image,
// and the grader's fixtures (grading/fixtures/part4_fixtures.cpp) install
// the buggy ones.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "stages/render_context.h"
#include "stages/global.h"

namespace pt::handout_steps {

enum class Bug {
    none,
    always_accumulates,  ///< -o ignored: every bounce counted, also with -o 0
    depth_is_bounces,    ///< bounces = isect.depth (the +1 forgotten): one bounce too many
    cap_before_direct,   ///< stops at the m-th vertex before its direct light: one too few
    roulette_without_q,  ///< survives with q but does not divide by it: too dark
    weight_without_cos,  ///< weight = f / pdf: |cos theta_i| forgotten
    weight_without_pdf,  ///< weight = f |cos theta_i|: the division by the pdf forgotten
    delta_light_skipped,     ///< step 6 left out: nothing seen through a mirror or glass
    delta_light_uncounted,   ///< step 6 without "counted": light after a delta bounce with -o 0 too
};

template <Bug bug>
Color bounce(const RenderContext& context, const Ray& ray, const SurfaceInteraction& isect,
             const Color& throughput, Rng& rng) {
    const RenderSettings& settings = context.settings;
    BSDF bsdf = context.bsdf_at(isect);
    const Vec3 wo = bsdf.to_local(isect.wo);
    const int bounces = bug == Bug::depth_is_bounces ? isect.depth : isect.depth + 1;
    const int m = settings.max_depth;
    const bool counted =
        bug == Bug::always_accumulates || settings.accumulate_bounces || bounces == m;
    if (bug == Bug::cap_before_direct && bounces == m) return Color(0);
    Color L;
    if (counted && !bsdf.is_delta())
        L = context.stages.direct.one_bounce_radiance(context, ray, isect, rng);
    if (bounces == m && !(bsdf.is_delta() && counted)) return L;
    BSDFSample bs = bsdf.sample_f(wo, rng.next_2d());
    if (!bs.valid() || bs.f.is_black()) return L;
    Color weight = bs.f;
    if (bug != Bug::weight_without_cos) weight *= std::fabs(bs.wi.z);
    if (bug != Bug::weight_without_pdf) weight /= bs.pdf;
    if (settings.russian_roulette && bounces > settings.rr_depth) {
        const double q = std::min(kMaxSurvivalProbability, (throughput * weight).max_component());
        if (rng.next_1d() >= q) return L;
        if (bug != Bug::roulette_without_q) weight /= q;
    }
    Ray next = isect.spawn_ray(bsdf.to_world(bs.wi));
    std::optional<SurfaceInteraction> hit = context.intersect(next);
    const bool step6 = bug == Bug::delta_light_uncounted ? bs.is_delta
                       : bug == Bug::delta_light_skipped ? false
                                                          : bs.is_delta && counted;
    if (step6)
        L += weight * (hit ? context.stages.direct.zero_bounce_radiance(context, next, *hit)
                           : context.lights.environment_radiance(next.d));
    if (hit && bounces < m)
        L += weight * bounce<bug>(context, next, *hit, throughput * weight, rng);
    return L;
}

enum class CameraBug {
    none,
    emission_always,      ///< zero-bounce light added whatever -o
    emission_only_at_m0,  ///< zero-bounce light only with -m 0: lost with -o 1
    sky_forgotten,        ///< a camera ray that misses is black, also with -o 1
    sky_always,           ///< a camera ray that misses sees the sky, also with -o 0
    zero_without_m0,      ///< zero-bounce light only with -o 1: -m 0 -o 0 is black
};

template <CameraBug bug>
Color camera_ray(const RenderContext& context, const Ray& ray, Rng& rng) {
    const RenderSettings& settings = context.settings;
    bool zero = settings.accumulate_bounces || settings.max_depth == 0;
    if (bug == CameraBug::emission_always) zero = true;
    if (bug == CameraBug::emission_only_at_m0) zero = settings.max_depth == 0;
    if (bug == CameraBug::zero_without_m0) zero = settings.accumulate_bounces;
    std::optional<SurfaceInteraction> isect = context.intersect(ray);
    if (!isect) {
        if (bug == CameraBug::sky_forgotten) return Color(0);
        if (bug == CameraBug::sky_always) return context.lights.environment_radiance(ray.d);
        return zero ? context.lights.environment_radiance(ray.d) : Color(0);
    }
    Color L;
    if (zero) L += context.stages.direct.zero_bounce_radiance(context, ray, *isect);
    if (settings.max_depth >= 1)
        L += context.stages.global.at_least_one_bounce_radiance(context, ray, *isect, Color(1.0),
                                                                rng);
    return L;
}

}  // namespace pt::handout_steps
