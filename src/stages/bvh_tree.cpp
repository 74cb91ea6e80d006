// The student-style (CS184) BVH: a tree of BVHNode built and queried by the
// four functions of stages/bvh.h. Here are the reference versions of those
// functions (the grader's answer key: plain, recursive, as the handout
// describes them, but robust) and the accelerator that runs either side.
#include <cfloat>
#include <cmath>
#include <stdexcept>

#include "core/counters.h"
#include "core/math.h"
#include "scene/scene.h"
#include "stages/bvh.h"
#include "stages/stages.h"

namespace pt {

BBox padded_primitive_bounds(const Scene& scene, uint32_t prim) {
    BBox b = scene.primitive_bounds(prim);
    double scale = std::max(max_component(abs(b.min)), max_component(abs(b.max)));
    Vec3 margin(std::ldexp(scale, -32));
    return BBox(b.min - margin, b.max + margin);
}

BVHTree::BVHTree(const Scene& scene, const IntersectStage& stage) : scene_(scene), stage_(stage) {}

std::optional<Hit> BVHTree::intersect_primitive(size_t i, const Ray& ray) const {
    ++thread_counters().primitive_tests;
    return pt::intersect_primitive(scene_, stage_, primitives[i].id, ray);
}

namespace reference {

std::unique_ptr<BVHNode> construct_bvh(std::vector<BVHPrimitive>& primitives, size_t start,
                                       size_t end, size_t max_leaf_size) {
    auto node = std::make_unique<BVHNode>();
    node->start = start;
    node->end = end;
    BBox centroids;
    for (size_t i = start; i < end; ++i) {
        node->bb.expand(primitives[i].bb);
        centroids.expand(primitives[i].centroid);
    }
    const size_t n = end - start;
    if (n <= max_leaf_size) return node;

    // Split at the mean centroid along the axis where centroids spread most.
    int axis = max_dimension(centroids.extent());
    double mean = 0;
    for (size_t i = start; i < end; ++i)
        mean += primitives[i].centroid[axis] / double(n);
    auto first = primitives.begin() + long(start), last = primitives.begin() + long(end);
    auto mid =
        std::partition(first, last, [&](const BVHPrimitive& p) { return p.centroid[axis] < mean; });
    // All centroids on one side (they coincide, or rounding put the mean on
    // the largest): halve the list so that the recursion always ends.
    if (mid == first || mid == last) mid = first + long(n / 2);
    size_t split = size_t(mid - primitives.begin());
    node->l = construct_bvh(primitives, start, split, max_leaf_size);
    node->r = construct_bvh(primitives, split, end, max_leaf_size);
    return node;
}

bool bbox_intersect(const BBox& box, const Ray& ray, double& t0, double& t1) {
    // Far distances and t1 get the rounding allowance of the reference
    // slab test (stages/bvh_traverse.cpp): never miss a box the ray enters.
    const double far_scale = 1.0 + 2.0 * gamma(6);
    t1 = std::min(t1 * far_scale, DBL_MAX);
    for (int a = 0; a < 3; ++a) {
        double inv = 1.0 / ray.d[a];  // +-inf for a +-0 component
        double t_near = (box.min[a] - ray.o[a]) * inv;
        double t_far = (box.max[a] - ray.o[a]) * inv;
        if (std::signbit(inv)) std::swap(t_near, t_far);
        t_far *= far_scale;
        // NaN (0 * inf: the ray lies in this slab's plane) fails both
        // comparisons and leaves the interval unchanged.
        if (t_near > t0) t0 = t_near;
        if (t_far < t1) t1 = t_far;
    }
    return t0 <= t1;
}

std::optional<Hit> bvh_intersect(const BVHTree& bvh, const Ray& ray, const BVHNode* node) {
    double t0 = ray.t_min, t1 = ray.t_max;
    if (!bbox_intersect(node->bb, ray, t0, t1)) return std::nullopt;
    if (node->is_leaf()) {
        std::optional<Hit> best;
        Ray r = ray;
        for (size_t i = node->start; i < node->end; ++i) {
            std::optional<Hit> hit = bvh.intersect_primitive(i, r);
            if (hit && BVHTree::closer(*hit, best)) {
                best = hit;
                r.t_max = hit->t;
            }
        }
        return best;
    }
    std::optional<Hit> left = bvh_intersect(bvh, ray, node->l.get());
    Ray r = ray;
    if (left) r.t_max = left->t;  // the right subtree need not look past the left's hit
    std::optional<Hit> right = bvh_intersect(bvh, r, node->r.get());
    return right && BVHTree::closer(*right, left) ? right : left;
}

bool bvh_has_intersection(const BVHTree& bvh, const Ray& ray, const BVHNode* node) {
    double t0 = ray.t_min, t1 = ray.t_max;
    if (!bbox_intersect(node->bb, ray, t0, t1)) return false;
    if (node->is_leaf()) {
        for (size_t i = node->start; i < node->end; ++i)
            if (bvh.intersect_primitive(i, ray)) return true;
        return false;
    }
    return bvh_has_intersection(bvh, ray, node->l.get()) ||
           bvh_has_intersection(bvh, ray, node->r.get());
}

BvhFunctions tree_functions() {
    return {construct_bvh, bbox_intersect, bvh_intersect, bvh_has_intersection};
}

}  // namespace reference

namespace student {
BvhFunctions tree_functions() {
    return {construct_bvh, bbox_intersect, bvh_intersect, bvh_has_intersection};
}
}  // namespace student

namespace {

class TreeBvh final : public Accelerator, public InspectableBvh {
  public:
    TreeBvh(const Scene& scene, const IntersectStage& stage, const AcceleratorSettings& settings,
            const BvhFunctions& functions)
        : tree_(scene, stage), functions_(functions) {
        const uint32_t n = scene.primitive_count();
        tree_.primitives.resize(n);
        for (uint32_t i = 0; i < n; ++i) {
            BVHPrimitive& p = tree_.primitives[i];
            p.id = i;
            p.bb = padded_primitive_bounds(scene, i);
            p.centroid = p.bb.centroid();
        }
        if (n == 0) return;
        tree_.root = functions_.construct_bvh(tree_.primitives, 0, n, size_t(settings.max_leaf));
        if (!tree_.root) throw std::runtime_error("Part 2: construct_bvh returned a null node");
        measure();
    }

