// The direct integrator: emission seen directly plus direct illumination at
// the first hit (paths of at most one bounce), through the direct stage:
//   -m 0        zero_bounce_radiance (emission only)
//   -m 1 (>= 1) zero_bounce_radiance + one_bounce_radiance
//   -o 0        only the m-th bounce: -m 1 -o 0 is direct light without emission
// Rays that leave the scene see the environment (zero bounces).
#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/student_probe.h"

namespace pt {
namespace {

class DirectIntegrator final : public Integrator {
  public:
    Color Li(const RenderContext& context, const Ray& ray, Rng& rng) const override {
        const RenderSettings& settings = context.settings;
        const bool want_zero = settings.accumulate_bounces || settings.max_depth == 0;
        const bool want_one =
            settings.max_depth >= 1 && (settings.accumulate_bounces || settings.max_depth == 1);
        std::optional<SurfaceInteraction> isect = context.intersect(ray);
        if (!isect) return want_zero ? context.lights.environment_radiance(ray.d) : Color(0);
        probe_.run_once(context, ray, *isect, context.stages.is_student(Stage::direct), false);
        const DirectStage& stage = context.stages.direct;
        Color L;
        if (want_zero) L += stage.zero_bounce_radiance(context, ray, *isect);
        if (want_one) L += stage.one_bounce_radiance(context, ray, *isect, rng);
        return L;
    }
    IntegratorKind kind() const override { return IntegratorKind::direct; }

  private:
    StudentProbe probe_;
};

}  // namespace

std::unique_ptr<Integrator> make_direct_integrator() {
    return std::make_unique<DirectIntegrator>();
}

}  // namespace pt
