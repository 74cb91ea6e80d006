// Stage `intersect` (Part 1): ray-triangle and ray-sphere intersection.
//
// Triangle: Moller and Trumbore, "Fast, Minimum Storage Ray/Triangle
// Intersection" (JGT 1997). With e1 = p1 - p0, e2 = p2 - p0, s = o - p0,
// Cramer's rule solves o + t d = (1 - b1 - b2) p0 + b1 p1 + b2 p2:
//     [t, b1, b2] = 1 / dot(d x e2, e1) * [dot(s x e1, e2), dot(d x e2, s), dot(s x e1, d)]
// A hit needs b1 >= 0, b2 >= 0, b1 + b2 <= 1 and t in [t_min, t_max].
//
// Sphere: |o + t d - c|^2 = r^2 is a quadratic in t. The reference solves it
// without catastrophic cancellation (Haines et al., "Precision Improvements
// for Ray/Sphere Intersection", Ray Tracing Gems chapter 7, 2019): the
// discriminant from the perpendicular distance |f - (f.d) d|, and the second
// root from the first by Vieta (t0 t1 = c/a).
//
// Tests: tests/unit/test_intersect.cpp (hand-computed hits, misses, edges,
// parallel and degenerate cases, a unit sphere 10^6 units away).
#pragma once

#include <cstdint>
#include <optional>

#include "core/ray.h"
#include "scene/geometry.h"

namespace pt {

/// A ray's closest hit with one primitive.
struct Hit {
    double t = kInfinity;  ///< ray parameter: the hit point is ray.o + t * ray.d
    Vec3 n;                ///< unit shading normal: interpolated vertex normals when the
                           ///< triangle has them, else the geometric normal (p1-p0) x (p2-p0)
                           ///< normalised; for spheres the outward normal. Never flipped
                           ///< towards the ray.
    double b1 = 0, b2 = 0;  ///< barycentric weights of p1 and p2 (p0's is 1 - b1 - b2); 0 for spheres
    uint32_t primitive = 0;  ///< primitive id; set by the caller (the accelerator), not by the routines
    /// For a hit on an instance (primitive is its id): the primitive of its
    /// shape that was hit, whose barycentrics b1, b2 are; kNoIndex otherwise.
    uint32_t part = kNoIndex;
};

using IntersectTriangleFn = std::optional<Hit> (*)(const Triangle& triangle, const Ray& ray);
using IntersectSphereFn = std::optional<Hit> (*)(const Sphere& sphere, const Ray& ray);

/// The function table of the stage.
struct IntersectStage {
    /// Closest hit of `ray` with the triangle within [ray.t_min, ray.t_max];
    /// nothing when the ray misses, is parallel to the plane, or the
    /// triangle is degenerate (zero area). Never returns NaN.
    IntersectTriangleFn intersect_triangle;
    /// Closest hit of `ray` with the sphere within [ray.t_min, ray.t_max]:
    /// the near root if it lies in the interval, else the far root (a ray
    /// starting inside the sphere hits the far side); nothing otherwise.
    IntersectSphereFn intersect_sphere;
};

namespace reference {
std::optional<Hit> intersect_triangle(const Triangle& triangle, const Ray& ray);
std::optional<Hit> intersect_sphere(const Sphere& sphere, const Ray& ray);
/// The same contract as intersect_triangle, computed with the watertight
/// test of Woop, Benthin and Wald (JCGT 2013): a ray through a shared
/// edge or vertex of a closed mesh always hits one of its triangles
/// (`--triangle watertight`; see stages/intersect_watertight.cpp).
std::optional<Hit> intersect_triangle_watertight(const Triangle& triangle, const Ray& ray);
}  // namespace reference

namespace student {
std::optional<Hit> intersect_triangle(const Triangle& triangle, const Ray& ray);
std::optional<Hit> intersect_sphere(const Sphere& sphere, const Ray& ray);
}  // namespace student

}  // namespace pt
