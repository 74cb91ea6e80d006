// The handout stubs grade as "not implemented" (0 points, no crash), and
// manifests are read strictly.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/stub_fallback.h"
#include "grade/check_registry.h"
#include "grade/image_case.h"
#include "grading_helpers.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "scene/scene_loader.h"
#include "stages/camera.h"

using namespace pt;
using namespace pt::testing;

namespace {

/// A table whose every student function behaves like its handout stub:
/// throws NotImplemented, or (Part 2's build and traversals) falls back on
/// something slow but correct after calling stub_fallback.
Stages stub_stages() {
    Stages s = reference_stages();
    s.camera.generate_ray = [](const Camera&, double, double, Vec2) -> Ray {
        throw NotImplemented(1, "1", "generate_ray");
    };
    s.camera.raytrace_pixel = [](const RenderContext&, int, int) -> PixelResult {
        throw NotImplemented(1, "2", "raytrace_pixel");
    };
    s.intersect.intersect_triangle = [](const Triangle&, const Ray&) -> std::optional<Hit> {
        throw NotImplemented(1, "3", "intersect_triangle");
    };
    s.intersect.intersect_sphere = [](const Sphere&, const Ray&) -> std::optional<Hit> {
        throw NotImplemented(1, "4", "intersect_sphere");
    };
    s.bvh.tree.construct_bvh = [](std::vector<BVHPrimitive>& p, size_t start, size_t end, size_t) {
        stub_fallback(2, "1", "construct_bvh", "one leaf of every primitive");
        return reference::construct_bvh(p, start, end, end - start);
    };
    s.bvh.tree.bbox_intersect = [](const BBox&, const Ray&, double&, double&) -> bool {
        throw NotImplemented(2, "2", "bbox_intersect");
    };
    s.bvh.tree.bvh_intersect = [](const BVHTree& bvh, const Ray& ray, const BVHNode*) {
        stub_fallback(2, "3", "bvh_intersect", "a linear scan");
        std::optional<Hit> best;
        for (size_t i = 0; i < bvh.primitives.size(); ++i)
            if (std::optional<Hit> h = bvh.intersect_primitive(i, ray);
                h && BVHTree::closer(*h, best))
                best = h;
        return best;
    };
    s.bvh.tree.bvh_has_intersection = [](const BVHTree& bvh, const Ray& ray, const BVHNode*) {
        stub_fallback(2, "4", "bvh_has_intersection", "a linear scan");
        for (size_t i = 0; i < bvh.primitives.size(); ++i)
            if (bvh.intersect_primitive(i, ray)) return true;
        return false;
    };
    s.bvh.grid_intersect = [](const GridCells&, const Ray&) -> std::optional<Hit> {
        throw NotImplemented(2, "6", "grid_intersect");
    };
    s.direct.diffuse_f = [](const Color&, const Vec3&, const Vec3&) -> Color {
        throw NotImplemented(3, "1", "diffuse_f");
    };
    s.direct.diffuse_sample_f = [](const Color&, const Vec3&, Vec2) -> BSDFSample {
        throw NotImplemented(3, "2", "diffuse_sample_f");
    };
    s.direct.zero_bounce_radiance = [](const RenderContext&, const Ray&,
                                       const SurfaceInteraction&) -> Color {
        throw NotImplemented(3, "3", "zero_bounce_radiance");
    };
    s.direct.estimate_direct_lighting_hemisphere = [](const RenderContext&, const Ray&,
                                                      const SurfaceInteraction&, Rng&) -> Color {
        throw NotImplemented(3, "4", "estimate_direct_lighting_hemisphere");
    };
    s.direct.estimate_direct_lighting_importance = [](const RenderContext&, const Ray&,
                                                      const SurfaceInteraction&, Rng&) -> Color {
        throw NotImplemented(3, "5", "estimate_direct_lighting_importance");
    };
    s.direct.one_bounce_radiance = [](const RenderContext&, const Ray&, const SurfaceInteraction&,
                                      Rng&) -> Color {
        throw NotImplemented(3, "6", "one_bounce_radiance");
    };
    s.direct.power_heuristic = [](double, double, double, double) -> double {
        throw NotImplemented(3, "7", "power_heuristic");
    };
    s.direct.balance_heuristic = [](double, double, double, double) -> double {
        throw NotImplemented(3, "7", "balance_heuristic");
    };
    s.direct.estimate_direct_lighting_mis = [](const RenderContext&, const Ray&,
                                               const SurfaceInteraction&, Rng&) -> Color {
        throw NotImplemented(3, "8", "estimate_direct_lighting_mis");
    };
    s.global.at_least_one_bounce_radiance =
        [](const RenderContext&, const Ray&, const SurfaceInteraction&, const Color&,
           Rng&) -> Color { throw NotImplemented(4, "1", "at_least_one_bounce_radiance"); };
    s.global.est_radiance_global_illumination = [](const RenderContext&, const Ray&,
                                                   Rng&) -> Color {
        throw NotImplemented(4, "2", "est_radiance_global_illumination");
    };
    s.adaptive.has_converged = [](const PixelStatistics&, double) -> bool {
        throw NotImplemented(5, "1", "has_converged");
    };
    s.sampler.stratified_sample_2d = [](int, int, int, Vec2) -> Vec2 {
        throw NotImplemented(6, "1", "stratified_sample_2d");
    };
    s.sampler.scrambled_radical_inverse = [](uint64_t, const DigitPermutation&) -> double {
        throw NotImplemented(6, "2", "scrambled_radical_inverse");
    };
    s.photon.emit_photon = [](const Light&, double, uint64_t, Vec2, Vec2) -> EmittedPhoton {
        throw NotImplemented(8, "1", "emit_photon");
    };
    s.photon.build_kdtree = [](const std::vector<Vec3>&) -> KdTree {
        throw NotImplemented(8, "2", "build_kdtree");
    };
    s.photon.k_nearest = [](const KdTree& tree, const Vec3& p, int k, double max_dist2,
                            std::vector<Neighbor>& out) {
        stub_fallback(8, "3", "k_nearest", "a brute-force scan of every photon");
        out.clear();
        for (size_t i = 0; i < tree.size(); ++i)
            if (double d2 = (tree.points[i] - p).norm2(); d2 <= max_dist2) out.push_back({tree.ids[i], d2});
        std::sort(out.begin(), out.end(), [](const Neighbor& a, const Neighbor& b) { return a.dist2 < b.dist2; });
        if (k >= 0 && out.size() > size_t(k)) out.resize(size_t(k));
    };
    s.photon.density_estimate = [](const std::vector<PhotonContribution>&, double, PhotonKernel) -> Color {
        throw NotImplemented(8, "4", "density_estimate");
    };
    s.media.homogeneous_transmittance = [](const Color&, double) -> Color {
        throw NotImplemented(9, "1", "homogeneous_transmittance");
    };
    s.media.sample_distance = [](double, double, double) -> DistanceSample {
        throw NotImplemented(9, "2", "sample_distance");
    };
    s.media.hg_phase = [](double, double) -> double { throw NotImplemented(9, "3", "hg_phase"); };
    s.media.sample_hg = [](const Vec3&, double, Vec2) -> Vec3 { throw NotImplemented(9, "4", "sample_hg"); };
    s.media.in_scattered_radiance = [](const RenderContext&, const Vec3&, const Vec3&, int, Rng&) -> Color {
        throw NotImplemented(9, "5", "in_scattered_radiance");
    };
    s.bdpt.random_walk = [](const RenderContext&, const Ray&, const Color&, double, int, Transport, Rng&,
                            std::vector<PathVertex>&) -> int { throw NotImplemented(7, "1", "random_walk"); };
    s.bdpt.connect = [](const RenderContext&, const std::vector<PathVertex>&, int, const std::vector<PathVertex>&,
                        int, Rng&) -> Connection { throw NotImplemented(7, "2", "connect"); };
    s.bdpt.mis_weight = [](const MisVertex*, int, const MisVertex*, int, bool, MisHeuristic) -> double {
        throw NotImplemented(7, "3", "mis_weight");
    };
    return s;
}

size_t task_count() {
    size_t n = 0;
    for (int part : graded_parts())
        n += manifest(part).tasks.size();
    return n;
}

std::vector<PartManifest> all_manifests() {
    std::vector<PartManifest> all;
    for (int part : graded_parts())
        all.push_back(manifest(part));
    return all;
}

/// Whether this build's student code of `part` is the handout's (its first
/// function still throws NotImplemented or falls back).
bool handout_of_part(int part) {
    StubFallbacksAreNotImplemented strict;
    try {
        switch (part) {
            case 1: {
                Camera c;
                c.finalize();
                student::generate_ray(c, 0.5, 0.5, Vec2(0.5, 0.5));
                break;
            }
            case 2: {
                std::vector<BVHPrimitive> p(1);
                student::construct_bvh(p, 0, 1, 4);
                break;
            }
            case 3:
                student::diffuse_f(Color(1), Vec3(0, 0, 1), Vec3(0, 0, 1));
                break;
            case 4: {
                // A camera ray into the Cornell box, with this build's global stage.
                Scene scene = load_scene(source_dir() + "/assets/scenes/cbox.json");
                Stages stages = make_stages(StageSet::all());
                std::unique_ptr<Accelerator> accelerator =
                    build_accelerator(scene, stages, AcceleratorSettings{});
                std::unique_ptr<Integrator> integrator = make_integrator(IntegratorKind::path);
                RenderSettings settings;
                RenderContext context{scene, *accelerator, stages, settings, *integrator};
                Rng rng(1);
                student::est_radiance_global_illumination(
                    context, Ray(scene.camera.position, normalize(Vec3(0, 0, 1))), rng);
                break;
            }
            case 5:
                student::has_converged(PixelStatistics{}, 0.05);
                break;
            case 6:
                student::stratified_sample_2d(0, 1, 1, Vec2(0.5, 0.5));
                break;
            case 8:
                student::build_kdtree({Vec3(0, 0, 0)});
                break;
            case 9:
                student::homogeneous_transmittance(Color(1), 1);
                break;
        }
    } catch (const NotImplemented&) {
        return true;
    }
    return false;
}

std::string write_manifest(const std::string& name, const std::string& text) {
    std::string dir = output_dir() + "/manifests/" + name + "/part1";
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/grading.json") << text;
    return dir + "/grading.json";
}

}  // namespace

