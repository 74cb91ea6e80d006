// Uniform grid (`--accel grid`): spatial subdivision into equal cells,
// traversed cell by cell along the ray with the 3D-DDA of Amanatides and
// Woo, "A Fast Voxel Traversal Algorithm for Ray Tracing" (Eurographics
// 1987). The course's counterpart to the BVH's object subdivision: cheap
// to build, fast on evenly spread triangles, slow on "a teapot in a
// stadium" (most cells empty, the teapot in a few of them).
//
// Resolution: about 3 cbrt(n) cells along the longest axis, the other axes
// in proportion (pbrt-v1's GridAccel; Cleary and Wyvill 1988), at most 256
// per axis. Each primitive is listed in every cell its box overlaps
// (grown by the margin of stages/spatial_subdivision.h), so a primitive
// can be met in several cells; mailboxing (Amanatides and Woo) remembers
// the primitives already tested by this ray in a small per-ray hash table
// (64 slots) and skips them. The closest hit stops at the first cell that
// ends beyond the closest hit found so far.
//
// Answers are exactly the linear scan's (same primitive, same t, ties to the
// larger id): the primitives are tested through the intersect stage.
// Tests: tests/bvh/test_accel_agreement.cpp.
#pragma once

#include <memory>

#include "stages/accelerator.h"

namespace pt {

std::unique_ptr<Accelerator> make_uniform_grid(const Scene& scene, const IntersectStage& stage);

}  // namespace pt
