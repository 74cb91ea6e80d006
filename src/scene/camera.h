// Camera: a pinhole or thin-lens perspective camera (CS184's Camera).
//
// Camera space follows CS184 and OpenGL: the camera looks down -z, +y is up
// and +x is right. The virtual sensor sits at z = -1 and spans
// [-tan(hfov/2), tan(hfov/2)] x [-tan(vfov/2), tan(vfov/2)].
#pragma once

#include <string>

#include "core/vec3.h"

namespace pt {

struct Camera {
    Vec3 position{0, 0, 0};   ///< centre of projection (lens centre), world space
    Vec3 look_at{0, 0, -1};   ///< a point the camera looks at, world space
    Vec3 up{0, 1, 0};         ///< approximate up direction, world space
    double vfov = 45.0;       ///< vertical field of view, degrees
    double aspect = 4.0 / 3;  ///< film width / height
    double lens_radius = 0;   ///< thin-lens aperture radius, scene units; 0 = pinhole
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
    /// the camera is degenerate (look_at == position, up parallel to the view).
    void finalize(const std::string& where = "camera");

    /// Camera-space vector to world space (rotation only).
    Vec3 to_world(const Vec3& v) const { return right * v.x + true_up * v.y + backward * v.z; }
};

}  // namespace pt
