// The reference BVH with 4- or 8-wide nodes (`--bvh-width 4|8`): the binary
// SAH tree of stages/flat_bvh.h collapsed so that each node holds up to four
// (eight) children's boxes, tested together with one SSE (AVX) instruction
// per plane.
//
// Why: the binary traversal is bound by latency and branch mispredictions
// (docs/bvh.md: about 26 mispredictions per incoherent ray, half of them on
// "did the ray hit both children"), not by arithmetic. A 4-wide node
// replaces two levels of the binary tree and an 8-wide one three, so a ray
// takes two (three) times fewer dependent steps and decisions (Dammertz,
// Hanika and Keller, "Shallow Bounding Volume Hierarchies for Fast SIMD Ray
// Tracing of Incoherent Rays", EGSR 2008; Wald, Benthin and Boulos, "Getting
// rid of packets", RT 2008; Embree's single-ray kernel uses 8-wide nodes).
//
// Collapse: starting from a binary node's two children, the interior child
// of largest surface area is replaced by its two children until there are
// W (or only leaves are left); each remaining interior child becomes a
// wide node the same way. Leaves and the primitive order are the binary
// tree's, so the per-primitive data (bvh_kernels.h) is shared. The 8-wide
// tree with leaf blocks (the default) is collapsed by a plan instead: the
// lanes and merged leaves of least SAH cost (plan_wide_nodes below).
//
// Layout: structure of arrays, 128 bytes per 4-wide node (two cache lines),
// 256 per 8-wide one (four): for each of the six planes (min x, y, z, max
// x, y, z, as FlatBvhNode::bounds) W floats, one per child; then the
// children: a node index, or a leaf's first slot and count. Nodes are in
// depth-first order.
//
// Exactness: each lane computes exactly the scalar slab test of
// bvh_kernels.h (same float operations in the same order; MAXPS/MINPS
// return their second operand on NaN like the scalar selects do), so every
// box answer is the binary traversal's and the hits are the linear scan's
// bit for bit (tests/bvh). The 8-wide test needs AVX; it is chosen at run
// time (__builtin_cpu_supports), and a portable scalar loop over the lanes,
// which gives the same answers, runs where the SIMD test cannot.
#pragma once

#include <cstdint>
#include <vector>

#include "stages/accelerator.h"
#include "stages/flat_bvh.h"

namespace pt {

struct Scene;

template <int W>
struct alignas(64) WideBvhNode {
    static constexpr int kWidth = W;
    /// bounds[plane][lane]: plane as FlatBvhNode::bounds, one lane per child;
    /// unused lanes hold an empty box (min +inf, max -inf).
    alignas(4 * W) float bounds[6][W];
    uint32_t child[W] = {};  ///< interior child: node index; leaf: first slot
    uint8_t count[W] = {};   ///< leaf: primitives (>= 1); interior child or unused: 0
    uint8_t valid = 0;       ///< bit i: lane i holds a child
};
static_assert(sizeof(WideBvhNode<4>) == 128, "a 4-wide node is two cache lines");
static_assert(sizeof(WideBvhNode<8>) == 256, "an 8-wide node is four cache lines");

/// Which binary subtrees become the lanes of each wide node, when chosen by
/// a cost model (bvh_wide_plan.cpp, plan_wide_nodes) instead of the greedy
/// collapse: for binary node i made a wide node, its lanes are
/// lanes[first[i], first[i] + count[i]) (first[i] is kNoPlan otherwise).
struct WidePlan {
    static constexpr uint32_t kNoPlan = UINT32_MAX;
    std::vector<uint32_t> first;
    std::vector<uint8_t> count;
    std::vector<uint32_t> lanes;
    bool empty() const { return first.empty(); }
};

/// Chooses the 8-wide nodes and their leaves by cost (bvh_wide_plan.cpp: the
/// SAH-optimal collapse of Ylitie, Karras and Laine 2017): fills `plan` and
/// turns each binary subtree chosen as one leaf (at most kWideMergedLeaf
/// primitives) into that leaf in `bvh`. A wide node costs
/// kWidePlanNodeCost times its area, a leaf its area times its blocks of four.
constexpr uint32_t kWideMergedLeaf = 8;
constexpr double kWidePlanNodeCost = 2.0;
void plan_wide_nodes(FlatBvh& bvh, WidePlan& plan);

/// The binary tree collapsed into W-wide nodes (W = 4 or 8); nodes[0] is the
/// root (a root that is a leaf becomes one node with one lane). Empty for no
/// primitives. `depth`, when given, receives the deepest wide node's level.
/// With `plan`, each wide node takes the lanes the plan gives.
template <int W>
std::vector<WideBvhNode<W>> collapse_to_wide(const FlatBvh& bvh, int* depth = nullptr,
                                             const WidePlan* plan = nullptr);

/// Whether the 8-wide AVX box test can run on this processor.
bool wide_bvh_has_avx();

/// The accelerator over `bvh` collapsed to `width`-wide nodes (4 or 8), with
/// the tester that make_reference_bvh picks for `stage` (bvh_kernels.h).
/// `simd` false: the portable scalar box test on every machine (the tests
/// compare it with the SIMD one).
std::unique_ptr<Accelerator> make_wide_bvh(const Scene& scene, const IntersectStage& stage, FlatBvh bvh,
                                           int width, bool simd = true);

}  // namespace pt
