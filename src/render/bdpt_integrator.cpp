// The bidirectional path tracer (--integrator bdpt): for each camera ray,
// one camera subpath and one light subpath (stages/bdpt.h), every strategy
// (s, t) of each path length joined and weighted by MIS. Strategies with
// t >= 2 add to the camera ray's radiance; light tracing (t = 1) splats
// onto the thread's SplatFilm (render/splat_film.h), merged exactly, so the
// image is the same at any -t.
//
// Random numbers: the subpaths draw from a PCG32 stream of their own,
// seeded from the camera sample's generator, so a sampler (--sampler)
// places the camera ray and BDPT's dimensions stay independent.
//
// Strategy images (--bdpt-strategies, render/bdpt_strategies.h): each
// (s, t) of up to settings.bdpt_strategy_depth bounces also splats its
// weighted and its unweighted contribution onto a layer of its own, at the
// pixel the strategy's path lands on.
#include <stdexcept>

#include "core/counters.h"
#include "core/error.h"
#include "render/bdpt_strategies.h"
#include "render/integrators.h"
#include "render/splat_film.h"
#include "scene/camera_importance.h"
#include "stages/bdpt.h"
#include "stages/render_context.h"

namespace pt {
namespace {

class BdptIntegrator final : public Integrator {
  public:
    Color Li(const RenderContext& context, const Ray& ray, Rng& rng) const override {
        const BdptStage& stage = context.stages.bdpt;
        const RenderSettings& settings = context.settings;
        SplatFilm* film = current_splat_film();
        if (film) film->count_path();
        Rng walk((uint64_t(rng.next_u32()) << 32) | rng.next_u32());
        const std::vector<PathVertex> camera = camera_subpath(context, stage, ray, walk);
        const std::vector<PathVertex> light = light_subpath(context, stage, walk);

        const int strategy_depth = film && film->layers() > 1 ? settings.bdpt_strategy_depth : -1;
        Vec2 ray_film;
        if (strategy_depth >= 0) {
            std::optional<Vec2> f = camera_film_position(context.scene.camera, ray.o, ray.d);
            ray_film = f.value_or(Vec2(-1, -1));
        }
        const int m = settings.max_depth;
        Color L;
        for (int t = 1; t <= int(camera.size()); ++t) {
            for (int s = 0; s <= int(light.size()); ++s) {
                const int depth = s + t - 2;
                if (depth < 0 || depth > m || (s == 1 && t == 1)) continue;
                if (!settings.accumulate_bounces && depth != m) continue;
                if (t == 1 && !film) continue;  // light tracing needs a film to splat on
                Connection c = stage.connect(context, light, s, camera, t, walk);
                if (c.L.is_black()) continue;
                const double w = strategy_weight(context, stage, light, s, camera, t, c);
                const Color value = c.L * w;
                if (!value.is_finite()) {
                    ++thread_counters().nonfinite_samples;
                    continue;
                }
                if (t == 1)
                    film->add(0, c.film, value);
                else
                    L += value;
                if (depth <= strategy_depth) {
                    const int layer = strategy_layer(s, t);
                    const Vec2 at = t == 1 ? c.film : ray_film;
                    film->add(layer, at, value);
                    film->add(layer + 1, at, c.L);
                }
            }
        }
        return L;
    }
    IntegratorKind kind() const override { return IntegratorKind::bdpt; }
    int splat_layers(const RenderContext& context) const override {
        return 1 + strategy_layer_count(context.settings.bdpt_strategy_depth);
    }
    void prepare(const RenderContext& context, int) const override {
        const std::string missing = camera_importance_missing(context.scene.camera);
        if (!missing.empty()) throw InputError("--integrator bdpt: " + missing);
    }
};

}  // namespace

std::unique_ptr<Integrator> make_bdpt_integrator() {
    return std::make_unique<BdptIntegrator>();
}

}  // namespace pt
