// Stage `bvh` (Part 2): a bounding volume hierarchy over the scene's
// primitives, so that a ray tests O(log n) boxes and a handful of
// primitives instead of all n primitives.
//
// Build. Each node bounds its primitives with an axis-aligned box and splits
// them into two children. The split is chosen by the surface area heuristic
// (SAH; Goldsmith and Salmon 1987, MacDonald and Booth 1990): a random ray
// that hits the parent box P hits a child box C with probability
// SA(C) / SA(P), so the expected cost of splitting P into L and R is
//     cost(split) = C_trav + C_isect * (SA(L) N_L + SA(R) N_R) / SA(P)
// against cost(leaf) = C_isect * N for making P a leaf of N primitives.
// The reference evaluates it at the boundaries of 16 bins per axis
// (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies",
// IRT 2007; pbrt-v3 section 4.3.2); the student version (CS184) splits at the
// mean centroid of the axis of largest centroid extent.
//
// Traversal. A ray visits a node only when it meets the node's box (the slab
// test: Kay and Kajiya 1986, made robust as in Ize, "Robust BVH Ray
// Traversal", JCGT 2013), children nearest first, and tests the primitives
// of the leaves it reaches. Closest hit keeps shrinking ray.t_max to the
// nearest hit so far; any hit (shadow rays) stops at the first hit.
//
// Ties: when two primitives are hit at exactly the same t (a ray through a
// shared edge), every accelerator returns the one with the larger id, as the
// linear scan does (it keeps the last of equal hits), so that all of them
// give the same image.
//
// This header is the student's contract (CS184's BVHAccel): the tree types
// and the four functions of the handout, declared for both `student` (in
// assignments/part2/bvh.cpp) and `reference` (stages/bvh_tree.cpp, the
// grader's answer key). The engine's own fast BVH is in stages/flat_bvh.h.
//
// Tests: tests/bvh (closest hit and any hit against the linear scan on
// 100,000 rays per mesh, including rays through vertices, along edges and
// along box faces with +0.0 and -0.0 direction components; structural
// invariants; degenerate inputs; the student fallback's image).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/bbox.h"
#include "core/ray.h"
#include "stages/accelerator.h"
#include "stages/intersect.h"

namespace pt {

struct Scene;
struct AcceleratorSettings;

/// The bounds a BVH uses for primitive `prim`: Scene::primitive_bounds
/// grown on every side by 2^-32 times its largest coordinate magnitude.
/// Moller-Trumbore is not watertight: rounding lets it report hits up to
/// about gamma(7) |o - p0| / cos(theta) outside the triangle (a ray through a
/// shared vertex can hit a triangle a few ulps beyond its exact box). The
/// margin keeps every such hit inside its box for ray origins up to about
/// 10^5 times the primitive's coordinates away (tests/bvh), at no
/// measurable cost in culling.
BBox padded_primitive_bounds(const Scene& scene, uint32_t prim);

/// A primitive as construct_bvh sees it: its id and its bounds.
struct BVHPrimitive {
    uint32_t id = 0;  ///< primitive id in the scene (triangles first, then spheres)
    BBox bb;          ///< world-space bounds of the primitive (padded_primitive_bounds)
    Vec3 centroid;    ///< centre of bb: the point that decides the side of a split
};

/// A node of the student's BVH (CS184's BVHNode): a box, and either two
/// children (an interior node) or none (a leaf).
struct BVHNode {
    BBox bb;                     ///< bounds of every primitive below this node
    std::unique_ptr<BVHNode> l;  ///< left child; null in a leaf
    std::unique_ptr<BVHNode> r;  ///< right child; null in a leaf
    size_t start = 0;            ///< the node's primitives are primitives[start, end)
    size_t end = 0;              ///< one past the last primitive of the node

    bool is_leaf() const { return !l && !r; }
};

/// A built student-style BVH: the primitive list that construct_bvh
/// reordered, its root, and how to intersect one primitive.
class BVHTree {
  public:
    BVHTree(const Scene& scene, const IntersectStage& stage);

    /// The closest hit of `ray` with primitives[i] within [ray.t_min,
    /// ray.t_max], through the intersect stage (student or reference);
    /// sets Hit::primitive. Counts one primitive test.
    std::optional<Hit> intersect_primitive(size_t i, const Ray& ray) const;

    /// Whether a hit `candidate` should replace `best` as the closest hit:
    /// nearer, or as near with a larger primitive id (see "Ties" above).
    static bool closer(const Hit& candidate, const std::optional<Hit>& best) {
        return !best || candidate.t < best->t ||
               (candidate.t == best->t && candidate.primitive > best->primitive);
    }

