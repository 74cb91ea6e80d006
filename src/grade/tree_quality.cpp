#include "grade/tree_quality.h"

#include <algorithm>
#include <utility>

#include "grade/random_inputs.h"

namespace pt {
namespace {

double surface_area(const BBox& b) {
    if (!(b.min.x <= b.max.x && b.min.y <= b.max.y && b.min.z <= b.max.z)) return 0;  // empty
    Vec3 e = b.extent();
    return 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

}  // namespace

std::optional<Hit> fixed_closest_hit(const BVHTree& tree, const Ray& ray, size_t& visited,
                                     size_t& tests) {
    // An explicit stack: a bad tree may be thousands of levels deep.
    Ray r = ray;
    std::optional<Hit> best;
    std::vector<const BVHNode*> stack;
    if (tree.root) stack.push_back(tree.root.get());
    while (!stack.empty()) {
        const BVHNode* node = stack.back();
        stack.pop_back();
        ++visited;
        double t0 = r.t_min, t1 = r.t_max;
        if (!reference::bbox_intersect(node->bb, r, t0, t1)) continue;
        if (node->is_leaf()) {
            // A recorded tree comes from the student: ranges outside the list are skipped.
            const size_t end = std::min(node->end, tree.primitives.size());
            for (size_t i = node->start; i < end; ++i) {
                ++tests;
                std::optional<Hit> hit = tree.intersect_primitive(i, r);
                if (hit && BVHTree::closer(*hit, best)) {
                    best = hit;
                    r.t_max = hit->t;
                }
            }
            continue;
        }
        if (!node->l || !node->r) {  // one child: a broken student tree
            stack.push_back(node->l ? node->l.get() : node->r.get());
            continue;
        }
        // Nearer child first: push it last. Entry t of each child box.
        double a0 = r.t_min, a1 = r.t_max, b0 = r.t_min, b1 = r.t_max;
        bool hit_l = reference::bbox_intersect(node->l->bb, r, a0, a1);
        bool hit_r = reference::bbox_intersect(node->r->bb, r, b0, b1);
        const BVHNode* first = node->l.get();
        const BVHNode* second = node->r.get();
        if (hit_r && (!hit_l || b0 < a0)) std::swap(first, second);
        stack.push_back(second);
        stack.push_back(first);
    }
    return best;
}

std::vector<Ray> incoherent_rays(const BBox& bounds, int count, Rng& rng) {
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        Vec3 o(uniform(rng, bounds.min.x, bounds.max.x), uniform(rng, bounds.min.y, bounds.max.y),
               uniform(rng, bounds.min.z, bounds.max.z));
        rays.emplace_back(o, random_unit(rng));
    }
    return rays;
}

TreeQuality measure_tree_quality(const BVHTree& tree, const std::vector<Ray>& rays) {
    TreeQuality q;
    if (!tree.root) return q;
    const double root_area = std::max(surface_area(tree.root->bb), 1e-300);
    std::vector<std::pair<const BVHNode*, int>> stack{{tree.root.get(), 0}};
    while (!stack.empty()) {
        auto [node, depth] = stack.back();
        stack.pop_back();
        q.depth = std::max(q.depth, depth);
        const double share = surface_area(node->bb) / root_area;
        if (node->is_leaf()) {
            q.sah_cost += share * double(node->end > node->start ? node->end - node->start : 0);
        } else {
            q.sah_cost += share;
            for (const BVHNode* child : {node->l.get(), node->r.get()})
                if (child) stack.push_back({child, depth + 1});
        }
    }
    size_t visited = 0, tests = 0;
    for (const Ray& ray : rays)
        fixed_closest_hit(tree, ray, visited, tests);
    q.nodes_per_ray = rays.empty() ? 0 : double(visited) / double(rays.size());
    return q;
}

}  // namespace pt
