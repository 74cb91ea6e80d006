// Medium boundaries: a material with an "interior" medium (scene/medium.h)
// fills the inside of the shapes made of it, so those shapes must have an
// inside. A sphere always has one; a mesh must be closed and consistently
// wound: every edge shared by exactly two of its triangles (of that
// material), once in each direction. The volume path tracer then knows it
// enters the medium where a ray crosses the surface against its geometric
// normal and leaves it where it crosses along it, which needs the normals to
// point out: a mesh wound inwards (negative signed volume) is turned round.
//
// Vertices are matched by position, so an OBJ whose seams repeat a vertex
// (for separate normals or texture coordinates) still counts as closed.
//
// Tests: tests/unit/test_media_scene.cpp (a closed cube passes, an open box
// and a mis-wound face fail with the edge named, an inward cube is flipped).
#pragma once

#include <string>
#include <vector>

#include "scene/material.h"
#include "scene/mesh.h"

namespace pt {

/// For each material of `mesh` that holds a medium: checks that its faces
/// are closed and consistently wound, and reverses their winding if they
/// face inwards. Returns "" when every such part is fine, else what is wrong
/// (for the loader's one-line error).
std::string orient_medium_boundaries(MeshData& mesh, const std::vector<Material>& materials);

/// The same check on all faces of `mesh` (a CSG operand, scene/csg.h, must
/// have an inside too); `intro` begins the message ("..., but ").
std::string orient_closed_mesh(MeshData& mesh, const std::string& intro);

}  // namespace pt
