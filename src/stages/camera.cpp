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

namespace {

constexpr uint64_t kDecisionStream = 0x73746F70ull;  // "stop": the split rule's own samples

/// The camera ray through (x + jitter.x, y + jitter.y).
Ray camera_ray(const RenderContext& context, int x, int y, Vec2 jitter, Vec2 lens) {
    const Scene& scene = context.scene;
    double u = (x + jitter.x) / scene.film_width;
    double v = 1.0 - (y + jitter.y) / scene.film_height;  // image rows run top to bottom
    return context.stages.camera.generate_ray(scene.camera, u, v, lens);
}

/// The radiance along `ray`; a sample that is not finite is counted and
/// dropped (--stats reports it).
Color sample_radiance(const RenderContext& context, const Ray& ray, Rng& rng) {
    Color L = context.radiance(ray, rng);
    if (!L.is_finite()) {
        ++thread_counters().nonfinite_samples;
        L = Color(0);
    }
    return L;
}

}  // namespace

Ray sample_camera_ray(const RenderContext& context, int x, int y, int index, Rng& rng) {
    // The dimensions: 0-1 the point in the pixel (its centre when spp is 1,
    // as CS184), 2-3 the lens (a pinhole skips them; without a sampler the
    // lens has a stream of its own, so a pinhole leaves every other number
    // of the sample where it was), the bounces from 4 on.
    const RenderSettings& settings = context.settings;
    const uint64_t pixel = uint64_t(y) * uint64_t(context.scene.film_width) + uint64_t(x);
    Vec2 jitter = settings.spp == 1 ? Vec2(0.5, 0.5) : rng.next_2d();
    rng.seek_dimension(2);
    Vec2 lens(0.5, 0.5);
    if (context.code_paths.lens_sampling)
        lens = rng.sampler() ? rng.next_2d() : Rng::lens(settings.seed, pixel, uint64_t(index)).next_2d();
    rng.seek_dimension(4);
    return camera_ray(context, x, y, jitter, lens);
}

PixelResult raytrace_pixel(const RenderContext& context, int x, int y) {
    const RenderSettings& settings = context.settings;
    const uint64_t pixel = uint64_t(y) * uint64_t(context.scene.film_width) + uint64_t(x);
    const bool lens_sampling = context.code_paths.lens_sampling;
    // Adaptive sampling's `split` rule (Kirk and Arvo 1991, "Unbiased
    // sampling techniques for image synthesis"): the stopping rule sees only
    // samples of a stream of their own, which the estimate never averages,
    // so when a pixel stops says nothing about the values it averages, and
    // the estimate stays unbiased. CS184's rule tests the averaged samples.
    const bool split = settings.adaptive && settings.adaptive_rule == AdaptiveRule::split;
    Color sum;
    int averaged = 0;       // samples in the estimate
    int n = 0;              // camera rays traced
    PixelStatistics stats;  // of the samples' illuminance that the stopping rule sees
    auto observe = [&stats](const Color& L) {
        double illuminance = L.luminance();
        stats.s1 += illuminance;
        stats.s2 += illuminance * illuminance;
        ++stats.n;
    };
    const TracedCameraRays* traced = traced_camera_rays();
    for (int i = 0; n < settings.spp; ++i) {
        // Sample i: its own generator (core/rng.h), so the image does not
        // depend on the thread count or on the order of the pixels (its
        // dimensions: sample_camera_ray).
        // With --packets on the renderer drew the first samples' rays
        // already (and traced them: render/camera_packets.h).
        Rng rng;
        Ray ray;
        if (traced && size_t(i) < traced->rays.size()) {
            rng = traced->generators[size_t(i)];
            ray = traced->rays[size_t(i)];
        } else {
            rng = context.sample_generator(x, y, i);
            ray = sample_camera_ray(context, x, y, i, rng);
        }
        Color L = sample_radiance(context, ray, rng);
        sum += L;
        ++averaged;
        ++n;
        if (!split) {
            observe(L);
        } else if (n < settings.spp) {
            Rng decision = Rng::substream(settings.seed, pixel, uint64_t(i), kDecisionStream);
            Vec2 decision_jitter = decision.next_2d();
            Vec2 decision_lens = lens_sampling ? decision.next_2d() : Vec2(0.5, 0.5);
            observe(sample_radiance(context, camera_ray(context, x, y, decision_jitter, decision_lens), decision));
            ++n;
        }
        // Adaptive sampling (Part 5): test for convergence after each batch.
        if (settings.adaptive && stats.n > 0 && stats.n % settings.samples_per_batch == 0 &&
            context.stages.adaptive.has_converged(stats, settings.max_tolerance))
            break;
    }
    return {sum / double(averaged), n};
}

}  // namespace pt::reference
