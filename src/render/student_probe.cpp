#include "render/student_probe.h"

#include "stages/render_context.h"

namespace pt {

void probe_student_direct_stage(const RenderContext& context, const Ray& ray,
                                const SurfaceInteraction& isect) {
    const DirectStage& stage = context.stages.direct;
    const RenderSettings& settings = context.settings;
    const bool one_bounce = settings.max_depth >= 1;
    Rng rng(settings.seed);
    if (one_bounce) {
        stage.diffuse_f(Color(0.5), Vec3(0, 0, 1), Vec3(0, 0, 1));
        stage.diffuse_sample_f(Color(0.5), Vec3(0, 0, 1), Vec2(0.5, 0.5));
    }
    stage.zero_bounce_radiance(context, ray, isect);
    if (!one_bounce) return;
    if (settings.direct == DirectStrategy::hemisphere)
        stage.estimate_direct_lighting_hemisphere(context, ray, isect, rng);
    if (settings.direct == DirectStrategy::light)
        stage.estimate_direct_lighting_importance(context, ray, isect, rng);
    stage.one_bounce_radiance(context, ray, isect, rng);
}

void probe_student_global_stage(const RenderContext& context, const Ray& ray,
                                const SurfaceInteraction& isect) {
    const GlobalStage& stage = context.stages.global;
    Rng rng(context.settings.seed);
    if (context.settings.max_depth >= 1 && isect.depth < context.settings.max_depth)
        stage.at_least_one_bounce_radiance(context, ray, isect, Color(1.0), rng);
    stage.est_radiance_global_illumination(context, ray, rng);
}

void StudentProbe::run_once(const RenderContext& context, const Ray& ray,
                            const SurfaceInteraction& isect, bool direct, bool global) const {
    if ((!direct && !global) || done()) return;
    // A throwing probe leaves the flag unset; the renderer stops at the
    // first exception anyway.
    std::call_once(once_, [&] {
        if (direct) probe_student_direct_stage(context, ray, isect);
        if (global) probe_student_global_stage(context, ray, isect);
        done_.store(true, std::memory_order_release);
    });
}

}  // namespace pt
