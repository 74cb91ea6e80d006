// Inputs shared by the Part 2 checks: the graded scenes, rays through them,
// and student-style trees (stages/bvh.h) built with a chosen construct_bvh,
// so that each handout function is graded with the reference's versions of
// the other three.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/rng.h"
#include "grade/grade_environment.h"
#include "scene/scene.h"
#include "stages/bvh.h"

namespace pt {

/// The scene at `path` (relative to the assets folder).
Scene load_graded_scene(const GradeEnvironment& env, const std::string& path);

/// `count` rays through the scene: half from random points of its bounding
/// box (enlarged by 10%) in random directions, half camera rays through
/// random points of the film. No direction component is exactly zero
/// (those are bbox_intersect's hard cases, graded there).
std::vector<Ray> scene_rays(const Scene& scene, const Stages& reference, int count, Rng& rng);

/// The primitives as make_tree_bvh hands them to construct_bvh: id i at
/// index i, padded bounds, their centroid.
std::vector<BVHPrimitive> tree_primitives(const Scene& scene);

/// A student-style tree over `scene` built by `construct` with leaves of at
/// most `max_leaf` primitives; its primitives are tested with `intersect`.
/// Throws std::runtime_error when construct returns a null root.
std::unique_ptr<BVHTree> build_tree(const Scene& scene, const IntersectStage& intersect,
                                    ConstructBvhFn construct, size_t max_leaf);

/// Every node under `root` (depth first, root first), without recursion.
std::vector<const BVHNode*> tree_nodes(const BVHNode* root);

/// The indices into tree.primitives of the leaves under `node`.
std::vector<size_t> primitives_under(const BVHNode* node);

/// Brute force: the closest hit of `ray` with the primitives at `indices`
/// (ties to the larger primitive id, as BVHTree::closer), and whether any
/// of them is hit.
std::optional<Hit> brute_force_closest(const BVHTree& tree, const std::vector<size_t>& indices,
                                       const Ray& ray);
bool brute_force_any(const BVHTree& tree, const std::vector<size_t>& indices, const Ray& ray);

}  // namespace pt
