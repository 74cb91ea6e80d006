// Reading Wavefront OBJ meshes (with tinyobjloader) and their MTL materials.
//
// MTL mapping (DESIGN.md): Kd -> diffuse albedo, Ke -> emission,
// illum 3 or 5 -> mirror with reflectance Ks, illum 4, 6 or 7 -> glass with
// index of refraction Ni, map_Kd -> an image texture for the diffuse albedo
// (its -s option scales u and v), Pm > 0 -> a rough metal (docs/global.md).
// Texture coordinates (vt) are kept for faces whose three corners have
// them. Polygons are triangulated on load.
#pragma once

#include <optional>
#include <string>

#include "core/transform.h"
#include "scene/mesh.h"

namespace pt {

struct Scene;

struct ObjLoadOptions {
    std::string where;                      ///< for errors: "scene.json: objects[1]"
    std::optional<uint32_t> material;       ///< scene material for every face (overrides the MTL)
    std::optional<uint32_t> fallback_material;  ///< for faces without a material; none = error
};

/// Reads `path` and returns it as MeshData with scene material indices,
/// adding the MTL's materials to `scene.materials`. Throws InputError for a
/// missing or unreadable file, a missing MTL, indices out of range,
/// non-finite coordinates, no faces, or faces left without a material.
MeshData read_obj(Scene& scene, const std::string& path, const ObjLoadOptions& options);

}  // namespace pt
