// The shapes the renderer intersects: triangles (from meshes and quads) and
// spheres, and the per-primitive records the scene stores.
//
// Primitive ids: triangles are 0 .. T-1 and spheres are T .. T+S-1, so one
// 32-bit id names any primitive without a type table.
#pragma once

#include <cstdint>
#include <limits>

#include "core/vec3.h"

namespace pt {

/// A triangle as the intersection routine sees it: corners p0, p1, p2 in
/// world space and, when the mesh has them, unit vertex normals n0, n1, n2.
struct Triangle {
    Vec3 p0, p1, p2;
    Vec3 n0, n1, n2;
    bool has_normals = false;
};

/// A sphere in world space.
struct Sphere {
    Vec3 center;
    double radius = 1;  ///< scene units, > 0
};

constexpr uint32_t kNoIndex = std::numeric_limits<uint32_t>::max();

/// How the scene stores a triangle: indices into its vertex arrays.
struct TriangleRecord {
    uint32_t v[3];  ///< indices into Scene::positions
    uint32_t n[3];  ///< indices into Scene::normals, or kNoIndex for a flat triangle
    uint32_t material;
};

struct SphereRecord {
    Sphere sphere;
    uint32_t material;
    /// Its surface faces inwards: a sphere subtracted by CSG (scene/csg.h),
    /// whose visible side bounds the hole it leaves.
    bool inward = false;
};

}  // namespace pt
