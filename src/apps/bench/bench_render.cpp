#include "apps/bench/bench_render.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/rng.h"
#include "core/timer.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "stages/camera.h"

namespace pt::bench {

RenderTiming time_render(const RenderContext& context, int threads, double min_seconds) {
    RenderOptions options;
    options.threads = threads;
    RenderTiming best;
    best.seconds = INFINITY;
    Timer total;
    do {
        RenderResult result = render_image(context, options);
        if (result.seconds < best.seconds) {
            best.seconds = result.seconds;
            best.counters = result.counters;
        }
    } while (total.seconds() < min_seconds);
    best.pixels = uint64_t(context.scene.film_width) * context.scene.film_height;
    return best;
}

RenderTiming time_render_sampled(const RenderContext& context, double budget_seconds,
                                 uint64_t seed) {
    const int width = context.scene.film_width;
    const uint64_t total_pixels = uint64_t(width) * context.scene.film_height;
    // A random order of all pixels (Fisher-Yates), so any prefix is a
    // uniform sample without replacement.
    std::vector<uint32_t> order(total_pixels);
    std::iota(order.begin(), order.end(), 0u);
    Rng rng(seed);
    for (uint32_t i = uint32_t(total_pixels) - 1; i > 0; --i)
        std::swap(order[i], order[rng.next_index(i + 1)]);

    RayCounters& counters = thread_counters();
    RayCounters before = counters;
    double sum = 0, sum_squares = 0;
    uint64_t n = 0;
    Timer budget;
    for (uint32_t pixel : order) {
        Timer timer;
        PixelResult result =
            context.stages.camera.raytrace_pixel(context, int(pixel % width), int(pixel / width));
        double dt = timer.seconds();
        counters.camera_rays += uint64_t(std::max(result.samples, 0));
        sum += dt;
        sum_squares += dt * dt;
        ++n;
        if (n >= 16 && budget.seconds() >= budget_seconds) break;  // at least 16 for a variance
    }
    RenderTiming timing;
    timing.counters = counters - before;
    timing.pixels = n;
    if (n == total_pixels) {
        timing.seconds = sum;
        return timing;
    }
    double N = double(total_pixels), mean = sum / double(n);
    double variance = std::max(0.0, (sum_squares - double(n) * mean * mean) / double(n - 1));
    double fpc = std::sqrt(1.0 - double(n) / N);
    timing.estimated = true;
    timing.seconds = N * mean;
    timing.half_width = 1.96 * N * std::sqrt(variance / double(n)) * fpc;
    return timing;
}

}  // namespace pt::bench
