#include "scene/framing.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace pt {

Vec3 default_view_direction() { return Vec3(0.0, 0.25, 1.0).unit(); }

void frame_camera_on(Camera& camera, const BBox& bounds, const Vec3& from) {
    Vec3 center = bounds.centroid();
    double radius = std::max(0.5 * bounds.extent().norm(), 1e-6);
    double half_fov = radians(camera.vfov) * 0.5;
    if (camera.aspect < 1) half_fov = std::atan(camera.aspect * std::tan(half_fov));
    double distance = radius / std::sin(half_fov);
    camera.look_at = center;
    camera.position = center + from.unit() * distance;
    camera.up = Vec3(0, 1, 0);
    camera.focal_distance = 0;
}

Framing choose_framing(const Scene& scene) {
    Vec3 normal_sum(0);
    double area = 0, volume6 = 0;
    for (const TriangleRecord& r : scene.triangles) {
        const Vec3& p0 = scene.positions[r.v[0]];
        const Vec3& p1 = scene.positions[r.v[1]];
        const Vec3& p2 = scene.positions[r.v[2]];
        Vec3 n = cross(p1 - p0, p2 - p0);  // twice the area, along the geometric normal
        normal_sum += n;
        area += n.norm();
        volume6 += dot(p0, cross(p1, p2));  // six times the signed volume (origin-independent when closed)
    }
    for (const SphereRecord& s : scene.spheres) area += 8 * kPi * s.sphere.radius * s.sphere.radius;
    if (area > 0 && normal_sum.norm() >= 0.05 * area) {
        Vec3 from = normal_sum.unit();
        // Straight above or below, "up" would be the view direction: lean
        // towards the front, as one looks at a terrain.
        if (std::abs(from.y) > 0.95) from = (from + Vec3(0, 0, 0.5)).unit();
        return {from, false, "open side"};
    }
    if (!scene.triangles.empty() && volume6 < 0) return {default_view_direction(), true, "inside a closed room"};
    return {default_view_direction(), false, "default view"};
}

void frame_camera_on_scene(Camera& camera, const Scene& scene) {
    Framing framing = choose_framing(scene);
    frame_camera_on(camera, scene.bounds, framing.from);
    if (framing.inside) {
        // From the centre of the room, looking away from the default side.
        camera.position = scene.bounds.centroid();
        camera.look_at = camera.position - framing.from;
    }
}

}  // namespace pt