TEST_CASE("stubs earn 0 points with 'not implemented' on every task of every part") {
    Stages stubs = stub_stages();
    GradeReport report = grade_all(all_manifests(), environment(stubs, 1));
    REQUIRE(report.tasks.size() == task_count());
    for (const TaskResult& t : report.tasks) {
        INFO(t.id << ": " << t.message);
        CHECK(t.status == TaskStatus::not_implemented);
        CHECK(t.points == 0);
        CHECK(t.message.find("not implemented yet") != std::string::npos);
        CHECK(std::isnan(t.value));
    }
    CHECK(report.points() == 0);
    // 100 per part, plus the 10 of Part 2's optional task 6 (the grid).
    CHECK(report.max_points() == 100.0 * graded_parts().size() + 10);
    CHECK_FALSE(report.all_passed());
}

TEST_CASE("a slow fallback is 'not implemented' for its task, not a pass on its correctness") {
    // Part 2 with only construct_bvh written: the traversal tasks still fall
    // back on the linear scan, which would agree with brute force.
    Stages s = stub_stages();
    s.bvh.tree.construct_bvh = reference::construct_bvh;
    s.bvh.tree.bbox_intersect = reference::bbox_intersect;
    GradeReport report = grade_all({manifest(2)}, environment(s, 1));
    REQUIRE(report.tasks.size() == 6);
    CHECK(report.tasks[0].status == TaskStatus::pass);  // construct_bvh
    CHECK(report.tasks[1].status == TaskStatus::pass);  // bbox_intersect
    for (size_t i : {2, 3, 4}) {
        INFO(report.tasks[i].id << ": " << report.tasks[i].message);
        CHECK(report.tasks[i].status == TaskStatus::not_implemented);
    }
    CHECK(report.tasks[2].message == "Part 2, task 3: bvh_intersect is not implemented yet");
    CHECK(report.tasks[3].message == "Part 2, task 4: bvh_has_intersection is not implemented yet");
    // Outside the grader the fallback only says so, once, and works.
    std::vector<BVHPrimitive> p(3);
    CHECK(stub_stages().bvh.tree.construct_bvh(p, 0, 3, 1)->is_leaf());
    {
        StubFallbacksAreNotImplemented strict;
        CHECK_THROWS_AS(stub_stages().bvh.tree.construct_bvh(p, 0, 3, 1), NotImplemented);
    }
    // In a child process too (grade's default).
    GradeReport isolated = grade_all({manifest(2)}, environment(stub_stages(), 1), nullptr, 30.0);
    for (const TaskResult& t : isolated.tasks)
        CHECK(t.status == TaskStatus::not_implemented);
}

