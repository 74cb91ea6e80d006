// Part 2, bvh_intersect and bvh_has_intersection: the student's traversal
// of a tree built by the reference construct_bvh (so that a wrong build is
// charged to construct_bvh alone), against brute force over the primitives
// under the node queried. Queries start at the root and at random inner
// nodes and leaves: the contract is "the primitives under `node`", and a
// traversal that ignores `node` (the handout's linear-scan fallback, when
// it is not reported as such) returns hits from elsewhere.
//
// The student's traversal calls the student's bbox_intersect (it is their
// code); the rays have no zero direction components, so a slab test that
// fails only there is charged to bbox_intersect alone.
#include <cmath>

#include "grade/bvh_inputs.h"
#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/hit_compare.h"
#include "grade/params.h"
#include "grade/random_inputs.h"

namespace pt {
namespace {

std::string node_text(size_t k) {
    return k == 0 ? "the root" : "node " + std::to_string(k) + " (depth first)";
}

std::string hit_text(const std::optional<Hit>& h) {
    return h ? "a hit on primitive " + std::to_string(h->primitive) + " at t = " + format_num(h->t)
             : std::string("a miss");
}

enum class Query { closest, any };

TaskResult check_traversal(const TaskSpec& spec, const GradeEnvironment& env, Query query) {
    const double tol = param(spec, "rel_tol", 1e-9);
    const int ray_count = param(spec, "rays", 1000);
    const size_t max_leaf = size_t(param(spec, "max_leaf", 4));
    std::vector<std::string> scenes =
        param(spec, "scenes",
              std::vector<std::string>{"scenes/cbox_spheres.json", "scenes/grading_knot.json"});
    const BvhFunctions& student = env.student.bvh.tree;
    Rng rng =
        check_rng(env.seed, query == Query::closest ? "bvh_intersect" : "bvh_has_intersection");
    CaseLog log;
    for (const std::string& path : scenes) {
        Scene scene = load_graded_scene(env, path);
        std::unique_ptr<BVHTree> tree = build_tree(scene, env.reference.intersect,
                                                   env.reference.bvh.tree.construct_bvh, max_leaf);
        std::vector<const BVHNode*> nodes = tree_nodes(tree->root.get());
        std::vector<size_t> all = primitives_under(tree->root.get());
        for (const Ray& ray : scene_rays(scene, env.reference, ray_count, rng)) {
            // Every ray from the root, and again from a random node below it.
            for (size_t k : {size_t(0), size_t(1 + rng.next_index(uint32_t(nodes.size() - 1)))}) {
                const BVHNode* node = nodes[k];
                const std::vector<size_t> under = k == 0 ? all : primitives_under(node);
                log.category(std::string(k == 0 ? "from the root" : "from inner nodes and leaves") +
                             (query == Query::closest ? "" : ", shadow rays"));
                std::string where = path + ": ray o = " + format_vec(ray.o) +
                                    " d = " + format_vec(ray.d) + " from " + node_text(k);
                std::optional<Hit> want = brute_force_closest(*tree, under, ray);
                if (query == Query::closest) {
                    std::optional<Hit> got = student.bvh_intersect(*tree, ray, node);
                    if (bool(got) == bool(want) && (!want || same_closest_t(got->t, want->t, tol)))
                        log.agreed();
                    else
                        log.mismatch(where + ": " + hit_text(got) + " instead of " +
                                     hit_text(want) + " (brute force over the node's " +
                                     std::to_string(under.size()) + " primitives)");
                    continue;
                }
                // Shadow rays: the interval ends before, or after, the closest hit.
                Ray shadow = ray;
                const double ends[] = {0.5, 1.5};
                shadow.t_max = want ? want->t * ends[rng.next_index(2)] : INFINITY;
                bool expected = brute_force_any(*tree, under, shadow);
                bool got = student.bvh_has_intersection(*tree, shadow, node);
                if (got == expected)
                    log.agreed();
                else
                    log.mismatch(where + ", t_max = " + format_num(shadow.t_max) + ": says " +
                                 (got ? "blocked" : "clear") + ", brute force over the node's " +
                                 std::to_string(under.size()) + " primitives says " +
                                 (expected ? "blocked" : "clear"));
            }
        }
    }
    return log.finish(spec, param(spec, "max_mismatches", 0), "brute force");
}

}  // namespace

TaskResult check_bvh_intersect(const TaskSpec& spec, const GradeEnvironment& env) {
    return check_traversal(spec, env, Query::closest);
}

TaskResult check_bvh_has_intersection(const TaskSpec& spec, const GradeEnvironment& env) {
    return check_traversal(spec, env, Query::any);
}

}  // namespace pt
