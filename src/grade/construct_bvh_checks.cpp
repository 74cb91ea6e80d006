// Part 2, construct_bvh: the structure of the student's tree, on the graded
// scenes and on synthetic primitive lists chosen for the cases that break
// builders (equal centroids, collinear and exponentially spaced centroids,
// a huge box among tiny ones, one to three primitives). The tree is then
// traversed by the reference bvh_intersect and must find the same hits as
// the linear scan (a brute-force check of the whole build).
#include <algorithm>
#include <cmath>

#include "grade/bvh_inputs.h"
#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"

namespace pt {
namespace {

bool same_box(const BBox& a, const BBox& b) {
    return a.min == b.min && a.max == b.max;
}

std::string range_text(size_t start, size_t end) {
    return "[" + std::to_string(start) + ", " + std::to_string(end) + ")";
}

/// Sizes of a tree that passed, for the report.
struct TreeFacts {
    size_t nodes = 0, leaves = 0, depth = 0;
    size_t full_leaves = 0;  ///< leaves over max_leaf whose centroids all coincide (accepted)
};

/// "" when the tree built over `input` (now reordered into `output`) keeps
/// every invariant of stages/bvh.h, else the first one it breaks. Nodes are
/// named by their path of L/R steps from the root, as --bvh-view takes it.
std::string check_structure(const std::vector<BVHPrimitive>& input,
                            const std::vector<BVHPrimitive>& output, const BVHNode* root,
                            size_t max_leaf, TreeFacts* facts) {
    const size_t n = input.size();
    if (!root) return "construct_bvh returned a null node";
    if (output.size() != n)
        return "the primitive list has " + std::to_string(output.size()) +
               " entries after the build instead of " + std::to_string(n) +
               " (construct_bvh may reorder it, not add or drop entries)";
    std::vector<int> copies(n, 0);
    for (size_t k = 0; k < n; ++k) {
        const BVHPrimitive& p = output[k];
        if (p.id >= n)
            return "entry " + std::to_string(k) + " holds an unknown id " + std::to_string(p.id);
        if (!same_box(p.bb, input[p.id].bb) || !(p.centroid == input[p.id].centroid))
            return "entry " + std::to_string(k) + " (primitive " + std::to_string(p.id) +
                   ") has a box or centroid that differs from the one it was given";
        ++copies[p.id];
    }
    for (size_t id = 0; id < n; ++id)
        if (copies[id] != 1)
            return "primitive " + std::to_string(id) + " appears " + std::to_string(copies[id]) +
                   " times in the reordered list";

    std::vector<int> in_leaves(n, 0);
    std::vector<std::pair<const BVHNode*, std::string>> stack{{root, ""}};
    while (!stack.empty()) {
        auto [node, path] = stack.back();
        stack.pop_back();
        const std::string where = "node \"" + path + "\"" + (path.empty() ? " (the root)" : "");
        ++facts->nodes;
        facts->depth = std::max(facts->depth, path.size());
        if (bool(node->l) != bool(node->r))
            return where + " has only a " + (node->l ? "left" : "right") +
                   " child: an interior node needs both, a leaf neither";
        if (node->is_leaf()) {
            ++facts->leaves;
            if (node->start > node->end || node->end > n)
                return where + " is a leaf with range " + range_text(node->start, node->end) +
                       " outside the " + std::to_string(n) + " primitives";
            bool equal_centroids = true;
            for (size_t i = node->start; i < node->end; ++i) {
                ++in_leaves[i];
                if (!node->bb.contains(output[i].bb))
                    return where + ": the leaf's box " + format_vec(node->bb.min) + " .. " +
                           format_vec(node->bb.max) + " does not contain the box of primitive " +
                           std::to_string(output[i].id) + ", " + format_vec(output[i].bb.min) +
                           " .. " + format_vec(output[i].bb.max);
                equal_centroids =
                    equal_centroids && output[i].centroid == output[node->start].centroid;
            }
            size_t size = node->end - node->start;
            if (size > max_leaf) {
                if (!equal_centroids)
                    return where + " is a leaf of " + std::to_string(size) +
                           " primitives, more than max_leaf_size = " + std::to_string(max_leaf) +
                           ", and their centroids differ (it can be split)";
                ++facts->full_leaves;  // no split by centroids exists: accepted
            }
            continue;
        }
        for (const auto& [child, step] : {std::pair{node->l.get(), 'L'}, {node->r.get(), 'R'}}) {
            if (!node->bb.contains(child->bb))
                return where + ": the box of its child \"" + path + step + "\", " +
                       format_vec(child->bb.min) + " .. " + format_vec(child->bb.max) +
                       ", is not inside the node's box " + format_vec(node->bb.min) + " .. " +
                       format_vec(node->bb.max);
            stack.push_back({child, path + step});
        }
    }
    for (size_t i = 0; i < n; ++i)
        if (in_leaves[i] != 1)
            return "primitive " + std::to_string(output[i].id) + " (entry " + std::to_string(i) +
                   ") is in " + std::to_string(in_leaves[i]) +
                   " leaves; every primitive must be in exactly one";
    return "";
}

BVHPrimitive primitive(uint32_t id, const Vec3& center, const Vec3& half) {
    BVHPrimitive p;
    p.id = id;
    p.bb = BBox(center - half, center + half);
    p.centroid = p.bb.centroid();
    return p;
}

struct PrimitiveList {
    std::string category, label;
    std::vector<BVHPrimitive> primitives;
    size_t max_leaf = 4;
};

/// The synthetic lists: each a classic way to break a builder.
std::vector<PrimitiveList> synthetic_lists(Rng& rng, int random_lists) {
    std::vector<PrimitiveList> lists;
    auto add = [&](const std::string& category, const std::string& label, size_t max_leaf) {
        lists.push_back({category, label, {}, max_leaf});
        return &lists.back().primitives;
    };
    const size_t leaf_sizes[] = {1, 2, 4, 8};
    for (int k = 0; k < random_lists; ++k) {
        size_t n = size_t(std::lround(log_uniform(rng, 2, 3000)));
        size_t max_leaf = leaf_sizes[rng.next_index(4)];
        double scale = log_uniform(rng, 1e-3, 1e4);
        auto* p = add("random boxes",
                      std::to_string(n) + " random boxes at scale " + format_num(scale), max_leaf);
        for (uint32_t i = 0; i < n; ++i)
            p->push_back(primitive(
                i, random_in_cube(rng) * scale,
                Vec3(log_uniform(rng, 1e-4, 0.1) * scale, log_uniform(rng, 1e-4, 0.1) * scale,
                     log_uniform(rng, 1e-4, 0.1) * scale)));
        if (k % 3 == 2)  // flat boxes in the plane z = 0, as a wall's triangles have
            for (BVHPrimitive& q : *p)
                q = primitive(q.id, Vec3(q.centroid.x, q.centroid.y, 0),
                              Vec3(q.bb.extent().x / 2, q.bb.extent().y / 2, 0));
    }
    auto* same = add("equal centroids", "40 copies of one box", 4);
    for (uint32_t i = 0; i < 40; ++i)
        same->push_back(primitive(i, Vec3(1, 2, 3), Vec3(0.5)));
    auto* two = add("equal centroids", "two groups of 30 boxes with equal centroids", 4);
    for (uint32_t i = 0; i < 60; ++i)
        two->push_back(primitive(i, i < 30 ? Vec3(-5, 0, 0) : Vec3(5, 1, 0), Vec3(0.5 + i % 3)));
    auto* column = add("equal centroids", "100 boxes with equal x and y, spread in z", 2);
    for (uint32_t i = 0; i < 100; ++i)
        column->push_back(primitive(i, Vec3(7, 7, uniform(rng, -50, 50)), Vec3(1, 1, 0.1)));
    auto* line = add("collinear", "200 boxes evenly spaced on a diagonal", 4);
    for (uint32_t i = 0; i < 200; ++i)
        line->push_back(primitive(i, Vec3(i, 2.0 * i, -0.5 * i), Vec3(0.25)));
    auto* powers = add("exponential spacing", "60 boxes at x = 2^k", 1);
    for (uint32_t i = 0; i < 60; ++i)
        powers->push_back(primitive(i, Vec3(std::ldexp(1.0, int(i)), 0, 0), Vec3(0.5)));
    auto* mixed = add("mixed sizes", "a box of size 10^6 among 100 boxes of size 10^-3", 4);
    mixed->push_back(primitive(0, Vec3(0), Vec3(1e6)));
    for (uint32_t i = 1; i <= 100; ++i)
        mixed->push_back(primitive(i, random_in_cube(rng) * 10.0, Vec3(1e-3)));
    auto* outlier = add("mixed sizes", "two clusters of 50 and one outlier far away", 4);
    for (uint32_t i = 0; i < 101; ++i) {
        Vec3 c = i == 100 ? Vec3(1e5, -1e5, 1e5) : random_in_cube(rng) + Vec3(i < 50 ? -10 : 10);
        outlier->push_back(primitive(i, c, Vec3(0.1)));
    }
    for (size_t n = 1; n <= 3; ++n) {
        auto* few = add("few primitives", std::to_string(n) + " primitives, max_leaf_size 1", 1);
        for (uint32_t i = 0; i < n; ++i)
            few->push_back(primitive(i, Vec3(i, -double(i), 0.5 * i), Vec3(0.5)));
    }
    return lists;
}

std::string facts_text(const TreeFacts& f) {
    return std::to_string(f.nodes) + " nodes, " + std::to_string(f.leaves) + " leaves, depth " +
           std::to_string(f.depth) +
           (f.full_leaves ? ", " + std::to_string(f.full_leaves) +
                                " leaves over max_leaf_size with equal centroids (accepted)"
                          : "");
}

}  // namespace

TaskResult check_construct_bvh(const TaskSpec& spec, const GradeEnvironment& env) {
    const ConstructBvhFn construct = env.student.bvh.tree.construct_bvh;
    const BvhFunctions reference = env.reference.bvh.tree;
    const size_t max_leaf = size_t(param(spec, "max_leaf", 4));
    const int rays = param(spec, "rays", 500);
    const double tol = param(spec, "rel_tol", 1e-9);
    std::vector<std::string> scenes =
        param(spec, "scenes",
              std::vector<std::string>{"scenes/cbox_spheres.json", "scenes/cbox_knot.json"});
    Rng rng = check_rng(env.seed, "construct_bvh");
    CaseLog log;
    std::vector<std::string> facts;

    for (const std::string& path : scenes) {
        Scene scene = load_graded_scene(env, path);
        const std::string label = path + " (" + std::to_string(scene.primitive_count()) +
                                  " primitives, max_leaf_size " + std::to_string(max_leaf) + ")";
        log.category("scenes");
        std::unique_ptr<BVHTree> tree =
            build_tree(scene, env.reference.intersect, construct, max_leaf);
        TreeFacts f;
        std::string problem = check_structure(tree_primitives(scene), tree->primitives,
                                              tree->root.get(), max_leaf, &f);
        if (!problem.empty()) {
            log.mismatch(label + ": " + problem);
            continue;
        }
        log.agreed();
        facts.push_back(label + ": " + facts_text(f));
        // The whole build against brute force: the reference traversal over
        // the student's tree finds what the linear scan finds.
        log.category("traversal of the tree by the reference bvh_intersect");
        std::unique_ptr<Accelerator> linear = make_linear_scan(scene, env.reference.intersect);
        for (const Ray& ray : scene_rays(scene, env.reference, rays, rng)) {
            std::optional<Hit> want = linear->intersect(ray);
            std::optional<Hit> got = reference.bvh_intersect(*tree, ray, tree->root.get());
            if (bool(want) == bool(got) &&
                (!want || std::fabs(got->t - want->t) <= tol * std::max(1.0, want->t))) {
                log.agreed();
            } else {
                log.mismatch(label + ": ray o = " + format_vec(ray.o) +
                             " d = " + format_vec(ray.d) + ": the tree gives " +
                             (got ? "t = " + format_num(got->t) : std::string("a miss")) +
                             ", the linear scan " +
                             (want ? "t = " + format_num(want->t) : std::string("a miss")));
            }
        }
    }
    size_t lists = 0;
    for (PrimitiveList& list : synthetic_lists(rng, param(spec, "random_lists", 12))) {
        ++lists;
        log.category(list.category);
        std::vector<BVHPrimitive> primitives = list.primitives;
        std::unique_ptr<BVHNode> root = construct(primitives, 0, primitives.size(), list.max_leaf);
        TreeFacts f;
        std::string problem =
            check_structure(list.primitives, primitives, root.get(), list.max_leaf, &f);
        if (problem.empty())
            log.agreed();
        else
            log.mismatch(list.label + ", max_leaf_size " + std::to_string(list.max_leaf) + ": " +
                         problem);
    }
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0),
                              "the invariants of a BVH and the linear scan");
    if (r.status == TaskStatus::pass)
        r.message = "every tree keeps the invariants of a BVH (" + std::to_string(scenes.size()) +
                    " scenes, " + std::to_string(lists) +
                    " synthetic primitive lists), and the reference traversal of the scene trees "
                    "agrees with the linear scan on " +
                    std::to_string(rays * scenes.size()) + " rays; " +
                    (facts.empty() ? "" : facts.back());
    r.details.insert(r.details.begin(), facts.begin(), facts.end());
    return r;
}

}  // namespace pt
