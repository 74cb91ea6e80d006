// In-process renders for the Part 4 tests: scenes from JSON text, rendered
// through the library with a chosen integrator and stage table, and the
// closed-form scenes the tests share (the interior furnace box).
#pragma once

#include <cstdio>
#include <memory>
#include <string>

#include "analytic/tiny_render.h"
#include "core/math.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "stages/stages.h"
#include "test_util.h"

namespace pt::global_test {

using analytic::channel_stats;
using analytic::PixelStats;

/// Renders `scene` on one thread with integrator `kind` (auto: what
/// --integrator auto picks) and the given stage table.
inline RenderResult render(const Scene& scene, const RenderSettings& settings,
                           IntegratorKind kind = IntegratorKind::path,
                           const Stages& stages = make_stages(StageSet::none())) {
    if (kind == IntegratorKind::automatic)
        kind = choose_integrator(scene, analyze_effects(scene, settings), settings, nullptr,
                                 stages.student);
    std::unique_ptr<Integrator> integrator = make_integrator(kind);
    std::unique_ptr<Accelerator> accelerator =
        build_accelerator(scene, stages, AcceleratorSettings{});
    RenderContext context{scene, *accelerator, stages, settings, *integrator};
    RenderOptions options;
    options.threads = 1;
    return render_image(context, options);
}

inline Scene scene_from(const std::string& json) {
    return parse_json_scene(json, "global.json");
}

inline RenderSettings path_settings(int max_depth, int spp, uint64_t seed = 1) {
    RenderSettings s;
    s.max_depth = max_depth;
    s.spp = spp;
    s.seed = seed;
    return s;
}

inline std::string color_json(const double c[3]) {
    return "[" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
           "]";
}

/// The closed box [-1, 1]^3 seen from its centre: six quads facing inwards,
/// every wall of material "wall" (given as JSON), `size` x `size` pixels.
inline std::string closed_box(const std::string& wall_material, int size,
                              const std::string& extra_lights = "") {
    return R"({
    "camera": {"position": [0, 0, 0], "look_at": [0.3, 0.2, -1], "vfov": 70},
    "film": {"width": )" +
           std::to_string(size) + R"(, "height": )" + std::to_string(size) + R"(},
    "materials": {"wall": )" +
           wall_material + R"(},
    "objects": [
      {"type": "quad", "corner": [-1, -1, -1], "edge1": [0, 0, 2], "edge2": [2, 0, 0], "material": "wall"},
      {"type": "quad", "corner": [-1, 1, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "wall"},
      {"type": "quad", "corner": [-1, -1, -1], "edge1": [0, 2, 0], "edge2": [0, 0, 2], "material": "wall"},
      {"type": "quad", "corner": [1, -1, -1], "edge1": [0, 0, 2], "edge2": [0, 2, 0], "material": "wall"},
      {"type": "quad", "corner": [-1, -1, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "wall"},
      {"type": "quad", "corner": [-1, -1, 1], "edge1": [0, 2, 0], "edge2": [2, 0, 0], "material": "wall"}
    ],
    "lights": [)" +
           extra_lights + R"(]
})";
}

/// An emitting, reflecting wall: diffuse with albedo rho and emission Le.
inline std::string glowing_wall(const double rho[3], const double Le[3]) {
    return R"({"type": "diffuse", "albedo": )" + color_json(rho) + R"(, "emission": )" +
           color_json(Le) + "}";
}

/// An OBJ of a UV sphere of radius `radius` about the origin, `bands` x
/// 2 bands triangles per band pair, whose faces face inwards (towards the
/// centre) with material "glow" from glow.mtl (albedo rho, emission Le).
/// Consecutive faces share a vertex, so the whole sphere is one area light.
inline void write_glowing_sphere(const std::string& dir, double radius, int bands,
                                 const double rho[3], const double Le[3]) {
    std::string obj = "mtllib glow.mtl\nusemtl glow\n";
    const int segments = 2 * bands;
    // Vertex (i, j): latitude i in [0, bands], longitude j; poles once each.
    auto index = [&](int i, int j) {
        if (i == 0) return 1;
        if (i == bands) return 2 + (bands - 1) * segments;
        return 2 + (i - 1) * segments + (j % segments);
    };
    char line[160];
    for (int i = 0; i <= bands; ++i) {
        double theta = kPi * i / bands;
        for (int j = 0; j < ((i == 0 || i == bands) ? 1 : segments); ++j) {
            double phi = kTwoPi * j / segments;
            std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n",
                          radius * std::sin(theta) * std::cos(phi), radius * std::cos(theta),
                          radius * std::sin(theta) * std::sin(phi));
            obj += line;
        }
    }
    // (b - a) x (c - a) points outwards, so the faces are a c b and b c d.
    for (int i = 0; i < bands; ++i)
        for (int j = 0; j < segments; ++j) {
            int a = index(i, j), b = index(i, j + 1), c = index(i + 1, j), d = index(i + 1, j + 1);
            if (i > 0)
                obj += "f " + std::to_string(a) + " " + std::to_string(c) + " " +
                       std::to_string(b) + "\n";
            if (i + 1 < bands)
                obj += "f " + std::to_string(b) + " " + std::to_string(c) + " " +
                       std::to_string(d) + "\n";
        }
    test::write_file(dir + "/glow.obj", obj);
    test::write_file(dir + "/glow.mtl",
                     "newmtl glow\nKd " + std::to_string(rho[0]) + " " + std::to_string(rho[1]) +
                         " " + std::to_string(rho[2]) + "\nKe " + std::to_string(Le[0]) + " " +
                         std::to_string(Le[1]) + " " + std::to_string(Le[2]) + "\n");
}

/// True when two images have identical bytes (the same floats everywhere).
inline bool same_pixels(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() && a.data() == b.data();
}

}  // namespace pt::global_test
