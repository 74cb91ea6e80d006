// Framing a camera on a scene that has none: a bare OBJ on the command line,
// a JSON scene without "camera", or a generated benchmark mesh.
//
// From outside, a closed mesh looks right from anywhere, but an open box or
// a room does not: seen from the default side, the Cornell box shows the
// outside of its back wall and renders black (issue 22). So the camera
// looks from the side the surfaces face. The area-weighted normals of a
// closed surface sum to zero (divergence theorem: the integral of n over a
// closed surface vanishes); an open box's sum points out of its missing
// wall (n = minus the missing wall's outward normal, times its area), which
// is where a camera sees the insides of the walls.
#pragma once

#include "core/bbox.h"
#include "scene/scene.h"

namespace pt {

/// The default view direction (from the centre towards the camera): the
/// front (+z) and a little above, as mesh viewers do.
Vec3 default_view_direction();

/// Places `camera` at the distance where a sphere around `bounds` fills the
/// smaller field of view, on the side `from` (a direction away from the
/// centre), looking at the centre.
void frame_camera_on(Camera& camera, const BBox& bounds, const Vec3& from = default_view_direction());

/// Where a camera framing the scene's primitives should stand, and why.
struct Framing {
    Vec3 from;          ///< direction from the centre towards the camera
    bool inside = false;  ///< a closed room (normals inward): stand at its centre
    const char* reason;   ///< for messages: "open side", "inside a closed room", "default view"
};

/// The open side of an open surface (|sum of area-weighted normals| at least
/// 5% of the total area), the inside of a closed surface whose normals point
/// inward (negative signed volume), else the default view.
Framing choose_framing(const Scene& scene);

/// frame_camera_on with the choice of choose_framing (scene.bounds must be set).
void frame_camera_on_scene(Camera& camera, const Scene& scene);

}  // namespace pt
