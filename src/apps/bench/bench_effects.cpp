// bench effects: what "simulate only what the scene calls for" saves
// (DESIGN.md "Effects"; docs/global.md). tests/global/test_effects.cpp
// proves the skipped code paths change no pixel; this measures the time.
//
// For each case, renders the scene as the effects analysis plans it and
// with every skippable code path forced on (RenderSettings::force), best
// of R runs each, checks that the two images are byte-identical, and
// prints a Markdown table: seconds, shadow rays, the time saved. A second
// table compares the integrator `auto` picks with the path tracer at the
// same flags where the images are identical (direct at -m 1 without
// mirrors or glass).
#include <algorithm>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/bench/bench_command.h"
#include "apps/bench/bench_util.h"
#include "core/error.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "stages/effects.h"
#include "scene/scene_loader.h"

namespace pt::bench {
namespace {

const char* const kUsage = "effects [-t N] [--repeat R]";

const char* const kHelp = R"(bench effects: the time the effects analysis saves.

  -t N          threads                                   [2]
  --repeat R    runs per render; the fastest counts       [3]

Cases: a diffuse sphere under the sky and a point light, the interior
furnace box (walls that emit and reflect), and the asset scenes cbox,
cbox_spheres, whitted and materials at small sizes. Each is rendered as
planned and with every skippable code path forced on; the images must be
byte-identical (the last column).
)";

struct Run {
    Image image;
    RayCounters counters;
    double seconds = 1e300;
};

Run render_best(const Scene& scene, const RenderSettings& settings, IntegratorKind kind,
                int threads, int repeat) {
    Stages stages = make_stages(StageSet::none());
    std::unique_ptr<Accelerator> accelerator =
        build_accelerator(scene, stages, AcceleratorSettings{});
    std::unique_ptr<Integrator> integrator = make_integrator(kind);
    Run best;
    for (int i = 0; i < repeat; ++i) {
        RenderContext context{scene, *accelerator, stages, settings, *integrator};
        RenderOptions options;
        options.threads = threads;
        RenderResult r = render_image(context, options);
        if (r.seconds < best.seconds) {
            best.seconds = r.seconds;
            best.image = r.image;
            best.counters = r.counters;
        }
    }
    return best;
}

struct Case {
    std::string name;
    std::function<Scene()> scene;
    RenderSettings settings;
};

RenderSettings flags(int max_depth, int spp, int light_samples = 1) {
    RenderSettings s;
    s.max_depth = max_depth;
    s.spp = spp;
    s.light_samples = light_samples;
    s.seed = 1;
    return s;
}

Scene sized(Scene scene, int width, int height) {
    scene.film_width = width;
    scene.film_height = height;
    scene.camera.aspect = double(width) / height;
    scene.camera.finalize();
    return scene;
}

std::string asset(const std::string& name) {
    return std::string(PT_SOURCE_DIR) + "/assets/scenes/" + name;
}

const char* kSphereUnderSky = R"({
    "camera": {"position": [0, 0.5, 4], "look_at": [0, 0, 0], "vfov": 40},
    "film": {"width": 128, "height": 128},
    "materials": {"grey": {"type": "diffuse", "albedo": [0.6, 0.5, 0.4]}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"}],
    "lights": [{"type": "environment", "radiance": [1, 0.8, 0.6]},
               {"type": "point", "position": [2, 3, 2], "intensity": [4, 4, 4]}]
})";

const char* kFurnaceBox = R"({
    "camera": {"position": [0, 0, 0], "look_at": [0.3, 0.2, -1], "vfov": 70},
    "film": {"width": 128, "height": 128},
    "materials": {"wall": {"type": "diffuse", "albedo": [0.5, 0.3, 0.7], "emission": [1, 2, 0.5]}},
    "objects": [
      {"type": "quad", "corner": [-1, -1, -1], "edge1": [0, 0, 2], "edge2": [2, 0, 0], "material": "wall"},
      {"type": "quad", "corner": [-1, 1, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "wall"},
      {"type": "quad", "corner": [-1, -1, -1], "edge1": [0, 2, 0], "edge2": [0, 0, 2], "material": "wall"},
      {"type": "quad", "corner": [1, -1, -1], "edge1": [0, 0, 2], "edge2": [0, 2, 0], "material": "wall"},
      {"type": "quad", "corner": [-1, -1, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "wall"},
      {"type": "quad", "corner": [-1, -1, 1], "edge1": [0, 2, 0], "edge2": [2, 0, 0], "material": "wall"}
    ]
})";