TEST_CASE("the stubs of this build (when it is the handout) grade as not implemented") {
    Stages student = make_stages(StageSet::all());
    for (int part : graded_parts()) {
        if (!handout_of_part(part)) {
            MESSAGE("this build has a student's Part " << part << ", not the handout: skipped");
            continue;
        }
        GradeReport report = grade_all({manifest(part)}, environment(student, 1));
        for (const TaskResult& t : report.tasks) {
            INFO(t.id << ": " << t.message);
            CHECK(t.status == TaskStatus::not_implemented);
        }
    }
}

TEST_CASE("a student function that throws something else fails its task with the message") {
    Stages s = reference_stages();
    s.intersect.intersect_sphere = [](const Sphere&, const Ray&) -> std::optional<Hit> {
        throw std::out_of_range("vector::at");
    };
    for (const TaskSpec& spec : part1_manifest().tasks) {
        if (spec.id != "part1.4") continue;
        TaskResult r = grade_task(spec, environment(s, 1));
        CHECK(r.status == TaskStatus::fail);
        CHECK(r.message.find("vector::at") != std::string::npos);
    }
}

TEST_CASE("the manifests name registered checks, 100 points each; a missing part is noted") {
    for (int part : graded_parts()) {
        const PartManifest& m = manifest(part);
        CHECK(m.part == part);
        double points = 0;
        for (const TaskSpec& t : m.tasks) {
            INFO(t.id);
            CHECK(find_check(t.check) != nullptr);
            CHECK(t.id.rfind("part" + std::to_string(part) + ".", 0) == 0);
            if (t.id != "part2.6") points += t.points;  // the optional extension: extra points
        }
        CHECK(points == 100);
    }
    CHECK(manifest(1).tasks.size() == 4);
    CHECK(manifest(2).tasks.size() == 6);
    CHECK(manifest(2).tasks[5].points == 10);  // optional (the grid): beyond the 100
    CHECK(manifest(3).tasks.size() == 8);
    CHECK(manifest(4).tasks.size() == 3);
    CHECK(manifest(5).tasks.size() == 2);
    CHECK(manifest(6).tasks.size() == 3);
    CHECK(manifest(7).tasks.size() == 4);
    CHECK(manifest(8).tasks.size() == 5);
    CHECK(manifest(9).tasks.size() == 5);
    std::vector<std::string> notes;
    std::vector<PartManifest> project = read_manifests(source_dir() + "/assignments", &notes);
    CHECK(project.size() >= graded_parts().size());
    // One note per part of 1 .. kLastPart without a manifest (none today).
    CHECK(project.size() + notes.size() == size_t(kLastPart));

    notes.clear();
    std::string dir = output_dir() + "/manifests/only_part1";
    std::filesystem::create_directories(dir + "/part1");
    std::filesystem::copy_file(source_dir() + "/assignments/part1/grading.json",
                               dir + "/part1/grading.json",
                               std::filesystem::copy_options::overwrite_existing);
    std::vector<PartManifest> all = read_manifests(dir, &notes);
    CHECK(all.size() == 1);
    CHECK(notes.size() == size_t(kLastPart - 1));
    CHECK(notes[0].find("Part 2") != std::string::npos);
}

