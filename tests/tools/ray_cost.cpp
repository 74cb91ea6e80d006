// ray_cost: what a shadow (any-hit) ray costs against a closest-hit ray, on
// the same rays through the same accelerator, for docs/direct.md. Not a test.
//
//   ray_cost SCENE.json [--rays N] [--accel none|bvh]
//
// Collects N shadow rays as the direct integrator makes them (camera ray ->
// first hit -> a light sample -> isect.spawn_ray_to), then times
// Accelerator::occluded and Accelerator::intersect over that same list, one
// thread, best of 3 runs each, in CPU seconds (so that other processes on
// the machine do not count). Also times closest-hit camera rays, and counts
// BVH nodes and primitive tests per ray (hardware-independent).
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "apps/number_flags.h"
#include "core/counters.h"
#include "core/error.h"
#include "core/timer.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "scene/scene_loader.h"
#include "stages/camera.h"

using namespace pt;

namespace {

const char* kUsage =
    "usage: ray_cost SCENE.json|MESH.obj [--rays N] [--accel none|bvh]\n"
    "Times any-hit (occluded) against closest-hit (intersect) queries on the same N shadow\n"
    "rays (default 1000000), one thread, best of 3, CPU seconds; docs/direct.md.\n"
    "exit codes: 0 ok, 1 failure, 2 bad input\n";

int run(const std::vector<std::string>& args) {
    std::string scene_path;
    size_t count = 1000000;
    AcceleratorSettings accel;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size()) throw InputError(a + ": expected a value after it");
            return args[++i];
        };
        if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            return kExitOk;
        } else if (a == "--rays") {
            count = size_t(parse_whole_number(a, value(), 1, 1ll << 32));
        } else if (a == "--accel") {
            const std::string& v = value();
            accel.kind = parse_accel_kind(v, "--accel");
        } else if (a.size() > 1 && a[0] == '-') {
            throw InputError(a + ": unknown option (ray_cost --help)");
        } else if (scene_path.empty()) {
            scene_path = a;
        } else {
            throw InputError("unexpected argument '" + a + "' (ray_cost --help)");
        }
    }
    if (scene_path.empty()) throw InputError("no scene given (ray_cost --help)");
    Scene scene = load_scene(scene_path);
    Stages stages = make_stages(StageSet::none());
    std::unique_ptr<Accelerator> accelerator = build_accelerator(scene, stages, accel);
    std::unique_ptr<Integrator> integrator = make_integrator(IntegratorKind::direct);
    RenderSettings settings;
    RenderContext context{scene, *accelerator, stages, settings, *integrator};

    std::vector<Ray> camera_rays, shadow_rays;
    Rng rng(1);
    while (shadow_rays.size() < count) {
        Ray ray =
            reference::generate_ray(scene.camera, rng.next_1d(), rng.next_1d(), Vec2(0.5, 0.5));
        std::optional<SurfaceInteraction> isect = context.intersect(ray);
        camera_rays.push_back(ray);
        if (!isect) continue;
        BSDF bsdf = context.bsdf_at(*isect);
        LightSampleContext ref{isect->p, bsdf.frame().n};
        for (const auto& light : context.lights.all()) {
            LightSample s = light->sample_Li(ref, rng.next_2d());
            if (s.valid() && bsdf.to_local(s.wi).z > 0)
                shadow_rays.push_back(isect->spawn_ray_to(s.p));
        }
    }
    auto time_best = [](auto body) {
        double best = 1e300;
        for (int run = 0; run < 3; ++run) {
            CpuTimer t;
            body();
            best = std::min(best, t.seconds());
        }
        return best;
    };
    size_t blocked = 0, hits = 0, camera_hits = 0;
    RayCounters before = thread_counters();
    double t_occluded = time_best([&] {
        blocked = 0;
        for (const Ray& r : shadow_rays)
            blocked += accelerator->occluded(r);
    });
    RayCounters occluded_work = thread_counters() - before;
    before = thread_counters();
    double t_closest = time_best([&] {
        hits = 0;
        for (const Ray& r : shadow_rays)
            hits += accelerator->intersect(r).has_value();
    });
    RayCounters closest_work = thread_counters() - before;
    double t_camera = time_best([&] {
        camera_hits = 0;
        for (const Ray& r : camera_rays)
            camera_hits += accelerator->intersect(r).has_value();
    });
    double n = double(shadow_rays.size());
    std::printf("scene %s, accelerator %s, %zu shadow rays (%.1f%% blocked), %zu camera rays\n",
                scene_path.c_str(), accelerator->info().name.c_str(), shadow_rays.size(), 100.0 * blocked / n,
                camera_rays.size());
    // Each query ran 3 times: per ray is work / (3 n).
    std::printf("| query on the shadow rays | ns per ray | nodes per ray | primitive tests per ray "
                "|\n|---|---|---|---|\n");
    std::printf("| occluded (any hit) | %.1f | %.1f | %.1f |\n", t_occluded / n * 1e9,
                occluded_work.nodes_visited / (3 * n), occluded_work.primitive_tests / (3 * n));
    std::printf("| intersect (closest hit) | %.1f | %.1f | %.1f |\n", t_closest / n * 1e9,
                closest_work.nodes_visited / (3 * n), closest_work.primitive_tests / (3 * n));
    std::printf("any-hit / closest-hit time on the same rays: %.2f\n", t_occluded / t_closest);
    std::printf("closest-hit camera rays: %.1f ns per ray; shadow / camera ray time: %.2f\n",
                t_camera / camera_rays.size() * 1e9,
                (t_occluded / n) / (t_camera / camera_rays.size()));
    return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const InputError& e) {
        std::fprintf(stderr, "ray_cost: error: %s\n", e.what());
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ray_cost: internal error: %s\n", e.what());
        return kExitFailure;
    }
}