int run_effects(const std::vector<std::string>& args) {
    Args a("effects", args, {{"-t", 1}, {"--repeat", 1}, {"-h", 0}, {"--help", 0}});
    if (a.has("-h") || a.has("--help")) {
        std::cout << "usage: bench " << kUsage << "\n" << kHelp;
        return kExitOk;
    }
    if (!a.positionals().empty())
        throw InputError("effects: unexpected argument '" + a.positionals()[0] +
                         "' (see bench effects --help)");
    const int threads = a.get_int("-t", 2, 1, 4096), repeat = a.get_int("--repeat", 3, 1, 1000);
    std::vector<Case> cases = {
        {"sphere under sky + point light",
         [] { return parse_json_scene(kSphereUnderSky, "sphere.json"); }, flags(3, 16, 4)},
        {"interior furnace box", [] { return parse_json_scene(kFurnaceBox, "box.json"); },
         flags(5, 8)},
        {"cbox", [] { return sized(load_scene(asset("cbox.json")), 128, 128); }, flags(5, 8)},
        {"cbox_spheres", [] { return sized(load_scene(asset("cbox_spheres.json")), 128, 128); },
         flags(5, 8)},
        {"whitted", [] { return sized(load_scene(asset("whitted.json")), 160, 120); }, flags(1, 4)},
        {"materials", [] { return sized(load_scene(asset("materials.json")), 256, 128); },
         flags(5, 8)},
    };
    std::printf(
        "Code paths skipped by the effects analysis against all forced on (best of %d, %d "
        "threads):\n\n",
        repeat, threads);
    std::printf(
        "| scene | -m, -s, -l | integrator | skipped | seconds | forced on | saved | shadow rays "
        "(forced) | identical |\n|---|---|---|---|---|---|---|---|---|\n");
    for (const Case& c : cases) {
        Scene scene = c.scene();
        Effects effects = analyze_effects(scene, c.settings);
        IntegratorKind kind = choose_integrator(scene, effects, c.settings, nullptr);
        RenderSettings forced = c.settings;
        forced.force = {true, true, true, true, true};
        Run plan = render_best(scene, c.settings, kind, threads, repeat);
        Run all = render_best(scene, forced, kind, threads, repeat);
        bool identical = plan.image.data() == all.image.data();
        std::printf("| %s | %d, %d, %d | %s | %s | %.3f | %.3f | %.1f%% | %llu (%llu) | %s |\n",
                    c.name.c_str(), c.settings.max_depth, c.settings.spp, c.settings.light_samples,
                    to_string(kind),
                    skipped_code_paths(plan_code_paths(scene, effects, c.settings)).c_str(),
                    plan.seconds, all.seconds, 100 * (1 - plan.seconds / all.seconds),
                    (unsigned long long)plan.counters.shadow_rays,
                    (unsigned long long)all.counters.shadow_rays, identical ? "yes" : "NO");
    }

    std::printf(
        "\nThe integrator auto picks against the path tracer at the same flags (same image):\n\n");
    std::printf(
        "| scene | flags | auto | seconds | path | seconds | identical "
        "|\n|---|---|---|---|---|---|---|\n");
    for (const char* name : {"cbox.json", "cbox_big_light.json"}) {
        Scene scene = sized(load_scene(asset(name)), 128, 128);
        RenderSettings s = flags(1, 16, 4);
        IntegratorKind kind = choose_integrator(scene, analyze_effects(scene, s), s, nullptr);
        Run a = render_best(scene, s, kind, threads, repeat);
        Run p = render_best(scene, s, IntegratorKind::path, threads, repeat);
        std::printf("| %s | -m 1 -s 16 -l 4 | %s | %.3f | path | %.3f | %s |\n", name,
                    to_string(kind), a.seconds, p.seconds,
                    a.image.data() == p.image.data() ? "yes" : "NO");
    }
    return kExitOk;
}

const BenchCommandRegistration kRegistration({"effects", kUsage,
                                              "time saved by skipping code paths of absent "
                                              "effects (images checked identical)",
                                              run_effects});

}  // namespace
}  // namespace pt::bench