    std::vector<BVHPrimitive> primitives;  ///< reordered by construct_bvh
    std::unique_ptr<BVHNode> root;         ///< set by construct_bvh

  private:
    const Scene& scene_;
    IntersectStage stage_;
};

using ConstructBvhFn = std::unique_ptr<BVHNode> (*)(std::vector<BVHPrimitive>& primitives,
                                                    size_t start, size_t end, size_t max_leaf_size);
using BboxIntersectFn = bool (*)(const BBox& box, const Ray& ray, double& t0, double& t1);
using BvhIntersectFn = std::optional<Hit> (*)(const BVHTree& bvh, const Ray& ray,
                                              const BVHNode* node);
using BvhHasIntersectionFn = bool (*)(const BVHTree& bvh, const Ray& ray, const BVHNode* node);

/// The four functions of the handout, from one side (student or reference).
struct BvhFunctions {
    /// Builds the subtree over primitives[start, end) (reordering that
    /// range) and returns its root. A node with at most max_leaf_size
    /// primitives is a leaf; otherwise it splits at the mean centroid along
    /// the axis where the centroids spread most. Never returns null.
    ConstructBvhFn construct_bvh;
    /// Slab test. On entry [t0, t1] is the interval of ray parameters to
    /// consider. Returns whether the ray is inside `box` for some t in
    /// [t0, t1], and then narrows t0 and t1 to the first and last such t.
    /// Must handle zero direction components (the ray is parallel to a
    /// slab). On a miss t0 and t1 are unspecified.
    BboxIntersectFn bbox_intersect;
    /// The closest hit of `ray` within [ray.t_min, ray.t_max] with the
    /// primitives under `node`, with Hit::primitive set; nothing on a miss.
    BvhIntersectFn bvh_intersect;
    /// Whether `ray` hits any primitive under `node` within [ray.t_min,
    /// ray.t_max] (shadow rays); may stop at the first hit found.
    BvhHasIntersectionFn bvh_has_intersection;
};

namespace reference {
std::unique_ptr<BVHNode> construct_bvh(std::vector<BVHPrimitive>& primitives, size_t start,
                                       size_t end, size_t max_leaf_size);
bool bbox_intersect(const BBox& box, const Ray& ray, double& t0, double& t1);
std::optional<Hit> bvh_intersect(const BVHTree& bvh, const Ray& ray, const BVHNode* node);
bool bvh_has_intersection(const BVHTree& bvh, const Ray& ray, const BVHNode* node);
/// The reference side of the table above.
BvhFunctions tree_functions();
}  // namespace reference

namespace student {
std::unique_ptr<BVHNode> construct_bvh(std::vector<BVHPrimitive>& primitives, size_t start,
                                       size_t end, size_t max_leaf_size);
bool bbox_intersect(const BBox& box, const Ray& ray, double& t0, double& t1);
std::optional<Hit> bvh_intersect(const BVHTree& bvh, const Ray& ray, const BVHNode* node);
bool bvh_has_intersection(const BVHTree& bvh, const Ray& ray, const BVHNode* node);
/// The student side of the table above.
BvhFunctions tree_functions();
}  // namespace student

/// The accelerator of a student-style BVH built and queried by `functions`
/// (the `bvh` stage when it is a student stage; with the reference
/// functions, the grader's answer key). --max-leaf applies; --bvh-split
/// does not (the handout prescribes its split).
std::unique_ptr<Accelerator> make_tree_bvh(const Scene& scene, const IntersectStage& stage,
                                           const AcceleratorSettings& settings,
                                           const BvhFunctions& functions);

/// The engine's BVH (stages/flat_bvh.h): binned SAH, flat 32-byte nodes,
/// ordered traversal. When `stage` holds the reference triangle routine,
/// it tests triangles with an inlined copy of it (same bits, no call).
std::unique_ptr<Accelerator> make_reference_bvh(const Scene& scene, const IntersectStage& stage,
                                                const AcceleratorSettings& settings);

/// What the BVH visualisation needs from any BVH: the node at a path of
/// L/R steps from the root ("" is the root, "R" its right child, ...).
struct BvhNodeView {
    BBox box;                          ///< the node's bounding box
    std::vector<uint32_t> primitives;  ///< ids of all primitives below the node
    bool leaf = false;                 ///< whether the node is a leaf
};

class InspectableBvh {
  public:
    virtual ~InspectableBvh() = default;
    /// The node at `path`; nothing when the path leads below a leaf.
    virtual std::optional<BvhNodeView> node_at(const std::string& path) const = 0;
};

}  // namespace pt
