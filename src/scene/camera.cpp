#include "scene/camera.h"

#include <cmath>

#include "core/error.h"
#include "core/math.h"

namespace pt {
namespace {

/// The fisheye film point (x, y) in units where the image circle has
/// radius 1: the shorter side of the film spans [-1, 1].
Vec2 fisheye_disk_point(const Camera& c, double x, double y) {
    Vec2 s = fisheye_disk_scale(c);
    return {(2.0 * x - 1.0) * s.x, (2.0 * y - 1.0) * s.y};
}

}  // namespace

Vec2 fisheye_disk_scale(const Camera& c) {
    return c.aspect >= 1 ? Vec2(c.aspect, 1.0) : Vec2(1.0, 1.0 / c.aspect);
}

const char* to_string(CameraType type) {
    switch (type) {
        case CameraType::perspective: return "perspective";
        case CameraType::orthographic: return "orthographic";
        case CameraType::fisheye: return "fisheye";
    }
    return "?";
}

void Camera::finalize(const std::string& where) {
    Vec3 view = look_at - position;
    if (!(view.norm() > 0)) throw InputError(where + ": look_at must differ from position");
    if (type == CameraType::perspective && !(vfov > 0 && vfov < 180))
        throw InputError(where + ".vfov: expected an angle in (0, 180) degrees");
    if (type == CameraType::orthographic && !(height > 0 && std::isfinite(height)))
        throw InputError(where + ".height: expected a number > 0 (the view height in scene units)");
    if (type == CameraType::fisheye && !(fov > 0 && fov <= 360))
        throw InputError(where + ".fov: expected an angle in (0, 360] degrees");
    if (type != CameraType::perspective && lens_radius > 0)
        throw InputError(where + ": a thin lens (lens_radius, -b) needs a perspective camera, not " +
                         to_string(type));
    if (!(aspect > 0) || !std::isfinite(aspect)) throw InputError(where + ": film aspect ratio must be positive");
    backward = -view.unit();
    Vec3 r = cross(up, backward);
    // Looking straight along the up vector leaves "right" undefined; pick any
    // perpendicular instead of failing, since such a camera is legitimate.
    if (r.norm() < 1e-12 * up.norm()) r = cross(std::fabs(backward.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0), backward);
    right = r.unit();
    true_up = cross(backward, right);
    tan_half_vfov = std::tan(radians(vfov) * 0.5);
    tan_half_hfov = aspect * tan_half_vfov;
    if (focal_distance <= 0) focal_distance = view.norm();
}

Ray orthographic_ray(const Camera& c, double x, double y, Vec2) {
    // The film is a rectangle height x (aspect height) through the camera
    // position, perpendicular to the view; every ray leaves it along -z.
    Vec3 film((2.0 * x - 1.0) * 0.5 * c.height * c.aspect, (2.0 * y - 1.0) * 0.5 * c.height, 0.0);
    return Ray(c.position + c.to_world(film), -c.backward, c.near_clip, c.far_clip);
}

Ray fisheye_ray(const Camera& c, double x, double y, Vec2) {
    Vec2 p = fisheye_disk_point(c, x, y);
    double r = std::hypot(p.x, p.y);
    if (r > 1.0) return Ray(c.position, -c.backward, kInfinity, 0.0);  // outside the image circle
    // Equidistant: the angle from the axis grows linearly with r.
    double theta = r * radians(c.fov) * 0.5;
    double sin_theta = std::sin(theta);
    Vec3 d = r > 0 ? Vec3(sin_theta * p.x / r, sin_theta * p.y / r, -std::cos(theta)) : Vec3(0, 0, -1);
    return Ray(c.position, c.to_world(d).unit(), c.near_clip, c.far_clip);
}

}  // namespace pt
