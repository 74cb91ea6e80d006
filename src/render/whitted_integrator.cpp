// The Whitted integrator (Whitted, "An Improved Illumination Model for
// Shaded Display", CACM 1980): at every hit, emission plus direct light from
// the lights with hard shadows at non-specular surfaces, and the mirror and
// refraction directions of mirrors and glass followed recursively. Glass
// splits deterministically into both lobes, each weighted by its Fresnel
// term (BSDF::delta_lobes); total internal reflection leaves one lobe.
//
// Its paths are camera, any number of specular bounces, at most one
// non-specular vertex, light (Heckbert's E S* D? L). With point and
// directional lights only, every term is computed exactly: the image has no
// Monte Carlo noise beyond anti-aliasing (-s). Area and environment lights
// are seen directly and in mirrors and glass, and they light diffuse
// surfaces through light sampling (-l), which is noisy; `--integrator auto`
// does not pick Whitted for them.
//
// Depth: -m counts non-specular bounces, as Whitted's model has at most
// one: -m 0 is emission, seen directly or through specular chains; -m >= 1
// adds direct light (-o 0 -m 1: direct light only). Specular chains are
// followed up to settings.whitted_max_specular (8) bounces. `auto` picks
// Whitted only with -m 1, where the path tracer would ask for no diffuse
// interreflection, so the difference to the path tracer's convention (in
// which a reflection in a mirror is one more bounce) shows only as the
// reflections Whitted adds: docs/global.md, "The Whitted integrator".
#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/student_probe.h"

namespace pt {
namespace {

class WhittedIntegrator final : public Integrator {
  public:
    Color Li(const RenderContext& context, const Ray& ray, Rng& rng) const override {
        return trace(context, ray, 0, rng);
    }
    IntegratorKind kind() const override { return IntegratorKind::whitted; }

  private:
    Color trace(const RenderContext& context, const Ray& ray, int specular_bounces,
                Rng& rng) const {
        const RenderSettings& settings = context.settings;
        const bool want_emission = settings.accumulate_bounces || settings.max_depth == 0;
        const bool want_direct =
            settings.max_depth >= 1 && (settings.accumulate_bounces || settings.max_depth == 1);
        std::optional<SurfaceInteraction> isect = context.intersect(ray);
        if (!isect) return want_emission ? context.lights.environment_radiance(ray.d) : Color(0);
        probe_.run_once(context, ray, *isect, context.stages.is_student(Stage::direct), false);

        const DirectStage& direct = context.stages.direct;
        Color L;
        if (want_emission) L += direct.zero_bounce_radiance(context, ray, *isect);
        BSDF bsdf = context.bsdf_at(*isect);
        if (!bsdf.is_delta()) {
            if (want_direct && context.code_paths.light_sampling)
                L += direct.one_bounce_radiance(context, ray, *isect, rng);
            return L;
        }
        if (specular_bounces >= settings.whitted_max_specular) return L;
        DeltaLobe lobes[2];
        int n = bsdf.delta_lobes(bsdf.to_local(isect->wo), lobes);
        for (int i = 0; i < n; ++i) {
            if (lobes[i].weight.is_black()) continue;
            Ray next = isect->spawn_ray(bsdf.to_world(lobes[i].wi));
            L += lobes[i].weight * trace(context, next, specular_bounces + 1, rng);
        }
        return L;
    }

    StudentProbe probe_;
};

}  // namespace

std::unique_ptr<Integrator> make_whitted_integrator() {
    return std::make_unique<WhittedIntegrator>();
}

}  // namespace pt
