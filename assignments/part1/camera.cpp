// Part 1, tasks 1 and 2: camera rays and the pixel sampling loop.
// Read assignments/part1/README.md first; the contract of each function is
// in src/stages/camera.h.
#include "core/error.h"
#include "core/rng.h"
#include "stages/render_context.h"
#include "stages/camera.h"

namespace pt::student {

Ray generate_ray(const Camera& camera, double x, double y, Vec2 lens_sample) {
    // TODO(part1.1): generate_ray, as src/stages/camera.h states its contract.
    // [guided]
    // build the camera-space point on the sensor plane z = -1
    // from (x, y) and the half-angle tangents camera.tan_half_hfov and
    // camera.tan_half_vfov, rotate it to world space with camera.to_world,
    // and return a ray from camera.position with a unit direction and
    // t in [camera.near_clip, camera.far_clip].
    // (Thin lens, optional until Part 4: when camera.lens_radius > 0, start
    // the ray on the lens disk picked by lens_sample.)
    // [/guided]
    (void)camera, (void)x, (void)y, (void)lens_sample;
    throw NotImplemented(1, "1", "generate_ray");
}

PixelResult raytrace_pixel(const RenderContext& context, int x, int y) {
    // TODO(part1.2): raytrace_pixel, as src/stages/camera.h states its contract.
    // [guided]
    // average context.settings.spp radiance samples over the
    // pixel square. For sample i, make the generator Rng rng(context.settings.seed,
    // pixel index, i), pick a point in the pixel (its centre when spp is 1),
    // convert to normalised coordinates (y = 0 is the top row of the image
    // but the bottom of generate_ray's square), call
    // context.stages.camera.generate_ray and context.radiance.
    // [/guided]
    (void)context, (void)x, (void)y;
    throw NotImplemented(1, "2", "raytrace_pixel");
}

}  // namespace pt::student
