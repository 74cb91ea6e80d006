// SAH kd-tree (`--accel kdtree`): spatial subdivision by axis-aligned planes
// chosen with the surface area heuristic, built in O(n log n) as in Wald
// and Havran, "On building fast kd-Trees for Ray Tracing, and on doing that
// in O(N log N)" (IEEE RT 2006), and traversed front to back (pbrt-v3
// section 4.4.3, after Jansen 1986 and Arvo 1988).
//
// Build. Every primitive contributes, per axis, a start and an end event at
// its box's bounds (or one "planar" event when the box is flat on that
// axis), clipped to the node's voxel. The events are sorted once; a sweep
// over them evaluates every candidate plane with
//     cost = K_T + K_I (SA(V_L) / SA(V) N_L + SA(V_R) / SA(V) N_R)
// scaled by 0.8 when one side is empty (the empty-space bonus), against
// K_I N for a leaf (K_T = 1, K_I = 0.8). Splitting a node keeps
// the events of primitives that lie on one side in order and merges in the
// sorted new events of primitives that straddle the plane, so no level
// sorts again: O(n log n) overall. Planar primitives on the plane go left.
// Unlike a BVH, a primitive that straddles a plane is listed on both
// sides. Depth is capped at 8 + 1.3 log2 n (pbrt).
//
// Traversal: the ray is clipped to the root's box; at a node the child on
// the origin's side of the plane comes first, the other is kept with its
// part of the ray; a leaf's closest hit ends the traversal unless it lies
// beyond the leaf's part of the ray. Primitive boxes carry the margin of
// stages/spatial_subdivision.h, so the answers are exactly the linear
// scan's (tests/bvh/test_accel_agreement.cpp).
#pragma once

#include <memory>

#include "stages/accelerator.h"

namespace pt {

std::unique_ptr<Accelerator> make_kd_tree(const Scene& scene, const IntersectStage& stage);

}  // namespace pt
