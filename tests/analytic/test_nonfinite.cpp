// NaN or Inf never reaches the film. The direct estimators must not make
// them in the first place: renders of the configurations where a careless
// estimator divides by zero (points on the plane of a light, a light edge-on,
// a point light touching a surface, a sphere light cut by the floor, a
// light of almost no area, a receiver touching a light) with every strategy
// count no non-finite sample. And the renderer's counter works: an
// integrator that returns NaN is counted and its samples dropped.
#include <doctest/doctest.h>

#include "analytic/tiny_render.h"
#include "core/counters.h"

using namespace pt;
using namespace pt::analytic;

namespace {

const char* kHardScene = R"({
    "camera": {"position": [0, 3, 6], "look_at": [0, 0, 0], "vfov": 50},
    "film": {"width": 48, "height": 48},
    "materials": {"floor": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]},
                  "lamp": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5], "emission": [5, 5, 5]}},
    "objects": [
        {"type": "quad", "corner": [-3, 0, -3], "edge1": [0, 0, 6], "edge2": [6, 0, 0], "material": "floor"},
        {"type": "quad", "corner": [-2, 0, 1], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "lamp"},
        {"type": "quad", "corner": [1, 0, -2], "edge1": [0, 1, 0], "edge2": [1, 0, 0], "material": "lamp"},
        {"type": "sphere", "center": [0, 0, -1], "radius": 0.7, "material": "lamp"},
        {"type": "quad", "corner": [0.5, 0.3, 1], "edge1": [1e-70, 0, 0], "edge2": [0, 0, 1e-70], "material": "lamp"},
        {"type": "sphere", "center": [1.5, 0.3, 1.5], "radius": 0.3, "material": "floor"},
        {"type": "quad", "corner": [1.2, 0.6, 1.2], "edge1": [0, 0, 0.6], "edge2": [0.6, 0, 0], "material": "lamp"}
    ],
    "lights": [{"type": "point", "position": [-1, 0, -1], "intensity": [3, 3, 3]},
               {"type": "point", "position": [0.7, 1e-300, 0.3], "intensity": [3, 3, 3]},
               {"type": "directional", "direction": [1, 0, 0], "irradiance": [1, 1, 1]},
               {"type": "environment", "radiance": [0.2, 0.2, 0.2]}]
})";

class NanIntegrator final : public Integrator {
  public:
    Color Li(const RenderContext&, const Ray& ray, Rng&) const override {
        return ray.d.x > 0 ? Color(std::nan(""), 0, 0) : Color(1, 1, 1);
    }
    IntegratorKind kind() const override { return IntegratorKind::normals; }
};

}  // namespace

TEST_CASE("no NaN or Inf from the direct estimators in the hard cases") {
    Scene scene = parse_json_scene(kHardScene, "hard.json");
    for (DirectStrategy strategy :
         {DirectStrategy::light, DirectStrategy::hemisphere, DirectStrategy::mis}) {
        CAPTURE(to_string(strategy));
        RenderResult r = render_scene(scene, settings_for(strategy, 4, 4));
        CHECK(r.counters.nonfinite_samples == 0);
        bool finite = true;
        for (float v : r.image.data())
            finite = finite && std::isfinite(v);
        CHECK(finite);
        CHECK(channel_stats(r.image, 0).max > 0);  // it did render something
    }
}

TEST_CASE("the renderer counts and drops non-finite samples") {
    Scene scene = parse_json_scene(kHardScene, "hard.json");
    RenderSettings settings = settings_for(DirectStrategy::light, 2, 1);
    Stages stages = make_stages(StageSet::none());
    NanIntegrator integrator;
    std::unique_ptr<Accelerator> accelerator =
        build_accelerator(scene, stages, AcceleratorSettings{});
    RenderContext context{scene, *accelerator, stages, settings, integrator};
    RenderResult r = render_image(context, RenderOptions{});
    CHECK(r.counters.nonfinite_samples > 0);
    for (float v : r.image.data())
        CHECK(std::isfinite(v));
}
