// Part 2, bvh_performance: what the student's whole BVH (their
// construct_bvh and traversal, the reference intersection routines) saves
// over the linear scan.
//
// The limit that decides is hardware-independent: primitive tests per ray
// (and nodes visited, when the manifest limits them), counted while the
// grader traverses the student's tree itself with a fixed traversal
// (tree_quality.h), so that no code of the student's runs while it counts.
// The student's own traversal is judged by its speed: the runner answers
// distinct rays with it (distinct, so that remembering answers saves
// nothing), every answer must be the closest hit the grader finds in the
// same tree, and its time is the runner's whole CPU time as the kernel
// counted it, which bounds the traversal's from above: code that forges a
// clock or a counter inside the runner changes nothing the grader reads.
// That bound includes starting the runner and building the tree (about
// 0.02 s against 0.02 s for 20,000 rays of a good traversal), so the
// speedup it gives is a lower bound too; the limit (10) is generous. The
// linear scan is timed in the grader (CPU time, the fastest of `repeats`
// runs, on the first `linear_rays` rays, compared per ray).
//
// Tree quality (tree_quality.h) judges the student's construct_bvh by its
// shape, which a tree that is fast on the test rays, or does few primitive
// tests per ray, cannot fake: its SAH cost and the nodes a fixed traversal
// visits per incoherent ray, both relative to the reference tree over the
// same primitives, and its depth relative to log2(n). A tree that splits
// one primitive off per level passes the primitive-test limit; its depth
// (n / 4) and its nodes per ray fail it.
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/counters.h"
#include "core/timer.h"
#include "grade/bvh_inputs.h"
#include "grade/case_log.h"
#include "grade/hit_compare.h"
#include "grade/params.h"
#include "grade/performance_checks.h"
#include "grade/random_inputs.h"
#include "grade/student_calls.h"
#include "grade/tree_quality.h"

