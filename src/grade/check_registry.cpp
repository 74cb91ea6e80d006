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
         {"rel_tol", "cameras", "points_per_camera", "thin_lens", "max_mismatches"},
         "camera rays against the reference: random cameras, corners, centre, random points"},
        {"intersect_triangle",
         TaskType::function,
         check_intersect_triangle,
         {"rel_tol", "edge_band", "cases", "max_mismatches"},
         "ray-triangle hits against the reference: random, edges, grazing, parallel, t bounds, "
         "degenerate"},
        {"intersect_sphere",
         TaskType::function,
         check_intersect_sphere,
         {"rel_tol", "edge_band", "cases", "max_mismatches"},
         "ray-sphere hits against the reference: outside, inside, tangent, behind, 10^6 away, t "
         "bounds"},
        {"bvh_intersect",
         TaskType::function,
         check_accelerator,
         {"scene", "rays", "rel_tol", "max_mismatches"},
         "the student's BVH against the linear scan: closest hits and occlusion on random rays"},
        {"bvh_performance",
         TaskType::performance,
         check_bvh_performance,
         {"scene", "rays", "repeats", "min_speedup", "max_nodes_per_ray", "max_tests_per_ray"},
         "BVH speedup over the linear scan, nodes visited and primitive tests per ray"},
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
