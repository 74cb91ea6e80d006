// Reference implementation of stage `camera`. See stages/camera.h.
#include "stages/camera.h"

#include "core/counters.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "stages/render_context.h"

namespace pt::reference {

Ray generate_ray(const Camera& camera, double x, double y, Vec2 lens_sample) {
    // The point on the sensor plane z = -1, in camera space.
    Vec3 sensor((2.0 * x - 1.0) * camera.tan_half_hfov, (2.0 * y - 1.0) * camera.tan_half_vfov, -1.0);
    if (camera.lens_radius <= 0) {
        Vec3 d = camera.to_world(sensor).unit();
        return Ray(camera.position, d, camera.near_clip, camera.far_clip);
    }
    // Thin lens: every ray through the lens that aims at the point where the
    // pinhole ray meets the plane of focus (z = -focal_distance) converges there.
    Vec2 disk = sample_concentric_disk(lens_sample);
    Vec3 lens(camera.lens_radius * disk.x, camera.lens_radius * disk.y, 0.0);
    Vec3 focus = sensor * camera.focal_distance;
    Vec3 d = camera.to_world(focus - lens).unit();
    return Ray(camera.position + camera.to_world(lens), d, camera.near_clip, camera.far_clip);
}

PixelResult raytrace_pixel(const RenderContext& context, int x, int y) {
    const RenderSettings& settings = context.settings;
    const Scene& scene = context.scene;
    const uint64_t pixel = uint64_t(y) * uint64_t(scene.film_width) + uint64_t(x);
    Color sum;
    PixelStatistics stats;  // of the samples' illuminance, for adaptive sampling
    int n = 0;
    for (int i = 0; i < settings.spp; ++i) {
        // One generator per (seed, pixel, sample): the image does not depend
        // on the thread count or on the order in which pixels are rendered.
        Rng rng(settings.seed, pixel, uint64_t(i));
        Vec2 jitter = settings.spp == 1 ? Vec2(0.5, 0.5) : rng.next_2d();
        // A pinhole needs no lens sample (DESIGN.md "Effects"); a thin lens
        // draws it from a stream of its own, so the rest of the sample's
        // random numbers are the same either way.
        Vec2 lens(0.5, 0.5);
        if (context.code_paths.lens_sampling) lens = Rng::lens(settings.seed, pixel, uint64_t(i)).next_2d();
        double u = (x + jitter.x) / scene.film_width;
        double v = 1.0 - (y + jitter.y) / scene.film_height;  // image rows run top to bottom
        Ray ray = context.stages.camera.generate_ray(scene.camera, u, v, lens);
        Color L = context.radiance(ray, rng);
        if (!L.is_finite()) {
            // Counted and dropped, never averaged in: --stats reports the count.
            ++thread_counters().nonfinite_samples;
            L = Color(0);
        }
        sum += L;
        ++n;
        double illuminance = L.luminance();
        stats.s1 += illuminance;
        stats.s2 += illuminance * illuminance;
        stats.n = n;
        // Adaptive sampling (Part 5): test for convergence after each batch.
        if (settings.adaptive && n % settings.samples_per_batch == 0 &&
            context.stages.adaptive.has_converged(stats, settings.max_tolerance))
            break;
    }
    return {sum / double(n), n};
}

}  // namespace pt::reference
