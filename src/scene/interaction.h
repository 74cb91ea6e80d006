// SurfaceInteraction: what the integrators know about a hit point, and how
// rays leave it without hitting the surface they start on.
//
// Self-intersection ("shadow acne") is avoided with floating-point error
// bounds, as in pbrt-v3 section 3.9 (Pharr, Jakob and Humphreys): the hit
// point is computed from barycentrics (triangles) or re-projected onto the
// surface (spheres), which bounds its error per component by p_error; a new
// ray starts at p offset along the geometric normal by dot(|ng|, p_error),
// rounded one ulp further away. The offset scales with the coordinates, so
// it works at 10^-3 and at 10^6 alike, and it is far smaller than any fixed
// epsilon, so rays do not leak through nearby parallel surfaces.
#pragma once

#include <cstdint>
#include <limits>

#include "core/ray.h"
#include "core/vec3.h"

namespace pt {

struct Material;

struct SurfaceInteraction {
    Vec3 p;        ///< hit point, world space
    Vec3 p_error;  ///< bound on the absolute error of each component of p
    Vec3 n;        ///< unit shading normal (from the intersection routine)
    Vec3 ng;       ///< unit geometric normal, as stored (not flipped towards the ray)
    Vec3 wo;       ///< unit direction from p back towards the ray origin
    double t = 0;  ///< ray parameter of the hit
    double b1 = 0, b2 = 0;  ///< barycentrics of the hit (triangles)
    uint32_t primitive = 0;  ///< primitive id
    uint32_t part = 0xffffffffu;  ///< for an instance: the primitive of its shape (Hit::part); else kNoIndex
    const Material* material = nullptr;  ///< never null for a real hit
    int depth = 0;  ///< depth of the ray that found this hit

    /// A ray leaving the surface in direction w (any length), starting just
    /// off the surface on w's side; depth is one more than the incoming ray's.
    Ray spawn_ray(const Vec3& w) const;
    /// A shadow ray from the surface towards `target`, for visibility tests:
    /// direction target - origin, interval [0, 1 - kShadowEpsilon], so it
    /// stops just short of the target.
    Ray spawn_ray_to(const Vec3& target) const;
};

/// t_min of spawned rays: the smallest positive double, so that t = 0 and
/// t = -0 are misses. A point on a plane at coordinate 0 (the Cornell box's
/// floor, y = 0) is computed exactly, so its error bound and its offset are
/// 0 and the ray starts on the plane; Moller-Trumbore then finds that plane
/// at t = +-0 exactly, which t_min = 0 would count as a hit (every shadow
/// ray blocked by the surface it leaves).
constexpr double kSpawnTMin = std::numeric_limits<double>::denorm_min();

/// Fraction of a shadow ray's length left out at its far end, so that it
/// does not hit the light surface it aims at (pbrt-v3's ShadowEpsilon).
constexpr double kShadowEpsilon = 1e-4;

/// p moved off the surface along ng, to the side of w, by the error bound;
/// each component rounded one more ulp away (pbrt-v3 OffsetRayOrigin).
Vec3 offset_ray_origin(const Vec3& p, const Vec3& p_error, const Vec3& ng, const Vec3& w);

}  // namespace pt
