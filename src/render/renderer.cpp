#include "render/renderer.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "core/progress.h"
#include "core/timer.h"
#include "render/camera_packets.h"
#include "render/splat_film.h"
#include "render/sppm.h"
#include "stages/integrator.h"
#include "stages/render_context.h"

namespace pt {

RenderResult render_image(const RenderContext& context, const RenderOptions& options) {
    // SPPM is a loop of whole-image passes, not a function per camera ray.
    if (context.integrator.kind() == IntegratorKind::sppm) return render_sppm(context, options);
    Timer prepare_timer;
    context.integrator.prepare(context, std::max(1, options.threads));
    const double prepare_seconds = prepare_timer.seconds();
    const int width = context.scene.film_width, height = context.scene.film_height;
    PixelRect area = options.cell.value_or(PixelRect{0, 0, width, height});
    constexpr int kTile = 16;
    const int tiles_x = (area.width + kTile - 1) / kTile;
    const int tiles_y = (area.height + kTile - 1) / kTile;
    const int tile_count = tiles_x * tiles_y;

    RenderResult result;
    result.image = Image(width, height);
    result.sample_counts.assign(size_t(width) * height, 0);
    Progress progress("render", uint64_t(area.width) * area.height, options.show_progress);

    // Splats (BDPT's light tracing): a film per thread, summed exactly.
    const int splat_layers = context.integrator.splat_layers(context);
    SplatFilm splats(splat_layers > 0 ? width : 0, splat_layers > 0 ? height : 0, splat_layers);

    const bool packets = options.packets && camera_packets_apply(context);
    std::atomic<int> next_tile{0};
    std::atomic<bool> abort{false};
    std::atomic<bool> out_of_time{false};
    std::exception_ptr failure;
    std::mutex merge_mutex;
    Timer timer;

    auto worker = [&] {
        RayCounters& counters = thread_counters();
        RayCounters before = counters;
        std::unique_ptr<SplatFilm> film;
        if (splat_layers > 0) film = std::make_unique<SplatFilm>(width, height, splat_layers);
        set_current_splat_film(film.get());
        TracedCameraRays traced[kPacketPixels];
        try {
            for (int tile = next_tile++; tile < tile_count && !abort; tile = next_tile++) {
                int x0 = area.x + (tile % tiles_x) * kTile, y0 = area.y + (tile / tiles_x) * kTile;
                int x1 = std::min(x0 + kTile, area.x + area.width), y1 = std::min(y0 + kTile, area.y + area.height);
                for (int y = y0; y < y1 && !abort; ++y) {
                    for (int x = x0; x < x1 && !abort; ++x) {
                        // A time-limited render (bench) gives up between pixels.
                        if (options.time_limit > 0 && timer.seconds() + prepare_seconds > options.time_limit) {
                            out_of_time = abort = true;
                            break;
                        }
                        if (packets && (x - x0) % kPacketPixels == 0)
                            trace_camera_packets(context, x, y, std::min(kPacketPixels, x1 - x), traced);
                        if (packets) set_traced_camera_rays(&traced[(x - x0) % kPacketPixels]);
                        PixelResult pixel = context.stages.camera.raytrace_pixel(context, x, y);
                        set_traced_camera_rays(nullptr);
                        // The last line of defence: whatever a stage returns, the
                        // film never stores NaN or Inf.
                        if (!pixel.radiance.is_finite()) {
                            ++counters.nonfinite_samples;
                            pixel.radiance = Color(0);
                        }
                        result.image.set(x, y, pixel.radiance);
                        result.sample_counts[size_t(y) * width + x] = uint32_t(std::max(pixel.samples, 0));
                        counters.camera_rays += uint64_t(std::max(pixel.samples, 0));
                    }
                }
                progress.advance(uint64_t(x1 - x0) * (y1 - y0));
            }
        } catch (...) {
            set_traced_camera_rays(nullptr);
            std::lock_guard<std::mutex> lock(merge_mutex);
            if (!failure) failure = std::current_exception();
            abort = true;
        }
        set_current_splat_film(nullptr);
        // Add only this render's share of the thread's counters.
        std::lock_guard<std::mutex> lock(merge_mutex);
        result.counters += counters - before;
        if (film) splats.merge(*film);
    };

    int threads = std::max(1, std::min(options.threads, tile_count));
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
    worker();  // the calling thread works too
    for (std::thread& t : pool) t.join();
    result.seconds = timer.seconds() + prepare_seconds;
    if (failure) std::rethrow_exception(failure);
    result.complete = !out_of_time;
    for (int layer = 0; layer < splat_layers; ++layer) {
        Image image(width, height);
        for (int y = area.y; y < area.y + area.height; ++y)
            for (int x = area.x; x < area.x + area.width; ++x) image.set(x, y, splats.value(layer, x, y));
        if (layer == 0) {
            for (int y = area.y; y < area.y + area.height; ++y)
                for (int x = area.x; x < area.x + area.width; ++x) {
                    Color c = result.image.at(x, y) + image.at(x, y);
                    if (!c.is_finite()) {
                        ++result.counters.nonfinite_samples;
                        c = Color(0);
                    }
                    result.image.set(x, y, c);
                }
        } else {
            result.layers.push_back(std::move(image));
        }
    }
    progress.finish();
    return result;
}

}  // namespace pt
