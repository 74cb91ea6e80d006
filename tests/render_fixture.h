// In-process rendering for tests: a tiny scene, the reference stages, and
// any integrator, without going through the command line.
#pragma once

#include <memory>

#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "stages/stages.h"

namespace pt::test {

/// A camera at the origin looking down -z at one large grey quad at z = -1.
inline Scene make_quad_scene(int width, int height) {
    std::string json = R"({"camera": {"position": [0,0,0], "look_at": [0,0,-1], "vfov": 60},
        "film": {"width": )" + std::to_string(width) + R"(, "height": )" + std::to_string(height) + R"(},
        "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
        "objects": [{"type": "quad", "corner": [-10,-10,-1], "edge1": [20,0,0], "edge2": [0,20,0], "material": "grey"}]})";
    return parse_json_scene(json, "quad.json");
}

/// Renders `scene` with `integrator` and the given stage tables and settings.
inline RenderResult render_with(const Scene& scene, const Integrator& integrator, const RenderSettings& settings,
                                const Stages& stages, int threads = 1) {
    std::unique_ptr<Accelerator> accelerator = build_accelerator(scene, stages, AcceleratorSettings());
    RenderContext context{scene, *accelerator, stages, settings, integrator};
    RenderOptions options;
    options.threads = threads;
    return render_image(context, options);
}

}  // namespace pt::test
