// Instancing by the inverse ray transform (pbrt-v3 section 4.1.2,
// "TransformedPrimitive"): a shape of the scene's "shapes" table is stored
// and accelerated once, in its own object space; an instance is the shape
// seen through a transform M. Instead of moving the shape's triangles into
// the world, the ray goes the other way, o' = M^-1 o, d' = M^-1 d (d' is
// not renormalised, so the ray parameter t is the same in both spaces) and
// is intersected with the shape's own BVH; normals come back by the inverse
// transpose of M (core/transform.h), hit points by M.
//
// Two levels: a BVH over the instances' world boxes (the top level, here)
// whose leaves hold instances, over one BVH per shape (the bottom level,
// built by the bvh stage like any scene's, so a student's BVH serves there
// too). The scene's own primitives (triangles, spheres) keep their BVH
// beside the instances. Memory: one copy of each shape plus one
// InstanceRecord (transform and box, ~180 bytes) per instance, whatever the
// shape's size (README "Instancing", docs/scenes.md "shapes").
//
// A CSG shape (scene/csg.h) gets stages/csg_accelerator.h below the top
// level instead of a BVH; group shapes never get here (the loader flattens
// them into instances), and emitting instances are copied into the world.
//
// Tests: tests/unit/test_instances.cpp (instances against the same
// geometry placed in the world: hits, normals under non-uniform scale,
// shadow rays; the loader's errors).
#pragma once

#include <memory>

#include "stages/stages.h"

namespace pt {

/// `own`, the accelerator of the scene's primitives, with the scene's
/// instances added over per-shape accelerators built by `stages`. Returns
/// `own` unchanged when the scene has no instances.
std::unique_ptr<Accelerator> add_instances(std::unique_ptr<Accelerator> own, const Scene& scene,
                                           const Stages& stages, const AcceleratorSettings& settings);

}  // namespace pt
