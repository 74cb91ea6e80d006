// Timing whole renders for the bench tables: with the BVH (fast, so
// repeated and the best time kept) and without it (slow, so measured on a
// random sample of pixels when the whole image would exceed a time budget).
#pragma once

#include <cstdint>

#include "core/counters.h"

namespace pt {
struct RenderContext;
}

namespace pt::bench {

struct RenderTiming {
    double seconds = 0;      ///< the render's wall-clock time (or its estimate)
    bool estimated = false;  ///< true: extrapolated from a sample of pixels
    double half_width = 0;   ///< estimate: half-width of its 95% confidence interval, seconds
    uint64_t pixels = 0;     ///< pixels actually rendered for the figure
    RayCounters counters;    ///< the work of one whole render (estimate: of the sample)
};

/// Renders the whole image with `threads` threads, again and again until
/// `min_seconds` have passed (at least once); keeps the fastest render.
RenderTiming time_render(const RenderContext& context, int threads, double min_seconds);

/// Renders the pixels one by one on this thread, in random order, until all
/// are done or `budget_seconds` have passed. In the second case the time of
/// the whole image is N times the mean time per pixel, with the 95%
/// confidence interval of that mean (normal approximation, finite
/// population correction: the pixels are drawn without replacement).
RenderTiming time_render_sampled(const RenderContext& context, double budget_seconds,
                                 uint64_t seed);

}  // namespace pt::bench