TEST_CASE("manifest errors name the file and the key") {
    auto fails_with = [](const std::string& name, const std::string& text,
                         const std::string& expected) {
        std::string path = write_manifest(name, text);
        INFO(name);
        try {
            read_manifest(path, 1);
            FAIL("no error for " << name);
        } catch (const InputError& e) {
            std::string what = e.what();
            INFO(what);
            CHECK(what.find(path) != std::string::npos);
            CHECK(what.find(expected) != std::string::npos);
        }
    };
    const std::string head = R"({"part": 1, "tasks": [)";
    fails_with("not_json", "{", "not valid JSON");
    fails_with("unknown_top_key", R"({"part": 1, "tasks": [], "taks": []})",
               "unknown key \"taks\"");
    fails_with(
        "unknown_check",
        head +
            R"({"id": "a", "name": "n", "check": "generate_rays", "type": "function", "points": 1}]})",
        "unknown check \"generate_rays\"");
    fails_with(
        "wrong_type",
        head +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "image", "points": 1}]})",
        "is a function check");
    fails_with(
        "unknown_param",
        head +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "function", "points": 1, "params": {"rel_toll": 1}}]})",
        "unknown key \"rel_toll\"");
    fails_with(
        "negative_points",
        head +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "function", "points": -1}]})",
        "non-negative");
    fails_with(
        "duplicate_id",
        head +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "function", "points": 1},)" +
            R"({"id": "a", "name": "n", "check": "generate_ray", "type": "function", "points": 1}]})",
        "appears twice");
    fails_with("wrong_part", R"({"part": 2, "tasks": []})", "is 2 but the file is in part1/");
}

