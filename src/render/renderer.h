// The tile renderer: splits the image (or the -p cell) into 16x16 tiles
// that worker threads take from a shared counter, and calls the camera
// stage's raytrace_pixel for every pixel. Per-pixel random streams make the
// result independent of the thread count (core/rng.h).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/counters.h"
#include "image/image.h"

namespace pt {

struct RenderContext;

/// A rectangle of pixels: x in [x, x + width), y in [y, y + height), y = 0 at the top.
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

struct RenderOptions {
    int threads = 1;                  ///< worker threads (-t)
    bool show_progress = false;       ///< progress bar on stderr
    std::optional<PixelRect> cell;    ///< -p: render only these pixels (others stay black)
    double time_limit = 0;            ///< seconds; > 0: stop starting pixels after this long (bench's budget)
    /// --packets on: camera rays traced in packets where camera_packets_apply
    /// says they can be (render/camera_packets.h); the same image either way.
    bool packets = false;
};

struct RenderResult {
    Image image;                         ///< full film size, linear radiance
    std::vector<uint32_t> sample_counts;  ///< camera rays per pixel, row-major (0 outside the cell)
    RayCounters counters;                ///< summed over all threads
    double seconds = 0;                  ///< wall-clock time of the render
    bool complete = true;                ///< false: stopped by options.time_limit, some pixels black
    /// The integrator's extra splat images (Integrator::splat_layers beyond
    /// layer 0, which is in `image`), normalised; empty for most integrators.
    std::vector<Image> layers;
};

/// Renders every pixel of the film (or of options.cell). A stage that throws
/// (e.g. NotImplemented) stops all threads; the first exception is rethrown.
/// With options.time_limit, the threads stop once that many seconds have
/// passed (checked before each pixel) and result.complete is false.
RenderResult render_image(const RenderContext& context, const RenderOptions& options);

}  // namespace pt
