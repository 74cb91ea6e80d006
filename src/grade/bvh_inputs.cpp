#include "grade/bvh_inputs.h"

#include <stdexcept>

#include "grade/random_inputs.h"
#include "scene/scene_loader.h"

namespace pt {

Scene load_graded_scene(const GradeEnvironment& env, const std::string& path) {
    return load_scene(env.assets_dir + "/" + path);
}

std::vector<Ray> scene_rays(const Scene& scene, const Stages& reference, int count, Rng& rng) {
    std::vector<Ray> rays;
    BBox b = scene.bounds;
    Vec3 lo = b.min - b.extent() * 0.1, hi = b.max + b.extent() * 0.1;
    for (int i = 0; i < count; ++i) {
        if (i % 2 == 0) {
            Vec3 o(uniform(rng, lo.x, hi.x), uniform(rng, lo.y, hi.y), uniform(rng, lo.z, hi.z));
            rays.emplace_back(o, random_unit(rng));
        } else {
            rays.push_back(reference.camera.generate_ray(scene.camera, rng.next_1d(), rng.next_1d(),
                                                         rng.next_2d()));
        }
    }
    return rays;
}

std::vector<BVHPrimitive> tree_primitives(const Scene& scene) {
    std::vector<BVHPrimitive> primitives(scene.primitive_count());
    for (uint32_t i = 0; i < primitives.size(); ++i) {
        primitives[i].id = i;
        primitives[i].bb = padded_primitive_bounds(scene, i);
        primitives[i].centroid = primitives[i].bb.centroid();
    }
    return primitives;
}

std::unique_ptr<BVHTree> build_tree(const Scene& scene, const IntersectStage& intersect,
                                    ConstructBvhFn construct, size_t max_leaf) {
    auto tree = std::make_unique<BVHTree>(scene, intersect);
    tree->primitives = tree_primitives(scene);
    tree->root = construct(tree->primitives, 0, tree->primitives.size(), max_leaf);
    if (!tree->root) throw std::runtime_error("construct_bvh returned a null node");
    return tree;
}

std::vector<const BVHNode*> tree_nodes(const BVHNode* root) {
    std::vector<const BVHNode*> nodes, stack;
    if (root) stack.push_back(root);
    while (!stack.empty()) {
        const BVHNode* n = stack.back();
        stack.pop_back();
        nodes.push_back(n);
        if (n->r) stack.push_back(n->r.get());
        if (n->l) stack.push_back(n->l.get());
    }
    return nodes;
}

std::vector<size_t> primitives_under(const BVHNode* node) {
    std::vector<size_t> indices;
    for (const BVHNode* n : tree_nodes(node))
        if (n->is_leaf())
            for (size_t i = n->start; i < n->end; ++i)
                indices.push_back(i);
    return indices;
}

std::optional<Hit> brute_force_closest(const BVHTree& tree, const std::vector<size_t>& indices,
                                       const Ray& ray) {
    std::optional<Hit> best;
    for (size_t i : indices) {
        std::optional<Hit> hit = tree.intersect_primitive(i, ray);
        if (hit && BVHTree::closer(*hit, best)) best = hit;
    }
    return best;
}

bool brute_force_any(const BVHTree& tree, const std::vector<size_t>& indices, const Ray& ray) {
    for (size_t i : indices)
        if (tree.intersect_primitive(i, ray)) return true;
    return false;
}

}  // namespace pt
