// The reference BVH with 4-wide nodes (`--bvh-width 4`): the binary SAH
// tree of stages/flat_bvh.h collapsed so that each node holds up to four
// children's boxes, tested together with one SSE instruction per plane.
//
// Why: the binary traversal is bound by latency and branch mispredictions
// (docs/bvh.md: about 26 mispredictions per incoherent ray, half of them on
// "did the ray hit both children"), not by arithmetic. A 4-wide node
// replaces two levels of the binary tree, so a ray takes half as many
// dependent steps and decisions (Dammertz, Hanika and Keller, "Shallow
// Bounding Volume Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays",
// EGSR 2008; Wald, Benthin and Boulos, "Getting rid of packets", RT 2008).
//
// Collapse: starting from a binary node's two children, the interior child
// of largest surface area is replaced by its two children until there are
// four (or only leaves are left); each remaining interior child becomes a
// wide node the same way. Leaves and the primitive order are the binary
// tree's, so the per-primitive data (bvh_kernels.h) is shared.
//
// Layout: 128 bytes per node (two cache lines), structure of arrays: for
// each of the six planes (min x, y, z, max x, y, z, as FlatBvhNode::bounds)
// four floats, one per child; then the children: a node index, or a leaf's
// first slot and count. Nodes are in depth-first order.
//
// Exactness: each lane computes exactly the scalar slab test of
// bvh_kernels.h (same float operations in the same order; MAXPS/MINPS
// return their second operand on NaN like the scalar selects do), so every
// box answer is the binary traversal's and the hits are the linear scan's
// bit for bit (tests/bvh). A portable scalar loop over the lanes is used
// where SSE is not available; it gives the same answers.
#pragma once

#include <cstdint>
#include <vector>

#include "stages/accelerator.h"
#include "stages/flat_bvh.h"

namespace pt {

struct Scene;

struct alignas(64) WideBvhNode {
    static constexpr int kWidth = 4;
    /// bounds[plane][lane]: plane as FlatBvhNode::bounds, one lane per child;
    /// unused lanes hold an empty box (min +inf, max -inf).
    alignas(16) float bounds[6][kWidth];
    uint32_t child[kWidth] = {0, 0, 0, 0};  ///< interior child: node index; leaf: first slot
    uint8_t count[kWidth] = {0, 0, 0, 0};   ///< leaf: primitives (>= 1); interior child or unused: 0
    uint8_t valid = 0;                      ///< bit i: lane i holds a child
};
static_assert(sizeof(WideBvhNode) == 128, "a wide node is two cache lines");

/// The binary tree collapsed into 4-wide nodes; nodes[0] is the root (a
/// root that is a leaf becomes one node with one lane). Empty for no primitives.
std::vector<WideBvhNode> collapse_to_wide(const FlatBvh& bvh, int* depth = nullptr);

/// The accelerator over `bvh` collapsed to 4-wide nodes, with the tester
/// that make_reference_bvh picks for `stage` (bvh_kernels.h).
std::unique_ptr<Accelerator> make_wide_bvh(const Scene& scene, const IntersectStage& stage, FlatBvh bvh);

}  // namespace pt
