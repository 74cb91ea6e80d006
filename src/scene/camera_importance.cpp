// Camera importance of the perspective camera (pinhole and thin lens). See
// scene/camera_importance.h for the normalisation and the densities.
#include "scene/camera_importance.h"

#include <cmath>

#include "core/math.h"
#include "core/sampling.h"

namespace pt {
namespace {

/// Area of the film on the plane at distance 1 in front of the lens.
double film_area(const Camera& camera) { return 4.0 * camera.tan_half_hfov * camera.tan_half_vfov; }

/// Area of the lens: 1 for a pinhole, whose position is a delta.
double lens_area(const Camera& camera) {
    return camera.lens_radius > 0 ? kPi * camera.lens_radius * camera.lens_radius : 1.0;
}

/// World vector to camera space (the inverse rotation of Camera::to_world).
Vec3 to_camera(const Camera& camera, const Vec3& v) {
    return {dot(v, camera.right), dot(v, camera.true_up), dot(v, camera.backward)};
}

/// cos theta of a unit world direction against the viewing axis (-backward).
double cos_to_axis(const Camera& camera, const Vec3& w) { return -dot(w, camera.backward); }

}  // namespace

std::string camera_importance_missing(const Camera& camera) {
    // The perspective camera (pinhole or thin lens) has one; the orthographic
    // camera's rays are parallel (a delta in direction) and the fisheye's
    // importance is not written yet.
    if (camera.type == CameraType::orthographic) return "the orthographic camera has no importance function";
    if (camera.type == CameraType::fisheye) return "the fisheye camera has no importance function";
    return "";
}

namespace {

/// Image coordinates, or nothing off the film.
std::optional<Vec2> on_film(double x, double y) {
    if (!(x >= 0 && x <= 1 && y >= 0 && y <= 1)) return std::nullopt;
    return Vec2(x, y);
}

/// orthographic_ray backwards: a ray along the view axis from a point of
/// the film rectangle (scene/camera.cpp).
std::optional<Vec2> orthographic_film_position(const Camera& camera, const Vec3& p_film, const Vec3& w) {
    if (!(dot(w, camera.backward) < -1.0 + 1e-12)) return std::nullopt;  // not along the axis
    Vec3 o = to_camera(camera, p_film - camera.position);
    return on_film(0.5 * (o.x / (0.5 * camera.height * camera.aspect) + 1.0), 0.5 * (o.y / (0.5 * camera.height) + 1.0));
}

/// fisheye_ray backwards: the angle theta off the axis is r fov / 2.
std::optional<Vec2> fisheye_film_position(const Camera& camera, const Vec3& w) {
    Vec3 d = to_camera(camera, w);
    double theta = std::acos(clamp(-d.z / d.norm(), -1.0, 1.0));
    double r = theta / (radians(camera.fov) * 0.5);
    if (!(r <= 1.0)) return std::nullopt;  // outside the image circle
    double rho = std::hypot(d.x, d.y);
    Vec2 s = fisheye_disk_scale(camera);
    double px = rho > 0 ? r * d.x / rho : 0.0, py = rho > 0 ? r * d.y / rho : 0.0;
    return on_film(0.5 * (px / s.x + 1.0), 0.5 * (py / s.y + 1.0));
}

}  // namespace

std::optional<Vec2> camera_film_position(const Camera& camera, const Vec3& p_lens, const Vec3& w) {
    if (camera.type == CameraType::orthographic) return orthographic_film_position(camera, p_lens, w);
    if (camera.type == CameraType::fisheye) return fisheye_film_position(camera, w);
    Vec3 d = to_camera(camera, w);
    double cos_theta = -d.z;
    if (!(cos_theta > 0)) return std::nullopt;  // behind the lens, or in its plane
    // Where the ray meets the plane of focus z = -focal_distance (any plane
    // for a pinhole, whose rays all pass through the centre), then that
    // point seen from the centre on the plane z = -1: generate_ray backwards.
    double focus = camera.lens_radius > 0 ? camera.focal_distance : 1.0;
    Vec3 o = to_camera(camera, p_lens - camera.position);
    Vec3 on_focus_plane = o + d * (focus / cos_theta);
    double sx = on_focus_plane.x / focus, sy = on_focus_plane.y / focus;
    Vec2 film(0.5 * (sx / camera.tan_half_hfov + 1.0), 0.5 * (sy / camera.tan_half_vfov + 1.0));
    if (!(film.x >= 0 && film.x <= 1 && film.y >= 0 && film.y <= 1)) return std::nullopt;
    return film;
}

double camera_We(const Camera& camera, const Vec3& p_lens, const Vec3& w, Vec2* film) {
    if (!camera_importance_missing(camera).empty()) return 0.0;
    std::optional<Vec2> at = camera_film_position(camera, p_lens, w);
    if (!at) return 0.0;
    if (film) *film = *at;
    double cos2 = sqr(cos_to_axis(camera, w));
    return 1.0 / (film_area(camera) * lens_area(camera) * cos2 * cos2);
}

CameraRayPdf camera_pdf_We(const Camera& camera, const Vec3& p_lens, const Vec3& w) {
    if (!camera_importance_missing(camera).empty()) return {};
    if (!camera_film_position(camera, p_lens, w)) return {};
    double cos_theta = cos_to_axis(camera, w);
    return {1.0 / lens_area(camera), 1.0 / (film_area(camera) * cos_theta * cos_theta * cos_theta)};
}

CameraImportanceSample camera_sample_Wi(const Camera& camera, const Vec3& ref, Vec2 u) {
    CameraImportanceSample s;
    s.p_lens = camera.position;
    if (camera.lens_radius > 0) {
        Vec2 disk = sample_concentric_disk(u);
        s.p_lens += camera.to_world(Vec3(camera.lens_radius * disk.x, camera.lens_radius * disk.y, 0));
    }
    Vec3 to_lens = s.p_lens - ref;
    double distance2 = to_lens.norm2();
    if (!(distance2 > 0) || !std::isfinite(distance2)) return {};
    s.distance = std::sqrt(distance2);
    s.wi = to_lens / s.distance;
    // The camera ray that would find ref starts at p_lens along -wi and
    // counts hits in [near_clip, far_clip].
    if (s.distance < camera.near_clip || s.distance > camera.far_clip) return {};
    s.We = camera_We(camera, s.p_lens, -s.wi, &s.film);
    if (!(s.We > 0)) return {};
    // Uniform on the lens, pdf_A = 1 / A_lens, to solid angle at ref.
    s.pdf = distance2 / (cos_to_axis(camera, -s.wi) * lens_area(camera));
    if (!std::isfinite(s.pdf) || !std::isfinite(s.We)) return {};
    return s;
}

}  // namespace pt
