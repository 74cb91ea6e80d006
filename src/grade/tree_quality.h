// Tree quality (Part 2): measures of a student-style BVH's shape that a
// tree cannot fake by being fast on one ray set or by doing few primitive
// tests (a tree that splits one primitive off per level does fewer
// primitive tests per ray than the reference's, and is linear in depth):
//
// - SAH cost (MacDonald and Booth 1990; pbrt-v3 section 4.3.2): the
//   expected cost of a random ray that hits the root, sum over interior
//   nodes of SA(node) / SA(root) * C_trav plus over leaves of
//   SA(leaf) / SA(root) * primitives * C_isect, with C_trav = C_isect = 1;
//   reported relative to the reference construct_bvh's tree over the same
//   primitives;
// - depth relative to log2(n), n the number of primitives;
// - nodes visited per incoherent ray (random origins in the scene's box,
//   uniform directions) by one fixed closest-hit traversal (the reference
//   slab test, nearer child first, t_max shrunk to the closest hit), so
//   that the figure judges the tree and not the student's traversal;
//   reported relative to the reference tree's.
#pragma once

#include <optional>
#include <vector>

#include "core/ray.h"
#include "core/rng.h"
#include "stages/bvh.h"

namespace pt {

struct TreeQuality {
    double sah_cost = 0;       ///< C_trav = C_isect = 1, areas relative to the root's
    int depth = 0;             ///< edges on the longest root-to-leaf path
    double nodes_per_ray = 0;  ///< nodes whose box the fixed traversal tests, per ray
};

/// The fixed traversal above: the closest hit of `ray` in `tree` (ties to
/// the larger primitive id, as BVHTree::closer), adding the nodes whose box
/// it tests to `visited` and its primitive tests to `tests`. The grader's
/// own traversal of a student's tree (the performance task counts with it).
std::optional<Hit> fixed_closest_hit(const BVHTree& tree, const Ray& ray, size_t& visited,
                                     size_t& tests);

/// The measures above for `tree` (built), over `rays`.
TreeQuality measure_tree_quality(const BVHTree& tree, const std::vector<Ray>& rays);

/// `count` incoherent rays: origins uniform in `bounds`, directions uniform on the sphere.
std::vector<Ray> incoherent_rays(const BBox& bounds, int count, Rng& rng);

}  // namespace pt