namespace pt {

AcceleratorMeasurement measure_accelerator(const Accelerator& accelerator,
                                           const std::vector<Ray>& rays, int repeats) {
    AcceleratorMeasurement m;
    m.seconds = INFINITY;
    for (int k = 0; k < std::max(1, repeats); ++k) {
        RayCounters before = thread_counters();
        ThreadCpuTimer timer;
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

TraversalTiming time_traversal(const BVHTree& tree, BvhIntersectFn traverse,
                               const std::vector<Ray>& rays, double max_seconds) {
    TraversalTiming m;
    m.answers.reserve(rays.size());
    ThreadCpuTimer timer;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (i % 64 == 0 && i > 0 && timer.seconds() > max_seconds) break;
        std::optional<Hit> hit =
            tree.root ? traverse(tree, rays[i], tree.root.get()) : std::optional<Hit>{};
        m.answers.push_back(hit);
    }
    m.seconds = timer.seconds();
    return m;
}

namespace {

/// A student's answer against the closest hit `truth`, with part2.3's
/// tolerance (hit_compare.h): the closest, another real hit or a miss (a
/// search that skipped part of the tree, as traversal bugs do), or no hit
/// of the primitive it names (made up).
enum class Answer { closest, not_closest, made_up };
Answer judge_answer(const Scene& scene, const IntersectStage& intersect, const Ray& ray,
                    const std::optional<Hit>& answer, const std::optional<Hit>& truth,
                    double rel_tol) {
    if (!answer) return truth ? Answer::not_closest : Answer::closest;
    if (answer->primitive >= scene.primitive_count()) return Answer::made_up;
    std::optional<Hit> real = intersect_primitive(scene, intersect, answer->primitive, ray);
    if (!real || !same_closest_t(answer->t, real->t, rel_tol)) return Answer::made_up;
    if (!truth) return Answer::made_up;  // a real hit the grader's traversal missed: impossible
    return same_closest_t(answer->t, truth->t, rel_tol) ? Answer::closest : Answer::not_closest;
}

std::string hit_text(const std::optional<Hit>& h) {
    return h ? "a hit on primitive " + std::to_string(h->primitive) + " at t = " + format_num(h->t)
             : std::string("a miss");
}

std::string joined(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& p : parts)
        out += (out.empty() ? "" : "; ") + p;
    return out;
}

}  // namespace

TaskResult check_bvh_performance(const TaskSpec& spec, const GradeEnvironment& env) {
    Scene scene =
        load_graded_scene(env, param(spec, "scene", std::string("scenes/cbox_knot.json")));
    const double min_speedup = param(spec, "min_speedup", 2.0);
    const double max_nodes = param(spec, "max_nodes_per_ray", INFINITY);
    const double max_tests = param(spec, "max_tests_per_ray", INFINITY);
    const double rel_tol = param(spec, "rel_tol", 1e-9);
    const size_t leaf = size_t(param(spec, "max_leaf", 4));
    Rng rng = check_rng(env.seed, "bvh_performance");

    // The student's part: their tree (recorded whole) and their traversal
    // of it on distinct rays (recorded: the answers).
    std::unique_ptr<BVHTree> mine =
        build_tree(scene, env.reference.intersect, env.student.bvh.tree.construct_bvh, leaf);
    std::vector<Ray> rays = scene_rays(
        scene, env.reference,
        std::max(param(spec, "timed_rays", 20000), param(spec, "rays", 2000)), rng);
    const TraversalTiming timing = student_traversal_timing(
        *mine, env.student.bvh.tree.bvh_intersect, rays, param(spec, "max_timed_seconds", 1.0));
    // The rest is the grader's own work (in the runner, nothing is read).
    if (call_mode() == CallMode::record) return TaskResult{};

    // The grader's traversal of the student's tree: counts, and the answers.
    const size_t counted = std::min<size_t>(rays.size(), size_t(param(spec, "rays", 2000)));
    const size_t answered = timing.answers.size();
    size_t visited = 0, tests = 0, wrong = 0, made_up = 0;
    std::string first_wrong;  // the first ray answered with another hit than the closest
    for (size_t i = 0; i < std::max(counted, answered); ++i) {
        size_t v = 0, t = 0;
        std::optional<Hit> truth = fixed_closest_hit(*mine, rays[i], v, t);
        if (i < counted) visited += v, tests += t;
        if (i >= answered) continue;
        Answer a = judge_answer(scene, env.reference.intersect, rays[i], timing.answers[i], truth,
                                rel_tol);
        wrong += a == Answer::not_closest;
        made_up += a == Answer::made_up;
        if (a == Answer::not_closest && first_wrong.empty())
            first_wrong = "ray o = " + format_vec(rays[i].o) + " d = " + format_vec(rays[i].d) +
                          ": " + hit_text(timing.answers[i]) + " instead of " + hit_text(truth);
    }
    const double tests_per_ray = double(tests) / double(std::max<size_t>(counted, 1));
    const double nodes_per_ray = double(visited) / double(std::max<size_t>(counted, 1));

    std::unique_ptr<Accelerator> linear = make_linear_scan(scene, env.reference.intersect);
    std::vector<Ray> linear_rays(
        rays.begin(),
        rays.begin() + std::min<long>(long(rays.size()), param(spec, "linear_rays", 200)));
    AcceleratorMeasurement l = measure_accelerator(*linear, linear_rays, param(spec, "repeats", 3));
    const double linear_per_ray = l.seconds / double(std::max<size_t>(linear_rays.size(), 1));
    const double student_per_ray =
        answered > 0 ? timing.seconds / double(answered) : INFINITY;
    const double speedup = student_per_ray > 0 ? linear_per_ray / student_per_ray : INFINITY;

    TaskResult r;
    r.metric = "primitive tests per ray";
    r.comparison = "<=";
    r.threshold = max_tests;
    r.value = tests_per_ray;
    char line[600];
    std::snprintf(line, sizeof line,
                  "the grader's traversal of the student's tree, %zu rays on %s (%u primitives): "
                  "%.3g primitive tests and %.3g nodes visited per ray (the linear scan: %.3g "
                  "tests); the student's traversal answered %zu of %zu distinct rays in %.3g s "
                  "of CPU (%s): %.3g us per ray against %.3g us for the linear scan: speedup %.3g",
                  counted, scene.name.c_str(), scene.primitive_count(), tests_per_ray,
                  nodes_per_ray, l.tests_per_ray, answered, rays.size(), timing.seconds,
                  timing.whole_runner ? "the whole runner, counted by the kernel"
                                      : "the loop, in process",
                  student_per_ray * 1e6, linear_per_ray * 1e6, speedup);
    r.details.push_back(line);
    r.details.push_back("the student's answers: " + std::to_string(answered - wrong - made_up) +
                        " closest hits, " + std::to_string(wrong) + " misses or farther hits, " +
                        std::to_string(made_up) + " made up");

    // The tree's shape against the reference construct_bvh's.
    std::unique_ptr<BVHTree> theirs =
        build_tree(scene, env.reference.intersect, env.reference.bvh.tree.construct_bvh, leaf);
    std::vector<Ray> incoherent =
        theirs->root ? incoherent_rays(theirs->root->bb, param(spec, "quality_rays", 1000), rng)
                     : std::vector<Ray>{};
    const TreeQuality qs = measure_tree_quality(*mine, incoherent);
    const TreeQuality qr = measure_tree_quality(*theirs, incoherent);
    r.details.push_back("the tree: " + std::to_string(tree_nodes(mine->root.get()).size()) +
                        " nodes, depth " + std::to_string(qs.depth) + ", leaves of at most " +
                        std::to_string(leaf) + " primitives where a split exists");
    const double log2n = std::log2(std::max(2.0, double(scene.primitive_count())));
    const double sah_ratio = qs.sah_cost / std::max(qr.sah_cost, 1e-300);
    const double depth_ratio = qs.depth / log2n;
    const double visited_ratio = qs.nodes_per_ray / std::max(qr.nodes_per_ray, 1e-300);
    char quality[400];
    std::snprintf(quality, sizeof quality,
                  "tree quality: SAH cost %.4g (%.3g x the reference tree's %.4g), depth %d "
                  "(%.3g x log2 n = %.3g), %.4g nodes visited per incoherent ray (%.3g x the "
                  "reference tree's %.4g)",
                  qs.sah_cost, sah_ratio, qr.sah_cost, qs.depth, depth_ratio, log2n,
                  qs.nodes_per_ray, visited_ratio, qr.nodes_per_ray);
    r.details.push_back(quality);
    std::vector<std::string> failures;
    const double max_sah = param(spec, "max_sah_ratio", INFINITY);
    const double max_depth = param(spec, "max_depth_ratio", INFINITY);
    const double max_visited = param(spec, "max_visited_ratio", INFINITY);
    if (!(sah_ratio <= max_sah))
        failures.push_back("SAH cost " + format_num(sah_ratio) + " x the reference tree's > " +
                           format_num(max_sah));
    if (!(depth_ratio <= max_depth))
        failures.push_back("depth " + std::to_string(qs.depth) + " = " + format_num(depth_ratio) +
                           " x log2 n > " + format_num(max_depth));
    if (!(visited_ratio <= max_visited))
        failures.push_back("nodes visited per incoherent ray " + format_num(visited_ratio) +
                           " x the reference tree's > " + format_num(max_visited));
    if (!(tests_per_ray <= max_tests))
        failures.push_back("primitive tests per ray " + format_num(tests_per_ray) + " > " +
                           format_num(max_tests));
    if (!(nodes_per_ray <= max_nodes))
        failures.push_back("nodes visited per ray " + format_num(nodes_per_ray) + " > " +
                           format_num(max_nodes));
    if (answered == 0)
        failures.push_back("the student's traversal answered no ray");
    else if (made_up > 0)
        failures.push_back("the student's traversal answered " + std::to_string(made_up) + " of " +
                           std::to_string(answered) +
                           " timed rays with a hit that the primitive it names does not have");
    else if (wrong > 0)
        // A search that skips part of the tree is faster for being wrong:
        // speed is credited only to a traversal right on every timed ray.
        failures.push_back("no speed credit: the student's traversal missed the closest hit on " +
                           std::to_string(wrong) + " of " + std::to_string(answered) +
                           " timed rays (first: " + first_wrong +
                           "); only a traversal that finds the closest hit on every ray is timed");
    else if (!(speedup >= min_speedup))
        failures.push_back("speedup " + format_num(speedup) + " < " + format_num(min_speedup));
    r.status = failures.empty() ? TaskStatus::pass : TaskStatus::fail;
    r.message = (failures.empty() ? std::string("") : joined(failures) + ": ") + line + "; " +
                quality;
    return r;
}

}  // namespace pt
