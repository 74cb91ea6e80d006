#include "grade/runners.h"

#include "core/error.h"
#include "grade/params.h"

namespace pt {
namespace {

struct Runner {
    const char* key;
    std::vector<std::string> withheld;
};

// The reference's direct calls (src/stages): the hemisphere estimator calls
// zero_bounce_radiance; one_bounce_radiance calls both estimators; the
// traversals call bbox_intersect. The triangle runner also withholds the
// watertight triangle test.
const std::vector<Runner>& runners() {
    static const std::vector<Runner> table = {
        {"generate_ray", {"camera.generate_ray"}},
        {"raytrace_pixel", {"camera.raytrace_pixel"}},
        {"intersect_triangle", {"intersect.intersect_triangle"}},
        {"intersect_sphere", {"intersect.intersect_sphere"}},
        {"construct_bvh", {"bvh.construct_bvh"}},
        {"bbox_intersect", {"bvh.bbox_intersect", "bvh.bvh_intersect", "bvh.bvh_has_intersection"}},
        {"bvh_intersect", {"bvh.bvh_intersect"}},
        {"bvh_has_intersection", {"bvh.bvh_has_intersection"}},
        {"bvh", {"bvh.construct_bvh", "bvh.bbox_intersect", "bvh.bvh_intersect",
                 "bvh.bvh_has_intersection"}},
        {"grid_intersect", {"bvh.grid_intersect"}},
        {"has_converged", {"adaptive.has_converged"}},
        {"diffuse_f", {"direct.diffuse_f"}},
        {"diffuse_sample_f", {"direct.diffuse_sample_f"}},
        {"zero_bounce_radiance",
         {"direct.zero_bounce_radiance", "direct.estimate_direct_lighting_hemisphere",
          "direct.one_bounce_radiance"}},
        {"estimate_direct_lighting_hemisphere",
         {"direct.estimate_direct_lighting_hemisphere", "direct.one_bounce_radiance"}},
        {"estimate_direct_lighting_importance",
         {"direct.estimate_direct_lighting_importance", "direct.one_bounce_radiance"}},
        {"one_bounce_radiance", {"direct.one_bounce_radiance"}},
        {"mis_heuristics", {"direct.power_heuristic", "direct.balance_heuristic"}},
        {"estimate_direct_lighting_mis",
         {"direct.estimate_direct_lighting_mis", "direct.one_bounce_radiance"}},
        {"at_least_one_bounce_radiance", {"global.at_least_one_bounce_radiance"}},
        {"est_radiance_global_illumination", {"global.est_radiance_global_illumination"}},
        {"stratified_sample_2d", {"sampler.stratified_sample_2d"}},
        {"scrambled_radical_inverse", {"sampler.scrambled_radical_inverse"}},
        {"emit_photon", {"photon.emit_photon"}},
        {"build_kdtree", {"photon.build_kdtree"}},
        {"k_nearest", {"photon.k_nearest"}},
        {"density_estimate", {"photon.density_estimate"}},
        {"photon", {"photon.emit_photon", "photon.build_kdtree", "photon.k_nearest",
                    "photon.density_estimate"}},
        {"homogeneous_transmittance", {"media.homogeneous_transmittance"}},
        {"sample_distance", {"media.sample_distance"}},
        {"hg_phase", {"media.hg_phase"}},
        {"sample_hg", {"media.sample_hg"}},
        {"in_scattered_radiance", {"media.in_scattered_radiance"}},
        {"random_walk", {"bdpt.random_walk"}},
        {"connect", {"bdpt.connect"}},
        {"mis_weight", {"bdpt.mis_weight"}},
        {"bdpt", {"bdpt.random_walk", "bdpt.connect", "bdpt.mis_weight"}},
    };
    return table;
}

}  // namespace

std::string runner_key(const TaskSpec& spec) {
    std::string graded = spec.check;
    if (spec.check == "bvh_performance") graded = "bvh";
    if (spec.check == "image") {
        std::vector<std::string> slots =
            param(spec, "student_functions", std::vector<std::string>{});
        if (slots.size() != 1)
            throw InputError(spec.manifest + ": task " + spec.id +
                             ": params.student_functions must name one function for the runners");
        graded = slots[0].substr(slots[0].find('.') + 1);
    }
    for (const Runner& r : runners())
        if (graded == r.key) return r.key;
    throw InputError(spec.manifest + ": task " + spec.id + ": no runner grades \"" + graded + "\"");
}

std::vector<std::string> withheld_slots(const std::string& key) {
    for (const Runner& r : runners())
        if (key == r.key) return r.withheld;
    return {};
}

std::vector<std::string> runner_keys() {
    std::vector<std::string> keys;
    for (const Runner& r : runners())
        keys.push_back(r.key);
    return keys;
}

}  // namespace pt
