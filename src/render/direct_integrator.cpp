// The direct integrator: emission seen directly plus direct illumination at
// the first hit (paths of at most one bounce), through the direct stage:
//   -m 0        zero_bounce_radiance (emission only)
//   -m 1 (>= 1) zero_bounce_radiance + one_bounce_radiance
//   -o 0        only the m-th bounce: -m 1 -o 0 is direct light without emission
// Rays that leave the scene see the environment (zero bounces).
#include <mutex>

#include "render/integrator.h"
#include "render/render_context.h"

namespace pt {
namespace {

/// Calls, in task order, every student function of the direct stage that
/// this render will use, once, so that the first one still missing is the
/// one reported ("Part 3, task 1: diffuse_f is not implemented yet"), not
/// whichever the renderer happens to reach first. The values are discarded.
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

class DirectIntegrator final : public Integrator {
  public:
    Color Li(const RenderContext& context, const Ray& ray, Rng& rng) const override {
        const RenderSettings& settings = context.settings;
        const bool want_zero = settings.accumulate_bounces || settings.max_depth == 0;
        const bool want_one =
            settings.max_depth >= 1 && (settings.accumulate_bounces || settings.max_depth == 1);
        std::optional<SurfaceInteraction> isect = context.intersect(ray);
        if (!isect) return want_zero ? context.lights.environment_radiance(ray.d) : Color(0);
        if (context.stages.is_student(Stage::direct)) {
            // Once per render; a throwing probe leaves the flag unset, and
            // the renderer stops at the first exception anyway.
            std::call_once(probed_, probe_student_direct_stage, context, ray, *isect);
        }
        const DirectStage& stage = context.stages.direct;
        Color L;
        if (want_zero) L += stage.zero_bounce_radiance(context, ray, *isect);
        if (want_one) L += stage.one_bounce_radiance(context, ray, *isect, rng);
        return L;
    }
    IntegratorKind kind() const override { return IntegratorKind::direct; }

  private:
    mutable std::once_flag probed_;
};

}  // namespace

std::unique_ptr<Integrator> make_direct_integrator() {
    return std::make_unique<DirectIntegrator>();
}

}  // namespace pt
