// FlatBvh: the reference BVH's data, built by binned SAH (or median or
// middle splits) and stored as a flat array of 32-byte nodes in depth-first
// order. The traversal over it is in stages/bvh_traverse.cpp; the split
// criteria and their sources are in stages/bvh.h.
//
// Layout (pbrt-v3 section 4.3.4, "Compact BVH for traversal"): a node's
// first child immediately follows it in the array; an interior node stores
// the index of its second child; a leaf stores the range of its primitives
// in `primitives`, which is sorted by leaf, so a leaf's primitives (and the
// traversal's per-primitive data, kept in the same order) are contiguous in
// memory, and so are all the primitives of any subtree.
//
// Boxes are stored in single precision, rounded outward (each bound is the
// nearest float on the far side of the double-precision bound), so a node's
// box always contains its primitives exactly and 32 bytes hold a node. The
// slab test runs in single precision too, with the double-precision ray
// rounded so that it stays conservative (stages/bvh_traverse.cpp).
//
// Leaf cost model of the SAH (bvh.h): C_trav = 1 and C_isect = 1, costs
// relative to one triangle test. C_trav = 0.5 and 2, and 32 bins instead of
// 16, traced incoherent rays within a few per cent of this choice on the
// bunny and Nefertiti (docs/bvh.md). A node of more than
// max_leaf primitives is always split; one of at most min(4, max_leaf) is
// always a leaf (as Embree's leaves of four: a faster build, and the 8-wide
// BVH tests four triangles at once, stages/bvh_leaf_block.h); between the
// two, a node is split only when the SAH says the split is cheaper. The
// children's triangles are counted in blocks of four, rounded up (as the
// 8-wide BVH tests them and Embree's SAH counts its four-triangle leaves):
// fuller leaves, fewer nodes, incoherent rays a few per cent faster
// (docs/bvh_history.md, issue 17, ninth run).
//
// Robustness: a node whose centroids all coincide (no split plane separates
// them) is split in the middle of its primitive list; below depth 48 every
// split is an object median, so no leaf is deeper than kMaxBvhDepth and
// the traversal stack never overflows.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/bbox.h"

namespace pt {

struct Scene;
struct AcceleratorSettings;

/// Deepest possible leaf: 48 levels of SAH, then at most 32 of median splits.
constexpr int kMaxBvhDepth = 80;

/// How the reference BVH chooses its split planes (`--bvh-split`).
enum class BvhSplit {
    sah,     ///< binned surface area heuristic
    median,  ///< the median centroid along the axis of largest centroid extent
    middle,  ///< the middle of the centroid bounds along that axis
};

BvhSplit parse_bvh_split(const std::string& name);  ///< "sah", "median", "middle"
const char* to_string(BvhSplit split);

/// One node: 32 bytes, aligned so that a node never straddles a cache line.
struct alignas(32) FlatBvhNode {
    /// The box: min x, y, z rounded down to float, then max x, y, z rounded up.
    float bounds[6] = {};
    /// Leaf: the first index in FlatBvh::primitives. Interior: the index of
    /// the second child (the first child follows the node).
    uint32_t offset = 0;
    uint16_t count = 0;  ///< leaf: number of primitives (>= 1); interior: 0
    uint8_t axis = 0;    ///< interior: the split axis (0, 1, 2); leaf: 0
    uint8_t pad = 0;     ///< unused

    bool is_leaf() const { return count > 0; }
    BBox box() const {
        return BBox(Vec3(bounds[0], bounds[1], bounds[2]), Vec3(bounds[3], bounds[4], bounds[5]));
    }
};
static_assert(sizeof(FlatBvhNode) == 32, "a BVH node must be 32 bytes");

struct FlatBvh {
    std::vector<FlatBvhNode> nodes;  ///< depth-first; nodes[0] is the root; empty for no primitives
    std::vector<uint32_t> primitives;  ///< primitive ids, grouped by leaf in depth-first order
    int depth = 0;                     ///< deepest leaf (the root alone: 0)
    BvhSplit split = BvhSplit::sah;    ///< how it was built

    /// Bytes of nodes and primitive references.
    uint64_t bytes() const {
        return nodes.size() * sizeof(FlatBvhNode) + primitives.size() * sizeof(uint32_t);
    }
};

/// Builds the BVH over all primitives of `scene` with `settings.split` and
/// `settings.max_leaf`. Single-threaded. Throws InputError for an unknown split.
FlatBvh build_flat_bvh(const Scene& scene, const AcceleratorSettings& settings);

/// The float box that contains `box`: each bound rounded outward.
void round_box_outward(const BBox& box, float lo[3], float hi[3]);

/// The next float towards +infinity / -infinity, by stepping the bit
/// pattern (pbrt-v3 section 3.9.1), inline: std::nextafter is a library call.
inline float next_float_up(float f) {
    if (f == INFINITY) return f;
    if (f == 0.0f) f = 0.0f;  // -0 steps up like +0
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof f);
    bits = f >= 0 ? bits + 1 : bits - 1;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}
inline float next_float_down(float f) {
    if (f == -INFINITY) return f;
    if (f == 0.0f) f = -0.0f;  // +0 steps down like -0
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof f);
    bits = f > 0 ? bits - 1 : bits + 1;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}
/// x rounded to float towards -infinity / +infinity.
inline float float_down(double x) {
    float f = float(x);
    return double(f) > x ? next_float_down(f) : f;
}
inline float float_up(double x) {
    float f = float(x);
    return double(f) < x ? next_float_up(f) : f;
}

}  // namespace pt
