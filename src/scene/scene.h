// Scene: everything a render needs to know about the world, in world space:
// camera and film, materials, primitives (triangles and spheres), lights.
// Built by the loaders (scene_loader.h), then read-only while rendering.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/bbox.h"
#include "scene/camera.h"
#include "scene/geometry.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/medium.h"

namespace pt {

struct Scene {
    std::string name;       ///< file name without directory and extension; default output name
    std::string path;       ///< the file it was loaded from
    Camera camera;
    int film_width = 480;   ///< pixels
    int film_height = 360;  ///< pixels

    std::vector<Material> materials;
    std::vector<Vec3> positions;             ///< mesh vertex positions, world space
    std::vector<Vec3> normals;               ///< mesh vertex normals, world space, unit
    std::vector<TriangleRecord> triangles;   ///< primitive ids 0 .. T-1
    std::vector<Vec2> uvs;                   ///< mesh texture coordinates (OBJ vt, quad corners)
    /// Per triangle, indices into `uvs` (kNoIndex: none); empty when no triangle has any.
    std::vector<std::array<uint32_t, 3>> triangle_uvs;
    std::vector<SphereRecord> spheres;       ///< primitive ids T .. T+S-1

    std::vector<PointLight> point_lights;
    std::vector<DirectionalLight> directional_lights;
    std::optional<EnvironmentLight> environment;

    /// Participating media (scene/medium.h): materials' interiors and the fog.
    std::vector<Medium> media;
    /// Index into `media` of the medium that fills space outside every
    /// medium boundary (the scene-level "medium"), or -1: vacuum.
    int outside_medium = -1;

    /// Ids of the primitives whose material emits (area lights); set by finalize().
    std::vector<uint32_t> emitters;
    /// Bounds of all primitives; set by finalize().
    BBox bounds;

    uint32_t primitive_count() const { return uint32_t(triangles.size() + spheres.size()); }
    bool is_sphere(uint32_t prim) const { return prim >= triangles.size(); }
    const SphereRecord& sphere_record(uint32_t prim) const { return spheres[prim - triangles.size()]; }
    /// The triangle with id `prim` (< triangles.size()) as the intersection routines see it.
    Triangle triangle(uint32_t prim) const;
    const Material& material_of(uint32_t prim) const;
    /// Texture coordinates of the point p with barycentrics (b1, b2) on
    /// primitive `prim`: interpolated vt for triangles that have them, else
    /// (b1 + b2, b2) (pbrt's default (0,0), (1,0), (1,1) corners); on a sphere,
    /// u the longitude about +y from +z, v = 1 at the top pole, 0 at the bottom.
    Vec2 uv_at(uint32_t prim, double b1, double b2, const Vec3& p) const;
    /// The surface's first tangent at p, dp/du (not unit): the x axis of an
    /// anisotropic BSDF's frame. A triangle without texture coordinates
    /// gives its first edge; a sphere the direction of growing longitude.
    Vec3 dpdu(uint32_t prim, const Vec3& p) const;
    BBox primitive_bounds(uint32_t prim) const;
    double primitive_area(uint32_t prim) const;
    bool has_lights() const {
        return !emitters.empty() || !point_lights.empty() || !directional_lights.empty() ||
               environment.has_value();
    }

    /// Whether light meets a medium anywhere, or a null surface (a volume
    /// path tracer's business: render/integrator_choice.cpp).
    bool has_media() const;
    /// The medium inside a closed shape of material `material` (-1: none).
    int interior_of(uint32_t prim) const { return material_of(prim).interior; }

    /// Computes `emitters` and `bounds`; call after adding primitives.
    void finalize();
};

}  // namespace pt
