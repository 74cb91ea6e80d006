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
    // Every camera today is perspective (pinhole or thin lens), which has one.
    (void)camera;
    return "";
}

std::optional<Vec2> camera_film_position(const Camera& camera, const Vec3& p_lens, const Vec3& w) {
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
    std::optional<Vec2> at = camera_film_position(camera, p_lens, w);
    if (!at) return 0.0;
    if (film) *film = *at;
    double cos2 = sqr(cos_to_axis(camera, w));
    return 1.0 / (film_area(camera) * lens_area(camera) * cos2 * cos2);
}

CameraRayPdf camera_pdf_We(const Camera& camera, const Vec3& p_lens, const Vec3& w) {
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
