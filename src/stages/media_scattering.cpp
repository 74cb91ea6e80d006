// Reference in_scattered_radiance of stage `media` (stages/media.h): light
// sampling at a point in a medium, Part 9's single scattering.
#include <memory>

#include "stages/media.h"
#include "stages/medium_tracking.h"
#include "stages/render_context.h"

namespace pt::reference {

Color in_scattered_radiance(const RenderContext& context, const Vec3& p, const Vec3& wo, int medium, Rng& rng) {
    const MediaStage& stage = context.stages.media;
    const double g = context.scene.media[size_t(medium)].g;
    const LightSampleContext ref{p, Vec3(0, 0, 0)};  // no surface: light from every side
    Color L;
    for (const std::unique_ptr<Light>& light : context.lights.all()) {
        const int n = light->sample_count(context.settings.light_samples);
        Color sum;
        for (int i = 0; i < n; ++i) {
            LightSample s = light->sample_Li(ref, rng.next_2d());
            if (!s.valid() || s.L.is_black()) continue;
            // cos theta between the light's direction of travel, -wi, and wo.
            const double phase = stage.hg_phase(-dot(wo, s.wi), g);
            const Color T = shadow_transmittance(context, Ray(p, s.p - p, kSpawnTMin, 1.0 - kShadowEpsilon), medium, rng);
            sum += s.L * T * (phase / s.pdf);
        }
        L += sum / double(n);
    }
    return L;
}

}  // namespace pt::reference
