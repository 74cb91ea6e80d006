// Self-intersection ("shadow acne") at any scale: rays leaving a surface
// through SurfaceInteraction::spawn_ray / spawn_ray_to never hit the surface
// they start on, and never pass through a parallel surface just beneath it.
// Scenes are translated by 10^2 to 10^6 and scaled by 10^-3 to 10^3.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

#include "core/frame.h"
#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "stages/render_context.h"
#include "scene/mesh.h"
#include "stages/accelerator.h"

using namespace pt;

namespace {

/// Two parallel, tilted squares of side `size` a gap of size * 1e-4 apart
/// (primitive ids 0-1 the upper square, 2-3 the lower), around `center`,
/// and a sphere of radius size / 4 beside them (id 4).
Scene make_layers(double size, const Vec3& center) {
    Scene scene;
    scene.materials.push_back(Material());
    Transform t;
    t.set_rotation(Vec3(1, 2, 3), 37);
    t.translate = center;
    for (double z : {0.0, -1e-4 * size}) {
        MeshData quad;
        double h = size / 2;
        quad.positions = {{-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z}};
        quad.faces = {{0, 1, 2}, {0, 2, 3}};
        add_mesh(scene, quad, t);
    }
    scene.spheres.push_back({{t.point(Vec3(2 * size, 0, 0)), size / 4}, 0});
    scene.finalize();
    return scene;
}

struct Tally {
    int rays = 0, self_hits = 0, leaks = 0;
};

}  // namespace

TEST_CASE("secondary and shadow rays never hit their own surface nor leak through a parallel one") {
    const IntersectStage stage{reference::intersect_triangle, reference::intersect_sphere};
    for (double scale : {1e-3, 1.0, 1e3}) {
        for (double offset : {0.0, 1e2, 1e4, 1e6}) {
            Vec3 center(offset, -0.5 * offset, 0.25 * offset);
            Scene scene = make_layers(scale, center);
            std::unique_ptr<Accelerator> scan = make_linear_scan(scene, stage);
            Rng rng(uint64_t(scale * 1000 + offset));
            Tally tally;
            Vec3 up = scene.triangle(0).p0 - scene.triangle(2).p0;  // from the lower square to the upper
            Vec3 normal = cross(scene.triangle(0).p1 - scene.triangle(0).p0, scene.triangle(0).p2 - scene.triangle(0).p0).unit();
            if (dot(normal, up) < 0) normal = -normal;
            Frame frame(normal);
            Vec3 camera = scene.triangle(0).p0 + normal * (2 * scale);
            for (int i = 0; i < 2000; ++i) {
                // A camera ray onto a random point of the upper square.
                const Triangle tri = scene.triangle(i % 2);
                double r1 = rng.next_1d(), r2 = rng.next_1d();
                if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
                Vec3 target = tri.p0 + r1 * (tri.p1 - tri.p0) + r2 * (tri.p2 - tri.p0);
                Ray camera_ray(camera, target - camera);
                std::optional<Hit> hit = scan->intersect(camera_ray);
                if (!hit || hit->primitive > 1) continue;
                SurfaceInteraction si = make_interaction(scene, camera_ray, *hit);
                ++tally.rays;
                // Reflected directions (above): must hit nothing of the squares.
                Vec3 w_up = frame.to_world(sample_cosine_hemisphere(rng.next_2d()));
                std::optional<Hit> up_hit = scan->intersect(si.spawn_ray(w_up));
                tally.self_hits += up_hit && up_hit->primitive <= 1;
                // Transmitted directions (below): must hit the lower square, not the upper one again.
                Vec3 w_down = -frame.to_world(sample_cosine_hemisphere(rng.next_2d()));
                std::optional<Hit> down_hit = scan->intersect(si.spawn_ray(w_down));
                if (down_hit && down_hit->primitive <= 1) tally.self_hits++;
                if (!down_hit && dot(w_down, -normal) > 0.2) {
                    // Far from grazing, a downward ray must meet the lower square
                    // unless it exits past its edge; check geometrically.
                    Vec3 lower_point = scene.triangle(2).p0;
                    double t_plane = dot(lower_point - si.p, normal) / dot(w_down, normal);
                    Vec3 q = si.p + t_plane * w_down;
                    bool inside = false;
                    for (uint32_t k : {2u, 3u})
                        inside = inside || reference::intersect_triangle(scene.triangle(k), Ray(q + normal * scale, -normal));
                    tally.leaks += inside;
                }
                // Shadow rays to points on the lower square: blocked by the upper
                // square itself only when they go through it, never by the start point.
                Vec3 above = si.p + normal * scale;
                Ray shadow = si.spawn_ray_to(above);
                tally.self_hits += scan->occluded(shadow);
            }
            CAPTURE(scale);
            CAPTURE(offset);
            CHECK(tally.rays > 1500);
            CHECK(tally.self_hits == 0);
            CHECK(tally.leaks == 0);
        }
    }
}

TEST_CASE("rays leaving a sphere at any scale: outward never re-hits, inward reaches the far side") {
    const IntersectStage stage{reference::intersect_triangle, reference::intersect_sphere};
    for (double scale : {1e-3, 1.0, 1e3}) {
        for (double offset : {0.0, 1e2, 1e4, 1e6}) {
            Scene scene;
            scene.materials.push_back(Material());
            Vec3 center(offset, 0.5 * offset, -offset);
            scene.spheres.push_back({{center, scale}, 0});
            scene.finalize();
            std::unique_ptr<Accelerator> scan = make_linear_scan(scene, stage);
            Rng rng(3);
            int self_hits = 0, missed_far_side = 0;
            for (int i = 0; i < 2000; ++i) {
                Vec3 n = sample_uniform_sphere(rng.next_2d());
                Ray camera_ray(center + n * (3 * scale), -n);
                std::optional<Hit> hit = scan->intersect(camera_ray);
                REQUIRE(hit);
                SurfaceInteraction si = make_interaction(scene, camera_ray, *hit);
                Frame frame(si.ng);
                Vec3 out = frame.to_world(sample_cosine_hemisphere(rng.next_2d()));
                self_hits += bool(scan->intersect(si.spawn_ray(out)));
                Vec3 in = -frame.to_world(sample_cosine_hemisphere(rng.next_2d()));
                std::optional<Hit> far = scan->intersect(si.spawn_ray(in));
                // The far side is at distance 2 r cos(theta) from the start.
                missed_far_side += !far || far->t < 1e-3 * scale * std::fabs(dot(in, si.ng));
            }
            CAPTURE(scale);
            CAPTURE(offset);
            CHECK(self_hits == 0);
            CHECK(missed_far_side == 0);
        }
    }
}

TEST_CASE("next_double_up and next_double_down step exactly as std::nextafter") {
    // spawn_ray's rounding away from the surface relies on them; they step
    // the bit pattern inline instead of calling the library.
    const double inf = std::numeric_limits<double>::infinity();
    const double values[] = {0.0, -0.0, 1.0, -1.0, 0.1, -0.1, 1e-310, -1e-310,
                             std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
                             -std::numeric_limits<double>::max(), 123456.789, -9.87e30, inf, -inf};
    for (double v : values) {
        CAPTURE(v);
        const double up = next_double_up(v), down = next_double_down(v);
        const double want_up = std::nextafter(v, inf), want_down = std::nextafter(v, -inf);
        CHECK(std::memcmp(&up, &want_up, sizeof up) == 0);
        CHECK(std::memcmp(&down, &want_down, sizeof down) == 0);
    }
    CHECK(std::isnan(next_double_up(std::nan(""))));
    CHECK(std::isnan(next_double_down(std::nan(""))));
}
