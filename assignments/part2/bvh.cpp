// Part 2, tasks 1 to 4: build a BVH and trace rays through it.
// Read assignments/part2/README.md first; the contract of each function is
// in src/stages/bvh.h (BvhFunctions).
//
// Until you write them, construct_bvh makes one leaf of everything and the
// two traversal functions test every primitive (a correct linear scan), so
// `part2` renders the right image, only slowly, and says so once
// (stub_fallback; `grade` counts a fallback as "not implemented"). Remove
// the stub_fallback line when you write the function. bbox_intersect has no
// such fallback: it stops the program with "not implemented" when called.
#include "stages/bvh.h"
#include "core/error.h"
#include "core/stub_fallback.h"

namespace pt::student {

std::unique_ptr<BVHNode> construct_bvh(std::vector<BVHPrimitive>& primitives, size_t start,
                                       size_t end, size_t max_leaf_size) {
    // TODO(part2.1): construct_bvh, as src/stages/bvh.h states its contract.
    // [guided]
    // build the BVH over primitives[start, end).
    //  1. Compute the node's box (the union of the primitives' boxes) and the
    //     box of their centroids.
    //  2. If there are at most max_leaf_size primitives, return a leaf
    //     (start and end set, no children).
    //  3. Otherwise pick the axis along which the centroid box is longest,
    //     split at the mean centroid along that axis (std::partition), and
    //     build the left and right children recursively. If every primitive
    //     lands on one side, split the range in half instead, or the
    //     recursion never ends.
    // Until then: a single leaf holding every primitive.
    // [/guided]
    (void)max_leaf_size;
    stub_fallback(2, "1", "construct_bvh", "one leaf of every primitive");
    auto node = std::make_unique<BVHNode>();
    for (size_t i = start; i < end; ++i)
        node->bb.expand(primitives[i].bb);
    node->start = start;
    node->end = end;
    return node;
}

bool bbox_intersect(const BBox& box, const Ray& ray, double& t0, double& t1) {
    // TODO(part2.2): bbox_intersect, as src/stages/bvh.h states its contract.
    // [guided]
    // the slab test. For each axis, the ray enters and leaves
    // the slab between box.min and box.max at (box.min - o) / d and
    // (box.max - o) / d (swap them when d < 0). The ray is inside the box
    // between the largest entry and the smallest exit; intersect that with
    // [t0, t1], store it in t0 and t1, and return whether it is non-empty.
    // A zero component of d makes 1/d infinite: check what your code does
    // then, with the origin inside the slab, outside it, and on its plane.
    // [/guided]
    (void)box, (void)ray, (void)t0, (void)t1;
    throw NotImplemented(2, "2", "bbox_intersect");
}

std::optional<Hit> bvh_intersect(const BVHTree& bvh, const Ray& ray, const BVHNode* node) {
    // TODO(part2.3): bvh_intersect, as src/stages/bvh.h states its contract.
    // [guided]
    // the closest hit under `node`. If the ray misses the
    // node's box within [ray.t_min, ray.t_max], there is none. In a leaf,
    // test primitives[node->start, node->end) with bvh.intersect_primitive
    // and keep the closest (BVHTree::closer). Otherwise ask both children
    // and return the closer of their hits.
    // Until then: a linear scan over every primitive.
    // [/guided]
    (void)node;
    stub_fallback(2, "3", "bvh_intersect", "a linear scan");
    std::optional<Hit> best;
    Ray r = ray;
    for (size_t i = 0; i < bvh.primitives.size(); ++i) {
        std::optional<Hit> hit = bvh.intersect_primitive(i, r);
        if (hit && BVHTree::closer(*hit, best)) {
            best = hit;
            r.t_max = hit->t;
        }
    }
    return best;
}

bool bvh_has_intersection(const BVHTree& bvh, const Ray& ray, const BVHNode* node) {
    // TODO(part2.4): bvh_has_intersection, as src/stages/bvh.h states its contract.
    // [guided]
    // like bvh_intersect, but return true at the first hit
    // found: shadow rays only need to know whether anything blocks them.
    // Until then: a linear scan over every primitive.
    // [/guided]
    (void)node;
    stub_fallback(2, "4", "bvh_has_intersection", "a linear scan");
    for (size_t i = 0; i < bvh.primitives.size(); ++i)
        if (bvh.intersect_primitive(i, ray)) return true;
    return false;
}

}  // namespace pt::student
