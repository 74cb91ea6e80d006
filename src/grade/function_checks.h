// Function checks: a student function against the reference on thousands
// of random inputs plus the hard ones, with stated tolerances. Each check
// draws its inputs from a generator seeded by env.seed, so a report can be
// reproduced with `grade --seed N`.
//
// Tolerances (the manifest's "rel_tol", default 1e-6): a figure a passes
// against the reference r when |a - r| <= rel_tol * max(1, |r|), vectors
// componentwise; unit vectors (directions, normals) must also have length
// 1 within rel_tol. Hit-or-miss verdicts may disagree only inside the edge
// band: where the exact (long double) margin of the verdict (a barycentric
// coordinate, b1 + b2 - 1, t - t_min, t_max - t, or for spheres the
// distance of the ray from the centre minus the radius) is within
// 1e-9 times the problem's condition number of zero, so that a one-ulp
// difference in a correct implementation may flip it. Such cases are
// counted and reported, never failed.
#pragma once

#include "grade/grade_environment.h"
#include "grade/task.h"

namespace pt {

/// Part 1, generate_ray: random pinhole cameras (position, orientation,
/// fov, aspect, clip range) at the corners, the centre, the edge midpoints
/// and random points of the image; with params.thin_lens, also thin-lens
/// cameras, checked by properties (origin on the lens disk, ray through the
/// point in focus) since any area-preserving disk mapping is correct.
TaskResult check_generate_ray(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 1, intersect_triangle: random triangles and rays, hits near edges
/// and vertices, grazing and parallel rays, t_min and t_max boundaries,
/// hits behind the origin, degenerate triangles, vertex normals, and
/// directions that are not unit length (shadow rays).
TaskResult check_intersect_triangle(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 1, intersect_sphere: rays from outside and inside, tangent rays,
/// spheres behind the origin, a unit sphere 10^6 units away, tiny and huge
/// spheres, every placement of [t_min, t_max] around the two roots.
TaskResult check_intersect_sphere(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 2, construct_bvh: the structure of the student's tree (every
/// primitive in exactly one leaf, child boxes inside their parent, leaf
/// boxes around their primitives, leaves of at most max_leaf_size unless
/// their centroids coincide) on the graded scenes and on synthetic lists
/// that break builders; the scene trees traversed by the reference against
/// the linear scan.
TaskResult check_construct_bvh(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 2, bbox_intersect: the slab test against its exact (long double)
/// answer; zero and -0.0 direction components, origins on faces and edges
/// and inside, every placement of [t0, t1]; the edge band as above.
TaskResult check_bbox_intersect(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 2, bvh_intersect and bvh_has_intersection: the student's traversal
/// of a reference-built tree, from the root and from inner nodes, against
/// brute force over the node's primitives (closest hit; any hit with
/// shadow-ray intervals).
TaskResult check_bvh_intersect(const TaskSpec& spec, const GradeEnvironment& env);
TaskResult check_bvh_has_intersection(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 2, grid_intersect (optional task 6): the student's 3D-DDA walk of a
/// reference-built uniform grid against brute force, on axis-aligned rays,
/// rays parallel to faces, along cell boundaries, through cell corners,
/// from inside and outside the grid.
TaskResult check_grid_intersect(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 3, diffuse_f: albedo / pi for wi above the surface, black below;
/// either on the horizon (|wi.z| <= edge_band).
TaskResult check_diffuse_f(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 3, diffuse_sample_f: every sample valid, unit, above the surface,
/// pdf = cos / pi, f = albedo / pi (or the student's diffuse_f); the
/// directions pass a chi-square test against cos / pi at `significance`.
TaskResult check_diffuse_sample_f(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 3, one_bounce_radiance: equals the estimator the settings choose,
/// with the same random numbers (dispatch_checks.cpp).
TaskResult check_one_bounce_radiance(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 3, power_heuristic and balance_heuristic: the weights against their
/// closed forms on random counts and densities, the limits of the contract
/// (0, 1, 0.5 for two deltas, no overflow at 1e300), and weights summing to 1.
TaskResult check_mis_heuristics(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 5, has_converged: CS184's interval rule on hand-made statistics;
/// either answer where the rule says nothing reliable (adaptive_checks.cpp).
TaskResult check_has_converged(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 6, stratified_sample_2d: one point per stratum in its own cell,
/// uniform within the cells (chi-square) (sampler_checks.cpp).
TaskResult check_stratified_sample_2d(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 6, scrambled_radical_inverse: the reference's exact values, closed
/// values, the stratification of the first b^m indices, and uniformity over
/// random permutations (chi-square) (sampler_checks.cpp).
TaskResult check_scrambled_radical_inverse(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 9, homogeneous_transmittance: e^(-sigma_t d) per channel; 1 where
/// sigma_t = 0 at any distance, infinite included (media_checks.cpp).
TaskResult check_homogeneous_transmittance(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 9, sample_distance: collisions with pdf sigma_t e^(-sigma_t t),
/// passes at t_max with e^(-sigma_t t_max), and the distribution of t
/// (chi-square) (media_checks.cpp).
TaskResult check_sample_distance(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 9, hg_phase: the Henyey-Greenstein closed form; integrates to 1.
TaskResult check_hg_phase(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 9, sample_hg: unit directions distributed as p_HG(-dot(wo, wi))
/// with uniform azimuth (chi-square) for g in {-0.9, -0.3, 0, 0.5, 0.95}.
TaskResult check_sample_hg(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 8, emit_photon: the ray of sample_Le and the flux of equation 2,
/// photon by photon; N photons' flux sums to the lights' power (photon_checks.cpp).
TaskResult check_emit_photon(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 8, build_kdtree: the layout of stages/kdtree.h; the reference's
/// queries on the student's tree equal brute force.
TaskResult check_build_kdtree(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 8, k_nearest: the student's query on reference trees against brute
/// force (uniform, clustered, duplicate, planar, collinear, tiny sets).
TaskResult check_k_nearest(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 8, density_estimate: equation 1 for the three kernels; uniform photons.
TaskResult check_density_estimate(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 7, random_walk: each vertex the first hit from the one before; its
/// area densities both ways, beta and delta flag against the grader's own
/// from the BSDFs at the hits; the next vertex's distribution in a cube
/// against the integrated area density (chi-square) (bdpt_checks.cpp).
TaskResult check_random_walk(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 7, connect: every strategy (s, t) of reference subpaths against the
/// closed forms (G, emission, We), 0 for blocked edges and vertices that
/// cannot be joined.
TaskResult check_bdpt_connect(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 7, mis_weight: the weights of every strategy of random paths
/// against brute force; they sum to 1 (both heuristics).
TaskResult check_bdpt_mis_weight(const TaskSpec& spec, const GradeEnvironment& env);

}  // namespace pt
