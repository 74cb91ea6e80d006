// Part 2, written from the README's steps.
#include <algorithm>

#include "stages/bvh.h"

namespace pt::student {

std::unique_ptr<BVHNode> construct_bvh(std::vector<BVHPrimitive>& primitives, size_t start,
                                       size_t end, size_t max_leaf_size) {
    auto node = std::make_unique<BVHNode>();
    BBox centroids;
    for (size_t i = start; i < end; ++i) {
        node->bb.expand(primitives[i].bb);
        centroids.expand(BBox(primitives[i].centroid, primitives[i].centroid));
    }
    node->start = start, node->end = end;
    if (end - start <= max_leaf_size) return node;
    Vec3 e = centroids.extent();
    int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
    double mean = 0;
    for (size_t i = start; i < end; ++i)
        mean += primitives[i].centroid[axis] / double(end - start);
    auto split = std::partition(primitives.begin() + long(start), primitives.begin() + long(end),
                                [&](const BVHPrimitive& p) { return p.centroid[axis] < mean; });
    size_t mid = size_t(split - primitives.begin());
    if (mid == start || mid == end) mid = start + (end - start) / 2;
    node->l = construct_bvh(primitives, start, mid, max_leaf_size);
    node->r = construct_bvh(primitives, mid, end, max_leaf_size);
    return node;
}

bool bbox_intersect(const BBox& box, const Ray& ray, double& t0, double& t1) {
    double entry = t0, exit = t1;
    for (int a = 0; a < 3; ++a) {
        double o = ray.o[a], d = ray.d[a];
        if (d == 0) {  // parallel to the slab: inside it for every t, or never
            if (o < box.min[a] || o > box.max[a]) return false;
            continue;
        }
        double near = (box.min[a] - o) / d, far = (box.max[a] - o) / d;
        if (d < 0) std::swap(near, far);
        entry = std::max(entry, near);
        exit = std::min(exit, far);
    }
    if (!(entry <= exit)) return false;
    t0 = entry, t1 = exit;
    return true;
}

std::optional<Hit> bvh_intersect(const BVHTree& bvh, const Ray& ray, const BVHNode* node) {
    double t0 = ray.t_min, t1 = ray.t_max;
    if (!bbox_intersect(node->bb, ray, t0, t1)) return std::nullopt;
    std::optional<Hit> best;
    if (node->is_leaf()) {
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
    best = bvh_intersect(bvh, ray, node->l.get());
    Ray r = ray;
    if (best) r.t_max = best->t;
    std::optional<Hit> right = bvh_intersect(bvh, r, node->r.get());
    if (right && BVHTree::closer(*right, best)) best = right;
    return best;
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

}  // namespace pt::student