    std::optional<Hit> intersect(const Ray& ray) const override {
        if (!tree_.root) return std::nullopt;
        return functions_.bvh_intersect(tree_, ray, tree_.root.get());
    }
    bool occluded(const Ray& ray) const override {
        return tree_.root && functions_.bvh_has_intersection(tree_, ray, tree_.root.get());
    }
    AcceleratorInfo info() const override { return {"bvh-tree", nodes_, depth_, bytes_, bytes_}; }

    std::optional<BvhNodeView> node_at(const std::string& path) const override {
        const BVHNode* node = tree_.root.get();
        if (!node) return std::nullopt;
        for (char step : path) {
            if (node->is_leaf()) return std::nullopt;
            node = step == 'L' ? node->l.get() : node->r.get();
            if (!node) return std::nullopt;  // a student node with one child
        }
        BvhNodeView view;
        view.box = node->bb;
        view.leaf = node->is_leaf();
        // The leaves' ranges, not the node's own: students need set start
        // and end only in leaves, as in CS184.
        std::vector<const BVHNode*> stack{node};
        while (!stack.empty()) {
            const BVHNode* n = stack.back();
            stack.pop_back();
            if (n->is_leaf()) {
                for (size_t i = n->start; i < n->end && i < tree_.primitives.size(); ++i)
                    view.primitives.push_back(tree_.primitives[i].id);
            }
            if (n->r) stack.push_back(n->r.get());
            if (n->l) stack.push_back(n->l.get());
        }
        return view;
    }

  private:
    /// Node count, depth and memory, without recursion (a student tree may be deep).
    void measure() {
        std::vector<std::pair<const BVHNode*, int>> stack{{tree_.root.get(), 0}};
        while (!stack.empty()) {
            auto [node, depth] = stack.back();
            stack.pop_back();
            ++nodes_;
            depth_ = std::max(depth_, depth);
            if (node->l) stack.push_back({node->l.get(), depth + 1});
            if (node->r) stack.push_back({node->r.get(), depth + 1});
        }
        bytes_ = nodes_ * sizeof(BVHNode) + tree_.primitives.size() * sizeof(BVHPrimitive);
    }

    BVHTree tree_;
    BvhFunctions functions_;
    uint64_t nodes_ = 0;
    int depth_ = 0;
    uint64_t bytes_ = 0;
};

}  // namespace

std::unique_ptr<Accelerator> make_tree_bvh(const Scene& scene, const IntersectStage& stage,
                                           const AcceleratorSettings& settings,
                                           const BvhFunctions& functions) {
    return std::make_unique<TreeBvh>(scene, stage, settings, functions);
}

}  // namespace pt
