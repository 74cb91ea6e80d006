// Scene: everything a render needs to know about the world, in world space:
// camera and film, materials, primitives (triangles and spheres), lights.
// Built by the loaders (scene_loader.h), then read-only while rendering.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/bbox.h"
#include "core/transform.h"
#include "scene/camera.h"
#include "scene/csg.h"
#include "scene/geometry.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/medium.h"

namespace pt {

struct Scene;

/// A named entry of the scene's "shapes" table: geometry in its own object
/// space, stored once however many instances place it.
struct ShapeRecord {
    std::string name;
    std::shared_ptr<const Scene> geometry;  ///< triangles and spheres only; material 0 everywhere
    /// A CSG shape (scene/csg.h): the tree over `geometry`'s primitives,
    /// whose leaves are closed solids; null for a plain shape.
    std::shared_ptr<const CsgTree> csg;
};

/// One placement of a shape ({"type": "instance"}): the shape's geometry
/// seen through `to_world` (rays go the other way, by its inverse).
struct InstanceRecord {
    uint32_t shape = 0;     ///< index into Scene::shapes
    uint32_t material = 0;  ///< index into Scene::materials
    Transform to_world;     ///< object space -> world space
    BBox bounds;            ///< world-space bounds (the shape's box, transformed)
};

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
    std::vector<ShapeRecord> shapes;         ///< the "shapes" table
    /// Instances: ids T+S .. T+S+I-1, outside primitive_count() (the
    /// accelerators of the scene's own primitives never see them; the
    /// instance level of stages/instance_accelerator.h does).
    std::vector<InstanceRecord> instances;

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

    /// Triangles and spheres; instances come after them (is_instance).
    uint32_t primitive_count() const { return uint32_t(triangles.size() + spheres.size()); }
    bool is_instance(uint32_t prim) const { return prim >= primitive_count(); }
    const InstanceRecord& instance(uint32_t prim) const { return instances[prim - primitive_count()]; }
    const Scene& shape_of(uint32_t prim) const { return *shapes[instance(prim).shape].geometry; }
    /// Whether there is anything to hit: primitives or instances.
    bool has_geometry() const { return primitive_count() > 0 || !instances.empty(); }
    bool is_sphere(uint32_t prim) const { return prim >= triangles.size(); }
    const SphereRecord& sphere_record(uint32_t prim) const { return spheres[prim - triangles.size()]; }
    /// The triangle with id `prim` (< triangles.size()) as the intersection routines see it.
    Triangle triangle(uint32_t prim) const;
    const Material& material_of(uint32_t prim) const;
    /// Texture coordinates of the point p with barycentrics (b1, b2) on
    /// primitive `prim`: interpolated vt for triangles that have them, else
    /// (b1 + b2, b2) (pbrt's default (0,0), (1,0), (1,1) corners); on a sphere,
    /// u the longitude about +y from +z, v = 1 at the top pole, 0 at the bottom.
    /// For an instance, `part` is the primitive of its shape that was hit
    /// (SurfaceInteraction::part) and p is a world-space point.
    Vec2 uv_at(uint32_t prim, double b1, double b2, const Vec3& p, uint32_t part = kNoIndex) const;
    /// The surface's first tangent at p, dp/du (not unit): the x axis of an
    /// anisotropic BSDF's frame. A triangle without texture coordinates
    /// gives its first edge; a sphere the direction of growing longitude.
    Vec3 dpdu(uint32_t prim, const Vec3& p, uint32_t part = kNoIndex) const;
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
