// The accelerator checks (Part 2): correctness of the student's BVH
// against the linear scan, and its performance. Both build the student's
// bvh stage with the reference intersection routines (stage_mix.h), so a
// wrong triangle test is charged to Part 1, not to the BVH.
#include <algorithm>
#include <cmath>

#include "core/counters.h"
#include "core/timer.h"
#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/performance_checks.h"
#include "grade/random_inputs.h"
#include "grade/stage_mix.h"
#include "scene/scene_loader.h"

namespace pt {
namespace {

/// Rays through the scene: from random points of its (slightly enlarged)
/// bounding box in random directions, and from the camera through random
/// points of the film.
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

Scene load_graded_scene(const TaskSpec& spec, const GradeEnvironment& env, const char* fallback) {
    return load_scene(env.assets_dir + "/" + param(spec, "scene", std::string(fallback)));
}

}  // namespace

TaskResult check_accelerator(const TaskSpec& spec, const GradeEnvironment& env) {
    Scene scene = load_graded_scene(spec, env, "scenes/cbox_spheres.json");
    const double tol = param(spec, "rel_tol", 1e-9);
    Stages mixed =
        mix_stages(env.reference, env.student, {"bvh"}, spec.manifest + ": task " + spec.id);
    std::unique_ptr<Accelerator> student = build_accelerator(scene, mixed, AcceleratorSettings{});
    std::unique_ptr<Accelerator> linear = make_linear_scan(scene, env.reference.intersect);
    Rng rng = check_rng(env.seed, "bvh_intersect");
    CaseLog log;
    for (const Ray& ray : scene_rays(scene, env.reference, param(spec, "rays", 4000), rng)) {
        std::optional<Hit> r = linear->intersect(ray);
        std::optional<Hit> s = student->intersect(ray);
        log.category("closest hit");
        std::string where = "ray o = " + format_vec(ray.o) + " d = " + format_vec(ray.d) + ": ";
        if (bool(r) != bool(s)) {
            log.mismatch(where +
                         (s ? "a hit on primitive " + std::to_string(s->primitive) +
                                  " where the linear scan misses"
                            : "a miss where the linear scan hits primitive " +
                                  std::to_string(r->primitive) + " at t = " + format_num(r->t)));
        } else if (r && !(std::fabs(s->t - r->t) <= tol * std::max(1.0, r->t))) {
            log.mismatch(where + "closest hit at t = " + format_num(s->t) + " (primitive " +
                         std::to_string(s->primitive) + ") instead of t = " + format_num(r->t) +
                         " (primitive " + std::to_string(r->primitive) + ")");
        } else {
            log.agreed();  // equal t on two primitives (a shared edge) is a tie, not an error
        }
        // Shadow rays: the interval ends before, or just after, the first hit.
        log.category("occlusion");
        Ray shadow = ray;
        shadow.t_max = r ? r->t * (rng.next_1d() < 0.5 ? 0.5 : 1.5) : 1e30;
        bool ro = linear->occluded(shadow), so = student->occluded(shadow);
        if (ro == so)
            log.agreed();
        else
            log.mismatch(where + "t_max = " + format_num(shadow.t_max) + ": occluded() says " +
                         (so ? "blocked" : "clear") + ", the linear scan " +
                         (ro ? "blocked" : "clear"));
    }
    return log.finish(spec, param(spec, "max_mismatches", 0));
}

AcceleratorMeasurement measure_accelerator(const Accelerator& accelerator,
                                           const std::vector<Ray>& rays, int repeats) {
    AcceleratorMeasurement m;
    m.seconds = INFINITY;
    for (int k = 0; k < std::max(1, repeats); ++k) {
        RayCounters before = thread_counters();
        Timer timer;
        size_t hits = 0;
        for (const Ray& ray : rays)
            hits += accelerator.intersect(ray).has_value();
        double seconds = timer.seconds();
        RayCounters used = thread_counters() - before;
        m.seconds = std::min(m.seconds, seconds);  // the least disturbed run
        m.nodes_per_ray = double(used.nodes_visited) / double(rays.size());
        m.tests_per_ray = double(used.primitive_tests) / double(rays.size());
        m.hits = hits;
    }
    return m;
}

TaskResult check_bvh_performance(const TaskSpec& spec, const GradeEnvironment& env) {
    Scene scene = load_graded_scene(spec, env, "scenes/cbox_spheres.json");
    const double min_speedup = param(spec, "min_speedup", 2.0);
    const double max_nodes = param(spec, "max_nodes_per_ray", INFINITY);
    const double max_tests = param(spec, "max_tests_per_ray", INFINITY);
    Stages mixed =
        mix_stages(env.reference, env.student, {"bvh"}, spec.manifest + ": task " + spec.id);
    std::unique_ptr<Accelerator> student = build_accelerator(scene, mixed, AcceleratorSettings{});
    std::unique_ptr<Accelerator> linear = make_linear_scan(scene, env.reference.intersect);
    Rng rng = check_rng(env.seed, "bvh_performance");
    std::vector<Ray> rays = scene_rays(scene, env.reference, param(spec, "rays", 20000), rng);
    const int repeats = param(spec, "repeats", 3);
    AcceleratorMeasurement s = measure_accelerator(*student, rays, repeats);
    AcceleratorMeasurement l = measure_accelerator(*linear, rays, repeats);

    TaskResult r;
    r.metric = "speedup over the linear scan";
    r.comparison = ">=";
    r.threshold = min_speedup;
    r.value = s.seconds > 0 ? l.seconds / s.seconds : INFINITY;
    char line[256];
    std::snprintf(line, sizeof line,
                  "%zu rays on %s: %.3g s against %.3g s for the linear scan (speedup %.3g); %.3g "
                  "nodes visited and "
                  "%.3g primitive tests per ray (linear scan: %.3g tests)",
                  rays.size(), scene.name.c_str(), s.seconds, l.seconds, r.value, s.nodes_per_ray,
                  s.tests_per_ray, l.tests_per_ray);
    r.details.push_back(line);
    std::vector<std::string> failures;
    if (!(r.value >= min_speedup))
        failures.push_back("speedup " + format_num(r.value) + " < " + format_num(min_speedup));
    if (!(s.nodes_per_ray <= max_nodes))
        failures.push_back("nodes visited per ray " + format_num(s.nodes_per_ray) + " > " +
                           format_num(max_nodes));
    if (!(s.tests_per_ray <= max_tests))
        failures.push_back("primitive tests per ray " + format_num(s.tests_per_ray) + " > " +
                           format_num(max_tests));
    r.status = failures.empty() ? TaskStatus::pass : TaskStatus::fail;
    std::string joined;
    for (const std::string& f : failures)
        joined += (joined.empty() ? "" : "; ") + f;
    r.message = (failures.empty() ? std::string("") : joined + ": ") + line;
    return r;
}

}  // namespace pt
