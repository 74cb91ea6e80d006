// Part 1, tasks 1 and 2, written from the TODO steps.
#include "core/rng.h"
#include "core/sampling.h"
#include "stages/camera.h"
#include "stages/render_context.h"

namespace pt::student {

Ray generate_ray(const Camera& camera, double x, double y, Vec2 lens_sample) {
    Vec3 sensor((2 * x - 1) * camera.tan_half_hfov, (2 * y - 1) * camera.tan_half_vfov, -1);
    if (camera.lens_radius <= 0)
        return Ray(camera.position, camera.to_world(sensor).unit(), camera.near_clip,
                   camera.far_clip);
    Vec2 disk = sample_concentric_disk(lens_sample);
    Vec3 lens(camera.lens_radius * disk.x, camera.lens_radius * disk.y, 0);
    Vec3 d = camera.to_world(sensor * camera.focal_distance - lens).unit();
    return Ray(camera.position + camera.to_world(lens), d, camera.near_clip, camera.far_clip);
}

PixelResult raytrace_pixel(const RenderContext& context, int x, int y) {
    const int w = context.scene.film_width, h = context.scene.film_height;
    const int spp = context.settings.spp;
    Color sum;
    for (int i = 0; i < spp; ++i) {
        Rng rng(context.settings.seed, uint64_t(y) * uint64_t(w) + uint64_t(x), uint64_t(i));
        Vec2 p = spp == 1 ? Vec2(0.5, 0.5) : rng.next_2d();
        double u = (x + p.x) / w, v = 1 - (y + p.y) / h;
        Ray ray = context.stages.camera.generate_ray(context.scene.camera, u, v, rng.next_2d());
        sum += context.radiance(ray, rng);
    }
    return {sum / double(spp), spp};
}

}  // namespace pt::student
