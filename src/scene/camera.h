// Camera: where camera rays start and where they go (CS184's Camera), of
// three types (DESIGN.md, second phase):
//
//   perspective   a pinhole or a thin lens. Camera space follows CS184 and
//                 OpenGL: the camera looks down -z, +y is up and +x is right;
//                 the virtual sensor sits at z = -1 and spans
//                 [-tan(hfov/2), tan(hfov/2)] x [-tan(vfov/2), tan(vfov/2)].
//                 Its rays are what Part 1's generate_ray computes (the
//                 student contract, stages/camera.h).
//   orthographic  parallel rays along -z from the points of a rectangle
//                 `height` scene units tall (and aspect x height wide) about
//                 the camera position: sizes do not shrink with distance
//                 (architectural and technical drawings).
//   fisheye       an equidistant projection (the "f-theta" lens): a film
//                 point at distance r from the centre sees the direction at
//                 angle theta = r (fov / 2) from the view axis, with r = 1 on
//                 the image circle inscribed in the film's shorter side. A
//                 fov of 180 degrees sees the half space ahead, 360 the whole
//                 sphere (T5's curved screen: rays through a sphere around
//                 the eye, unrolled onto a disk). Film points outside the
//                 image circle see nothing (black).
//
// The orthographic and fisheye rays are reference code, not a student task
// (RenderContext puts them in place of the stage's generate_ray when the
// scene asks for them). A camera ray whose interval is empty (t_min >
// t_max) sees nothing: RenderContext::radiance returns black for it.
//
// For bidirectional methods every type also answers the inverse question,
// where a ray from a point of the camera lands on the film
// (camera_film_position, scene/camera_importance.h).
//
// Tests: tests/unit/test_camera.cpp (centre and corner rays by hand for
// each type; camera_film_position inverts the rays).
#pragma once

#include <optional>
#include <string>

#include "core/ray.h"
#include "core/vec3.h"

namespace pt {

enum class CameraType { perspective, orthographic, fisheye };

struct Camera {
    CameraType type = CameraType::perspective;
    Vec3 position{0, 0, 0};   ///< centre of projection (lens centre; the film's centre for orthographic), world space
    Vec3 look_at{0, 0, -1};   ///< a point the camera looks at, world space
    Vec3 up{0, 1, 0};         ///< approximate up direction, world space
    double vfov = 45.0;       ///< perspective: vertical field of view, degrees
    double height = 2.0;      ///< orthographic: height of the viewed rectangle, scene units
    double fov = 180.0;       ///< fisheye: field of view across the image circle, degrees, (0, 360]
    double aspect = 4.0 / 3;  ///< film width / height
    double lens_radius = 0;   ///< thin-lens aperture radius, scene units; 0 = pinhole (perspective only)
    double focal_distance = 0;  ///< distance to the plane in focus; 0 = distance to look_at
    double near_clip = 0;     ///< camera rays start at this ray parameter
    double far_clip = 1e300;  ///< camera rays end at this ray parameter

    // Derived by finalize(): the camera-to-world rotation as three columns.
    Vec3 right;     ///< world-space camera +x
    Vec3 true_up;   ///< world-space camera +y
    Vec3 backward;  ///< world-space camera +z (the camera looks along -backward)
    double tan_half_vfov = 0;  ///< tan(vfov / 2)
    double tan_half_hfov = 0;  ///< tan(hfov / 2) = aspect * tan(vfov / 2)

    /// Computes the derived members; throws InputError naming `where` when
    /// the camera is degenerate (look_at == position, a field of view or
    /// height out of range, a thin lens on a camera that is not perspective).
    void finalize(const std::string& where = "camera");

    /// Camera-space vector to world space (rotation only), and back.
    Vec3 to_world(const Vec3& v) const { return right * v.x + true_up * v.y + backward * v.z; }
    Vec3 to_camera(const Vec3& w) const { return {dot(w, right), dot(w, true_up), dot(w, backward)}; }
};

const char* to_string(CameraType type);

/// The camera ray of an orthographic camera through image point (x, y)
/// (lens_sample unused); the signature of the camera stage's generate_ray.
Ray orthographic_ray(const Camera& camera, double x, double y, Vec2 lens_sample);
/// The camera ray of a fisheye camera through image point (x, y), or an
/// empty ray (t_min > t_max) outside the image circle.
Ray fisheye_ray(const Camera& camera, double x, double y, Vec2 lens_sample);

/// Half the film's width and height in units of the fisheye's image-circle
/// radius: (aspect, 1) for a wide film, (1, 1 / aspect) for a tall one.
Vec2 fisheye_disk_scale(const Camera& camera);

/// Whether a camera ray sees nothing (a film point outside the fisheye's circle).
inline bool sees_nothing(const Ray& ray) { return !(ray.t_min <= ray.t_max); }

}  // namespace pt