TEST_CASE("bad task parameters are the grader's error (InputError), not the student's") {
    std::string path = write_manifest("bad_image_case", R"({"part": 1, "tasks": [
        {"id": "x", "name": "n", "check": "image", "type": "image", "points": 1,
         "params": {"student_functions": ["camera.raytrace_pixl"],
                    "cases": [{"scene": "scenes/cbox_spheres.json", "integrator": "normals", "spp": 1}]}}]})");
    PartManifest m = read_manifest(path, 1);
    CHECK_THROWS_AS(grade_task(m.tasks[0], environment(reference_stages(), 1)), InputError);
}

TEST_CASE("case families that do not fit the check's categories are the grader's error") {
    // Part 2's slab task with its families, broken three ways.
    TaskSpec good;
    for (const TaskSpec& t : manifest(2).tasks)
        if (t.id == "part2.2") good = t;
    REQUIRE(good.params.contains("families"));
    good.params["cases"] = 40;
    auto message = [&](const TaskSpec& t) {
        try {
            grade_task(t, environment(reference_stages(), 1));
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    TaskSpec missing = good;
    missing.params["families"].erase(missing.params["families"].size() - 1);
    missing.points -= 2;
    CHECK(message(missing).find("is in no family") != std::string::npos);
    TaskSpec points = good;
    points.params["families"][0]["points"] = 1;
    CHECK(message(points).find("add up to 10, not the task's 20") != std::string::npos);
    TaskSpec unknown = good;
    unknown.params["families"][0]["categories"].push_back("no such category");
    CHECK(message(unknown).find("no case category \"no such category\"") != std::string::npos);
    CHECK(message(good) == "no error");
}

TEST_CASE("isolated tasks: a crash or an endless loop fails only its task") {
    Stages s = reference_stages();
    // Both without undefined behaviour, so that they do the same under the
    // sanitizers (scripts/sanitize.sh), which would report a null load or a
    // signed overflow and exit instead.
    s.intersect.intersect_sphere = [](const Sphere&, const Ray&) -> std::optional<Hit> {
        std::raise(SIGSEGV);  // a segmentation fault
        return std::nullopt;
    };
    s.intersect.intersect_triangle = [](const Triangle&, const Ray&) -> std::optional<Hit> {
        for (volatile unsigned i = 0;; i = i + 1) {
        }
    };
    GradeReport report = grade_all({part1_manifest()}, environment(s, 1), nullptr, 3.0);
    REQUIRE(report.tasks.size() == 4);
    CHECK(report.tasks[0].status == TaskStatus::pass);
    CHECK(report.tasks[1].status == TaskStatus::pass);
    CHECK(report.tasks[1].images.size() == 3);  // the result survives the trip through the pipe
    CHECK(report.tasks[2].status == TaskStatus::fail);
    CHECK(report.tasks[2].message.find("timed out") != std::string::npos);
    CHECK(report.tasks[3].status == TaskStatus::fail);
    CHECK(report.tasks[3].message.find("crashed") != std::string::npos);
    // Not implemented survives the trip too.
    Stages stubs = stub_stages();
    GradeReport stub_report = grade_all({part1_manifest()}, environment(stubs, 1), nullptr, 30.0);
    for (const TaskResult& t : stub_report.tasks)
        CHECK(t.status == TaskStatus::not_implemented);
}

TEST_CASE("image cases: Russian roulette keys are read strictly and change the fingerprint") {
    using nlohmann::json;
    const json base = {{"scene", "scenes/cbox.json"}, {"integrator", "path"}, {"spp", 8}};
    auto with = [&](const json& extra) {
        json j = base;
        j.update(extra);
        return j;
    };
    ImageCase plain = parse_image_case(base, "case");
    CHECK(plain.settings.russian_roulette);
    CHECK(plain.settings.rr_depth == 3);
    ImageCase rr0 = parse_image_case(with({{"rr_depth", 0}}), "case");
    CHECK(rr0.settings.rr_depth == 0);
    ImageCase off = parse_image_case(with({{"russian_roulette", false}}), "case");
    CHECK_FALSE(off.settings.russian_roulette);
    const std::string assets = source_dir() + "/assets";
    // The default keeps the fingerprint of cases written before the keys existed.
    CHECK(case_fingerprint(parse_image_case(with({{"rr_depth", 3}}), "case"), assets) ==
          case_fingerprint(plain, assets));
    CHECK(case_fingerprint(rr0, assets) != case_fingerprint(plain, assets));
    CHECK(case_fingerprint(off, assets) != case_fingerprint(plain, assets));
    CHECK(case_fingerprint(off, assets) != case_fingerprint(rr0, assets));

    auto fails_with = [&](const json& extra, const std::string& expected) {
        try {
            parse_image_case(with(extra), "m.json: case");
            FAIL("no error for " << extra.dump());
        } catch (const InputError& e) {
            INFO(e.what());
            CHECK(std::string(e.what()).find(expected) != std::string::npos);
        }
    };
    fails_with({{"rr_depth", -1}}, "m.json: case.rr_depth: expected an integer from 0");
    fails_with({{"rr_depth", "off"}}, "case.rr_depth: expected an integer");
    fails_with({{"russian_roulette", 1}}, "case.russian_roulette: expected true or false");
    fails_with({{"russian_roulette", false}, {"rr_depth", 2}}, "has no effect");
    fails_with({{"rr_dpth", 2}}, "unknown key \"rr_dpth\"");
}

TEST_CASE("image cases: sampler and photon keys are read strictly and change the fingerprint") {
    using nlohmann::json;
    const std::string assets = source_dir() + "/assets";
    const json path = {{"scene", "scenes/cbox.json"}, {"integrator", "path"}, {"spp", 8}};
    const json pm = {{"scene", "scenes/caustic_glass.json"}, {"integrator", "pm"}, {"spp", 8},
                     {"photon_seed", 1}};
    auto with = [](json j, const json& extra) {
        j.update(extra);
        return j;
    };
    ImageCase plain = parse_image_case(path, "case");
    ImageCase stratified = parse_image_case(with(path, {{"sampler", "stratified"}}), "case");
    CHECK(stratified.settings.sampler == SamplerKind::stratified);
    CHECK(case_fingerprint(parse_image_case(with(path, {{"sampler", "independent"}}), "case"), assets) ==
          case_fingerprint(plain, assets));
    CHECK(case_fingerprint(stratified, assets) != case_fingerprint(plain, assets));
    ImageCase photons = parse_image_case(with(pm, {{"caustic_photons", 1000}, {"photon_view", "caustic"}}), "case");
    CHECK(photons.settings.photon.fixed_seed);
    CHECK(photons.settings.photon.seed == 1);
    CHECK(photons.settings.photon.caustic_photons == 1000);
    CHECK(photons.settings.photon.view == PhotonView::caustic);
    CHECK(case_fingerprint(photons, assets) !=
          case_fingerprint(parse_image_case(with(pm, {{"caustic_photons", 2000}, {"photon_view", "caustic"}}), "case"),
                           assets));
    CHECK(case_fingerprint(photons, assets) !=
          case_fingerprint(parse_image_case(with(pm, {{"caustic_photons", 1000}, {"photon_view", "caustic"},
                                                      {"photon_seed", 2}}),
                                            "case"),
                           assets));
    auto fails_with = [&](const json& j, const std::string& expected) {
        try {
            parse_image_case(j, "m.json: case");
            FAIL("no error for " << j.dump());
        } catch (const InputError& e) {
            INFO(e.what());
            CHECK(std::string(e.what()).find(expected) != std::string::npos);
        }
    };
    fails_with(with(path, {{"sampler", "sobel"}}), "m.json: case.sampler");
    fails_with(with(path, {{"photons", 1000}}), "applies only to \"integrator\": \"pm\"");
    json no_seed = pm;
    no_seed.erase("photon_seed");
    fails_with(no_seed, "photon_seed");
    fails_with(with(pm, {{"photon_kernel", "gauss"}}), "photon_kernel");
    fails_with(with(pm, {{"knn", -1}}), "knn");
}
