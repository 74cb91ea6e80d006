// The path integrator: global illumination through the global stage
// (stages/global.h), so that `--student global` runs the student's path
// tracer: est_radiance_global_illumination per camera ray.
#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/student_probe.h"

namespace pt {
namespace {

class PathIntegrator final : public Integrator {
  public:
    Color Li(const RenderContext& context, const Ray& ray, Rng& rng) const override {
        const Stages& stages = context.stages;
        const bool direct = stages.is_student(Stage::direct);
        const bool global = stages.is_student(Stage::global);
        if ((direct || global) && !probe_.done()) {
            // The probes need a hit; a camera ray that misses everything
            // uses no student function but est_radiance itself.
            std::optional<SurfaceInteraction> isect = context.intersect(ray);
            if (isect) probe_.run_once(context, ray, *isect, direct, global);
        }
        return stages.global.est_radiance_global_illumination(context, ray, rng);
    }
    IntegratorKind kind() const override { return IntegratorKind::path; }

  private:
    StudentProbe probe_;
};

}  // namespace

std::unique_ptr<Integrator> make_path_integrator() {
    return std::make_unique<PathIntegrator>();
}

}  // namespace pt
