// Camera importance: the camera seen as an emitter of importance We, the
// adjoint of a light's radiance, so that a path can end at the camera from
// the light's side (light tracing, Part 7's t = 1 strategies; Veach 1997
// section 4.5 and 10.2; pbrt-v3 section 16.1.1).
//
// A pixel's value is the measurement I_j = integral of W_j(x, w) L(x, w)
// cos theta dA dw over the lens and the directions, with W_j = N We on the
// rays that land in pixel j (N pixels). We is normalised so that the
// camera's total importance is 1:
//
//     integral We(x, w) cos theta dA(x) dw = 1,
//     We(x, w) = 1 / (A_film A_lens cos^4 theta)   inside the film, else 0,
//
// with theta the angle between w and the viewing axis, A_film = 4
// tan(hfov/2) tan(vfov/2) the film's area on the plane at distance 1, and
// A_lens = pi r^2 (1 for a pinhole, a delta in position). A camera ray
// drawn the way generate_ray draws it (uniform on the film, uniform on the
// lens) has the densities
//
//     pdf_pos = 1 / A_lens,   pdf_dir = 1 / (A_film cos^3 theta),
//
// since a film patch dA at distance 1 / cos theta along the ray subtends
// dw = cos^3 theta dA, so We cos / (pdf_pos pdf_dir) = 1: a camera subpath
// starts with weight 1, as a path tracer's ray does.
//
// Film positions use generate_ray's normalised image coordinates (x, y) in
// [0, 1]^2, (0, 0) at the bottom-left (stages/camera.h); a thin-lens ray
// lands where the pinhole ray through its point on the plane of focus lands.
//
// Projections: the perspective pinhole and the thin lens. A camera type
// without an importance function must make camera_importance_missing()
// name it, so that bidirectional methods drop the strategies that need it
// instead of rendering wrong.
//
// Tests: tests/unit/test_camera_importance.cpp (round trip of generate_ray,
// We cos / pdf = 1, the normalisation by quadrature, the lens density by
// chi-square, and the light-tracing identity: importance splatted from
// points of a uniformly bright plane renders its radiance in every pixel).
#pragma once

#include <optional>
#include <string>

#include "core/vec3.h"
#include "scene/camera.h"

namespace pt {

/// Why `camera` has no importance function ("" when it has one).
std::string camera_importance_missing(const Camera& camera);

/// Where the ray leaving lens point p_lens in unit world direction w lands
/// on the film, in normalised image coordinates, or nothing when it misses
/// the film or points behind the camera. Every camera type: for the
/// orthographic camera p_lens is a point of its film rectangle and w the
/// view direction; for the fisheye only w matters (outside its image
/// circle: nothing).
std::optional<Vec2> camera_film_position(const Camera& camera, const Vec3& p_lens, const Vec3& w);

/// The importance We emitted along the ray leaving p_lens in unit direction
/// w, 1 / (m^2 sr); 0 off the film. `film` receives its film position.
double camera_We(const Camera& camera, const Vec3& p_lens, const Vec3& w, Vec2* film = nullptr);

/// The densities with which the camera draws the ray leaving p_lens in
/// unit direction w (both 0 off the film).
struct CameraRayPdf {
    double pos = 0;  ///< per unit lens area: 1 / A_lens (1 for a pinhole)
    double dir = 0;  ///< per unit solid angle: 1 / (A_film cos^3 theta)
};
CameraRayPdf camera_pdf_We(const Camera& camera, const Vec3& p_lens, const Vec3& w);

/// A point on the lens seen from a point `ref` in the scene (the
/// connection of a light subpath vertex to the camera).
struct CameraImportanceSample {
    double We = 0;      ///< importance along the ray from p_lens towards ref
    Vec3 wi;            ///< unit direction from ref towards p_lens
    double pdf = 0;     ///< solid-angle density of wi at ref: distance^2 / (cos theta A_lens)
    Vec3 p_lens;        ///< the lens point
    double distance = 0;  ///< |p_lens - ref|
    Vec2 film;          ///< normalised image coordinates where the camera sees ref

    bool valid() const { return pdf > 0 && We > 0; }
};
/// Draws a lens point uniformly (u in [0, 1)^2; the pinhole's only point
/// otherwise). Invalid when ref lands off the film, behind the camera, or
/// outside [near_clip, far_clip].
CameraImportanceSample camera_sample_Wi(const Camera& camera, const Vec3& ref, Vec2 u);

}  // namespace pt
