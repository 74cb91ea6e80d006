// Tiny in-process renders for the analytic tests: a scene from JSON text,
// rendered through the library (not the CLI) with the reference stages, and
// the mean of its pixels with a standard error.
//
// Every pixel has its own random stream (core/rng.h), so pixel values are
// independent samples of the estimator; when every pixel sees the same
// expected radiance (the tests aim a very narrow camera at one point, or
// look at a surface of constant radiance), the pixel mean m and the
// standard error s / sqrt(P) (s the sample standard deviation over the P
// pixels, each the average of spp samples) give the z-score
// (m - closed form) / SE. The tests accept |z| <= 4: a correct estimator
// fails with probability 6.3e-5 per check (normal tail), and the fixed
// seeds make every run the same.
#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "stages/effects.h"
#include "scene/scene_loader.h"
#include "stages/stages.h"

namespace pt::analytic {

struct PixelStats {
    double mean = 0;
    double standard_error = 0;  ///< of the mean
    double min = 0, max = 0;
    int count = 0;

    double z(double expected) const {
        return standard_error > 0 ? (mean - expected) / standard_error
                                  : (mean == expected ? 0.0 : kInfinity);
    }
};

/// Statistics of channel `c` over the pixels where `use(x, y)` is true.
inline PixelStats channel_stats(
    const Image& image, int c,
    const std::function<bool(int, int)>& use = [](int, int) { return true; }) {
    double sum = 0, sum2 = 0;
    PixelStats s;
    s.min = kInfinity, s.max = -kInfinity;
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            if (!use(x, y)) continue;
            double v = image.at(x, y)[c];
            sum += v, sum2 += v * v;
            s.min = std::min(s.min, v), s.max = std::max(s.max, v);
            ++s.count;
        }
    }
    s.mean = sum / s.count;
    double variance = std::max(0.0, (sum2 - s.count * s.mean * s.mean) / (s.count - 1));
    s.standard_error = std::sqrt(variance / s.count);
    return s;
}

/// Renders `scene` with `settings` on one thread with the reference stages
/// and the integrator that --integrator auto picks.
inline RenderResult render_scene(const Scene& scene, const RenderSettings& settings,
                                 StageSet student = StageSet::none()) {
    Stages stages = make_stages(student);
    std::unique_ptr<Integrator> integrator = make_integrator(
        choose_integrator(scene, analyze_effects(scene, settings), settings, nullptr));
    std::unique_ptr<Accelerator> accelerator =
        build_accelerator(scene, stages, AcceleratorSettings{});
    RenderContext context{scene, *accelerator, stages, settings, *integrator};
    RenderOptions options;
    options.threads = 1;
    return render_image(context, options);
}

inline RenderResult render_json(const std::string& json, const RenderSettings& settings) {
    return render_scene(parse_json_scene(json, "analytic.json"), settings);
}

inline RenderSettings settings_for(DirectStrategy strategy, int spp, int light_samples,
                                   uint64_t seed = 1) {
    RenderSettings s;
    s.direct = strategy;
    s.spp = spp;
    s.light_samples = light_samples;
    s.max_depth = 1;
    s.seed = seed;
    return s;
}

}  // namespace pt::analytic
