// Self-intersection at scale, in a whole render: the Cornell box (direct
// light, soft shadows) translated by 10^4 and 10^5 mm renders the same as
// the untranslated box. With the same seed the random streams are the same,
// so the only differences come from floating-point geometry; they must be
// far below the Monte Carlo noise, measured as the difference between two
// seeds of the untranslated box. (In practice the float images come out
// bit-identical: the double-precision differences are below float's
// resolution. A self-intersecting shadow ray would show as dark speckles.)
#include <doctest/doctest.h>

#include <string>

#include "image/metrics.h"
#include "render_fixture.h"
#include "test_util.h"

using namespace pt;

namespace {

Scene cbox_translated(double offset) {
    std::string t = "[" + std::to_string(offset) + ", " + std::to_string(-0.5 * offset) + ", " +
                    std::to_string(0.25 * offset) + "]";
    auto shifted = [&](double x, double y, double z) {
        return "[" + std::to_string(x + offset) + ", " + std::to_string(y - 0.5 * offset) + ", " +
               std::to_string(z + 0.25 * offset) + "]";
    };
    std::string meshes = test::source_path("assets/meshes/");
    std::string json = R"({"camera": {"position": )" + shifted(278, 273, -800) + R"(, "look_at": )" +
                       shifted(278, 273, 0) + R"(, "vfov": 39.3},
        "film": {"width": 48, "height": 48},
        "objects": [{"type": "mesh", "file": ")" + meshes + R"(cbox.obj", "transform": {"translate": )" + t + R"(}},
                    {"type": "mesh", "file": ")" + meshes + R"(cbox_blocks.obj", "transform": {"translate": )" + t + R"(}}]})";
    return parse_json_scene(json, "cbox_translated.json");
}

Image render_direct(const Scene& scene, uint64_t seed) {
    std::unique_ptr<Integrator> integrator = make_integrator(IntegratorKind::direct);
    RenderSettings settings;
    settings.spp = 8;
    settings.light_samples = 2;
    settings.seed = seed;
    return test::render_with(scene, *integrator, settings, make_stages(StageSet::none()), 2).image;
}

}  // namespace

TEST_CASE("the Cornell box translated by 10^4 and 10^5 renders the same as untranslated within noise") {
    Scene origin = cbox_translated(0);
    Image reference = render_direct(origin, 1);
    double noise = relmse(render_direct(origin, 2), reference);  // two seeds: the Monte Carlo noise
    for (double offset : {1e4, 1e5, 1e6}) {
        Image moved = render_direct(cbox_translated(offset), 1);
        double difference = relmse(moved, reference);
        MESSAGE("offset " << offset << ": relMSE against the untranslated box " << difference
                          << " (noise between two seeds: " << noise << ")");
        CHECK(difference < 0.05 * noise);
    }
}
