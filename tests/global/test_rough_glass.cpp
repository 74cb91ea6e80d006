// Rough glass in the path tracer: light sampling through a transmissive
// BSDF (lights on both sides, scene/microfacet_bsdf.h and stages/mis.cpp's
// light_sample_context), MIS and pure BSDF sampling are three unbiased
// estimators of the same image, so their per-pixel differences have mean 0
// (within 4 standard errors). A light sample that skipped the far side of a
// rough glass pane, or a pdf that disagreed with sample_f, would bias one
// of them. Also: no NaN, and the anisotropic and Beckmann variants render.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "global/global_render.h"
#include "global/same_mean.h"

using namespace pt;
using namespace pt::global_test;

namespace {

/// A rough glass pane (a single quad: light must be sampled through it) and
/// a rough glass ball in front of a large lamp, over a diffuse floor.
std::string scene_json(const std::string& glass) {
    return R"({
    "camera": {"position": [0, 0.6, 3], "look_at": [0, 0.4, 0], "vfov": 50},
    "film": {"width": 20, "height": 20},
    "materials": {
      "floor": {"type": "diffuse", "albedo": [0.6, 0.5, 0.4]},
      "glass": )" + glass + R"(,
      "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [3, 3, 3]}
    },
    "objects": [
      {"type": "quad", "corner": [-3, 0, 3], "edge1": [6, 0, 0], "edge2": [0, 0, -6], "material": "floor"},
      {"type": "quad", "corner": [-1.2, 0.1, 0.3], "edge1": [1.1, 0, 0], "edge2": [0, 1.2, 0], "material": "glass"},
      {"type": "sphere", "center": [0.6, 0.45, 0.2], "radius": 0.4, "material": "glass"},
      {"type": "quad", "corner": [-2, 0, -1.5], "edge1": [4, 0, 0], "edge2": [0, 2.5, 0], "material": "lamp"}
    ]
})";
}

}  // namespace

TEST_CASE("rough glass: light sampling, MIS and BSDF sampling agree") {
    for (std::string glass : {R"({"type": "rough_dielectric", "ior": 1.5, "roughness": 0.3})",
                              R"({"type": "rough_dielectric", "ior": 1.5, "distribution": "beckmann", "roughness": [0.1, 0.5]})"}) {
        CAPTURE(glass);
        Scene scene = scene_from(scene_json(glass));
        RenderSettings light = path_settings(4, 512, 3), mis = light, bsdf = light;
        mis.direct = DirectStrategy::mis;
        mis.seed = 4;
        bsdf.direct = DirectStrategy::hemisphere;  // in the path tracer: BSDF sampling only
        bsdf.seed = 5;
        RenderResult a = render(scene, light), b = render(scene, mis), c = render(scene, bsdf);
        CHECK(a.counters.nonfinite_samples == 0);
        CHECK(b.counters.nonfinite_samples == 0);
        CHECK(c.counters.nonfinite_samples == 0);
        check_same_mean(a.image, c.image, 0.05);
        check_same_mean(b.image, c.image, 0.05);  // a 5% bias would fail
    }
}
