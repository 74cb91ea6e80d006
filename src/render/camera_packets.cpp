#include "render/camera_packets.h"

#include <algorithm>

#include "scene/camera.h"
#include "stages/accelerator.h"
#include "stages/camera.h"

namespace pt {

bool camera_packets_apply(const RenderContext& context) {
    return context.stages.camera.raytrace_pixel == &reference::raytrace_pixel &&
           context.stages.camera.generate_ray != &student::generate_ray && context.accelerator.shares_packet_traversal();
}

void trace_camera_packets(const RenderContext& context, int x0, int y, int count, TracedCameraRays* lists) {
    const RenderSettings& settings = context.settings;
    // raytrace_pixel's samples: spp, or half as many with the adaptive
    // `split` rule (each sample has a decision sample of its own stream);
    // with adaptive sampling, the first batch (later ones may not happen).
    int samples = settings.spp;
    if (settings.adaptive) {
        if (settings.adaptive_rule == AdaptiveRule::split) samples = (samples + 1) / 2;
        samples = std::min(samples, settings.samples_per_batch);
    }
    samples = std::min(samples, kPacketSamples);
    // Pixel by pixel first: a sampler's per-pixel cache (zsobol's, core/
    // sampler.cpp) is filled once per pixel, not once per ray as it would
    // be going across the strip for each sample.
    for (int i = 0; i < count; ++i) {
        lists[i].clear();
        for (int s = 0; s < samples; ++s) {
            Rng rng = context.sample_generator(x0 + i, y, s);
            lists[i].rays.push_back(reference::sample_camera_ray(context, x0 + i, y, s, rng));
            lists[i].generators.push_back(rng);
        }
        lists[i].hits.resize(lists[i].rays.size());
    }
    // Then one packet per sample index, of the strip's rays that will be
    // traced (a ray that sees nothing never is: RenderContext::radiance).
    Ray rays[kPacketPixels];
    std::optional<Hit> hits[kPacketPixels];
    int pixel_of[kPacketPixels];
    for (int s = 0; s < samples; ++s) {
        int n = 0;
        for (int i = 0; i < count; ++i) {
            if (sees_nothing(lists[i].rays[size_t(s)])) continue;
            pixel_of[n] = i;
            rays[n++] = lists[i].rays[size_t(s)];
        }
        context.accelerator.intersect_packet(rays, n, hits);
        for (int k = 0; k < n; ++k) lists[pixel_of[k]].hits[size_t(s)] = hits[k];
    }
}

}  // namespace pt
