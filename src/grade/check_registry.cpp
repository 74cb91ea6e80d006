#include "grade/check_registry.h"

#include "grade/function_checks.h"
#include "grade/image_check.h"
#include "grade/performance_checks.h"

namespace pt {

// The table of checks. A new kind of function check (a BSDF's f, a
// hemisphere estimator, ...) is one routine and one row; image tasks need
// no row (they all use `image`).
const std::vector<CheckInfo>& all_checks() {
    static const std::vector<CheckInfo> checks = {
        {"generate_ray",
         TaskType::function,
         check_generate_ray,
         {"rel_tol", "cameras", "points_per_camera", "thin_lens", "max_mismatches", "families"},
         "camera rays against the reference: random cameras, corners, centre, random points"},
        {"intersect_triangle",
         TaskType::function,
         check_intersect_triangle,
         {"rel_tol", "edge_band", "cases", "max_mismatches", "families"},
         "ray-triangle hits against the reference: random, edges, grazing, parallel, t bounds, "
         "degenerate"},
        {"intersect_sphere",
         TaskType::function,
         check_intersect_sphere,
         {"rel_tol", "edge_band", "cases", "max_mismatches", "families"},
         "ray-sphere hits against the reference: outside, inside, tangent, behind, 10^6 away, t "
         "bounds"},
        {"construct_bvh",
         TaskType::function,
         check_construct_bvh,
         {"scenes", "max_leaf", "random_lists", "rays", "rel_tol", "max_mismatches"},
         "the student's BVH build: every primitive in one leaf, boxes nested, leaf sizes; scene "
         "trees traversed by the reference against the linear scan"},
        {"bbox_intersect",
         TaskType::function,
         check_bbox_intersect,
         {"cases", "rel_tol", "edge_band", "max_mismatches", "families"},
         "the slab test against its exact answer: zero and -0.0 components, faces, edges, inside, "
         "t intervals"},
        {"bvh_intersect",
         TaskType::function,
         check_bvh_intersect,
         {"scenes", "rays", "max_leaf", "rel_tol", "max_mismatches", "families"},
         "the student's closest-hit traversal of a reference-built tree, from the root and inner "
         "nodes, against brute force"},
        {"bvh_has_intersection",
         TaskType::function,
         check_bvh_has_intersection,
         {"scenes", "rays", "max_leaf", "rel_tol", "max_mismatches", "families"},
         "the student's any-hit traversal (shadow rays) of a reference-built tree against brute "
         "force"},
        {"grid_intersect",
         TaskType::function,
         check_grid_intersect,
         {"scenes", "rays", "empty_grid_rays", "rel_tol", "max_mismatches", "families"},
         "the student's 3D-DDA walk of a reference-built uniform grid against brute force: "
         "axis-aligned, parallel to faces, along cell boundaries, through corners, inside and outside, "
         "and an empty grid (every ray misses)"},
        {"bvh_performance",
         TaskType::performance,
         check_bvh_performance,
         {"scene", "rays", "timed_rays", "max_timed_seconds", "rel_tol", "linear_rays",
          "repeats", "max_leaf", "min_speedup", "max_tests_per_ray", "max_nodes_per_ray",
          "quality_rays", "max_sah_ratio", "max_depth_ratio", "max_visited_ratio"},
         "the student's whole BVH: primitive tests and nodes per ray of the grader's traversal of "
         "the student's tree; the student's traversal's speedup over the linear scan (the "
         "runner's CPU time, counted by the kernel); the tree's SAH cost, depth and nodes "
         "visited per incoherent ray against the reference's"},
        {"diffuse_f",
         TaskType::function,
         check_diffuse_f,
         {"cases", "rel_tol", "edge_band", "max_mismatches", "families"},
         "the Lambertian BSDF value: albedo / pi above the surface, black below"},
        {"diffuse_sample_f",
         TaskType::function,
         check_diffuse_sample_f,
         {"samples", "significance", "rel_tol", "max_mismatches"},
         "Lambertian sampling: valid unit samples above the surface, pdf = cos / pi, f = albedo / "
         "pi, chi-square of the directions"},
        {"one_bounce_radiance",
         TaskType::function,
         check_one_bounce_radiance,
         {"scene", "points", "max_mismatches"},
         "one_bounce_radiance returns the estimate of the strategy the settings ask for (same "
         "random numbers)"},
        {"mis_heuristics",
         TaskType::function,
         check_mis_heuristics,
         {"cases", "rel_tol", "max_mismatches"},
         "the power and balance heuristics against their closed forms, limits (zero, delta, 1e300) "
         "and the sum of the two strategies' weights"},
        {"has_converged",
         TaskType::function,
         check_has_converged,
         {"cases", "edge_band", "max_mismatches", "families"},
         "the adaptive-sampling convergence test against CS184's rule on hand-made statistics"},
        {"stratified_sample_2d",
         TaskType::function,
         check_stratified_sample_2d,
         {"significance", "grid", "max_mismatches"},
         "Part 6: one point per stratum, each in its own cell; uniform within the cells "
         "(chi-square)"},
        {"scrambled_radical_inverse",
         TaskType::function,
         check_scrambled_radical_inverse,
         {"significance", "permutations", "max_mismatches"},
         "Part 6: radical inverses against closed values and the reference's exact values; the "
         "first b^m indices stratified; uniform over random permutations (chi-square)"},
        {"emit_photon",
         TaskType::function,
         check_emit_photon,
         {"scenes", "photons", "rel_tol", "max_mismatches"},
         "Part 8: the ray of sample_Le and the flux of equation 2; N photons sum to the lights' "
         "power"},
        {"build_kdtree",
         TaskType::function,
         check_build_kdtree,
         {"points", "queries", "max_mismatches"},
         "Part 8: the kd-tree layout; the reference's queries on the student's tree against brute "
         "force"},
        {"k_nearest",
         TaskType::function,
         check_k_nearest,
         {"points", "queries", "max_mismatches"},
         "Part 8: k nearest within a radius on reference trees against brute force"},
        {"density_estimate",
         TaskType::function,
         check_density_estimate,
         {"cases", "rel_tol", "max_mismatches"},
         "Part 8: equation 1 for the box, cone and Epanechnikov kernels; uniform photon density"},
        {"homogeneous_transmittance",
         TaskType::function,
         check_homogeneous_transmittance,
         {"cases", "rel_tol", "max_mismatches"},
         "Part 9: e^(-sigma_t d) per channel; 1 for zero extinction at any distance"},
        {"sample_distance",
         TaskType::function,
         check_sample_distance,
         {"samples", "significance", "rel_tol", "max_mismatches"},
         "Part 9: free flights: collision pdf, probability of passing, chi-square of the distances"},
        {"hg_phase",
         TaskType::function,
         check_hg_phase,
         {"cases", "rel_tol", "max_mismatches"},
         "Part 9: the Henyey-Greenstein closed form; integrates to 1 over the sphere"},
        {"sample_hg",
         TaskType::function,
         check_sample_hg,
         {"samples", "significance", "rel_tol", "max_mismatches"},
         "Part 9: Henyey-Greenstein sampling: unit directions, chi-square of cos theta and azimuth"},
        {"random_walk",
         TaskType::function,
         check_random_walk,
         {"scenes", "walks", "max_vertices", "samples", "significance", "rel_tol", "max_mismatches"},
         "Part 7: subpath vertices at the first hits, area densities both ways, beta; the next "
         "vertex's distribution against the integrated area density (chi-square)"},
        {"connect",
         TaskType::function,
         check_bdpt_connect,
         {"scenes", "paths", "rel_tol", "max_mismatches"},
         "Part 7: every strategy (s, t) against the closed forms: G, visibility, emission, We"},
        {"mis_weight",
         TaskType::function,
         check_bdpt_mis_weight,
         {"cases", "rel_tol", "max_mismatches"},
         "Part 7: MIS weights of random paths against brute force, summing to 1 (both heuristics)"},
        {"image",
         TaskType::image,
         check_image,
         {"student_functions", "cases", "k", "floor", "alpha", "tile", "tau_rel", "reference_runs",
          "heatmap_low", "heatmap_high"},
         "renders with the student's functions switched in, against a converged reference "
         "(noise-aware)"},
    };
    return checks;
}

const CheckInfo* find_check(const std::string& name) {
    for (const CheckInfo& c : all_checks())
        if (name == c.name) return &c;
    return nullptr;
}

}  // namespace pt
