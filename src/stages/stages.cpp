#include "stages/stages.h"

#include "core/error.h"
#include "scene/scene.h"
#include "stages/bvh.h"
#include "stages/embree_accel.h"
#include "stages/instance_accelerator.h"
#include "stages/kd_tree.h"
#include "stages/uniform_grid.h"

namespace pt {
namespace {

// The student's side of the bvh stage: the CS184-style tree of
// assignments/part2/bvh.cpp.
std::unique_ptr<Accelerator> build_student_bvh(const Scene& scene, const IntersectStage& intersect,
                                               const AcceleratorSettings& settings) {
    return make_tree_bvh(scene, intersect, settings, student::tree_functions());
}

}  // namespace

Stages make_stages(StageSet student, TriangleTest triangle_test) {
    Stages s;
    s.student = student;
    if (student.contains(Stage::camera)) {
        s.camera = {student::generate_ray, student::raytrace_pixel};
    } else {
        s.camera = {reference::generate_ray, reference::raytrace_pixel};
    }
    if (student.contains(Stage::intersect)) {
        s.intersect = {student::intersect_triangle, student::intersect_sphere};
    } else {
        s.intersect = {triangle_test == TriangleTest::watertight ? reference::intersect_triangle_watertight
                                                                 : reference::intersect_triangle,
                       reference::intersect_sphere};
    }
    if (student.contains(Stage::bvh)) {
        s.bvh = {build_student_bvh, student::tree_functions(), student::grid_intersect};
    } else {
        s.bvh = {make_reference_bvh, reference::tree_functions(), reference::grid_intersect};
    }
    s.adaptive = {student.contains(Stage::adaptive) ? student::has_converged : reference::has_converged};
    if (student.contains(Stage::direct)) {
        s.direct = {student::diffuse_f,
                    student::diffuse_sample_f,
                    student::zero_bounce_radiance,
                    student::estimate_direct_lighting_hemisphere,
                    student::estimate_direct_lighting_importance,
                    student::one_bounce_radiance,
                    student::power_heuristic,
                    student::balance_heuristic,
                    student::estimate_direct_lighting_mis};
    } else {
        s.direct = {reference::diffuse_f,
                    reference::diffuse_sample_f,
                    reference::zero_bounce_radiance,
                    reference::estimate_direct_lighting_hemisphere,
                    reference::estimate_direct_lighting_importance,
                    reference::one_bounce_radiance,
                    reference::power_heuristic,
                    reference::balance_heuristic,
                    reference::estimate_direct_lighting_mis};
    }
    if (student.contains(Stage::global)) {
        s.global = {student::at_least_one_bounce_radiance,
                    student::est_radiance_global_illumination};
    } else {
        s.global = {reference::at_least_one_bounce_radiance,
                    reference::est_radiance_global_illumination};
    }
    if (student.contains(Stage::sampler)) {
        s.sampler = {student::stratified_sample_2d, student::scrambled_radical_inverse};
    } else {
        s.sampler = {reference::stratified_sample_2d, reference::scrambled_radical_inverse};
    }
    if (student.contains(Stage::photon)) {
        s.photon = {student::emit_photon, student::build_kdtree, student::k_nearest, student::density_estimate};
    } else {
        s.photon = {reference::emit_photon, reference::build_kdtree, reference::k_nearest, reference::density_estimate};
    }
    if (student.contains(Stage::media)) {
        s.media = {student::homogeneous_transmittance, student::sample_distance, student::hg_phase, student::sample_hg,
                   student::in_scattered_radiance};
    } else {
        s.media = {reference::homogeneous_transmittance, reference::sample_distance, reference::hg_phase,
                   reference::sample_hg, reference::in_scattered_radiance};
    }
    if (student.contains(Stage::bdpt))
        s.bdpt = {student::random_walk, student::connect, student::mis_weight};
    else
        s.bdpt = {reference::random_walk, reference::connect, reference::mis_weight};
    return s;
}

namespace {
constexpr AccelKind kAccelKinds[] = {AccelKind::none, AccelKind::grid, AccelKind::kdtree, AccelKind::bvh,
                                     AccelKind::embree};
}  // namespace

const char* to_string(AccelKind kind) {
    switch (kind) {
        case AccelKind::none:
            return "none";
        case AccelKind::grid:
            return "grid";
        case AccelKind::kdtree:
            return "kdtree";
        case AccelKind::bvh:
            return "bvh";
        case AccelKind::embree:
            return "embree";
    }
    return "?";
}

AccelKind parse_accel_kind(const std::string& name, const std::string& flag) {
    for (AccelKind k : kAccelKinds)
        if (name == to_string(k)) return k;
    throw InputError(flag + ": expected one of none, grid, kdtree, bvh, embree, got '" + name + "'");
}

std::unique_ptr<Accelerator> build_accelerator(const Scene& scene, const Stages& stages,
                                               const AcceleratorSettings& settings) {
    std::unique_ptr<Accelerator> own;
    switch (settings.kind) {
        case AccelKind::none:
            own = make_linear_scan(scene, stages.intersect);
            break;
        case AccelKind::grid:
            own = make_uniform_grid(scene, stages.intersect, stages.bvh.grid_intersect);
            break;
        case AccelKind::kdtree:
            own = make_kd_tree(scene, stages.intersect);
            break;
        case AccelKind::embree:
            own = make_embree_accelerator(scene, stages.intersect);
            break;
        case AccelKind::bvh:
            own = stages.bvh.build(scene, stages.intersect, settings);
            break;
    }
    // Instanced shapes get their own accelerators of the same kind, under a
    // BVH over the instances (stages/instance_accelerator.h).
    return add_instances(std::move(own), scene, stages, settings);
}

}  // namespace pt
