// The interior furnace: the camera inside a closed surface whose every
// point emits Le and reflects diffusely with albedo rho. Radiance is then
// the same everywhere and in every direction, L = Le + rho L, so the
// Neumann series is geometric, whatever the shape:
//
//     -m m -o 1:  Le (1 + rho + ... + rho^m) = Le (1 - rho^(m+1)) / (1 - rho)
//     -m m -o 0:  Le rho^m                   (only the m-th bounce)
//     no cap:     Le / (1 - rho)             (Russian roulette ends the paths)
//
// Checked per channel: the pixel mean within 4 standard errors (from the
// spread of independent pixels; a correct estimator fails one check with
// probability 6.3e-5; the seeds are fixed). -m 0 is exact.
//
// Two closed surfaces: a tessellated sphere (inward faces, one area light),
// for every strategy; and the box [-1, 1]^3, for MIS and BSDF sampling only.
// Light sampling in a box has infinite variance: a point at distance h from
// an edge sees the adjacent wall's nearby points with cos cos / r^2 ~ 1 / h^2,
// whose square is not integrable, so its pixel means converge too slowly
// for a z-test. On a sphere cos cos / r^2 = 1 / (4 R^2) is constant. Both
// surfaces are convex and hold every light: no shadow ray is traced.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "global/global_render.h"

using namespace pt;
using namespace pt::global_test;

namespace {

const double kRho[3] = {0.5, 0.3, 0.7};
const double kLe[3] = {1.0, 2.0, 0.5};

void check_mean(const RenderResult& r, const double expected[3]) {
    CHECK(r.counters.nonfinite_samples == 0);
    CHECK(r.counters.shadow_rays == 0);
    for (int c = 0; c < 3; ++c) {
        PixelStats s = channel_stats(r.image, c);
        CAPTURE(c);
        CAPTURE(s.mean);
        CAPTURE(s.standard_error);
        CAPTURE(expected[c]);
        if (s.standard_error == 0) {
            CHECK(s.mean == doctest::Approx(expected[c]).epsilon(1e-6));
        } else {
            CHECK(std::fabs(s.z(expected[c])) <= 4.0);
            // A test that cannot tell right from wrong proves nothing.
            CHECK(s.standard_error < 0.05 * expected[c]);
        }
    }
}

struct Furnace {
    std::string name;
    Scene scene;
    std::vector<DirectStrategy> strategies;
};

std::vector<Furnace> furnaces() {
    std::string dir = test::scratch_dir("interior_furnace");
    write_glowing_sphere(dir, 1.0, 12, kRho, kLe);
    std::string sphere = R"({
        "camera": {"position": [0.1, 0.2, 0], "look_at": [0.4, 0.3, -1], "vfov": 70},
        "film": {"width": 16, "height": 16},
        "objects": [{"type": "mesh", "file": "glow.obj"}]})";
    test::write_file(dir + "/sphere.json", sphere);
    std::vector<Furnace> out;
    out.push_back({"sphere",
                   load_scene(dir + "/sphere.json"),
                   {DirectStrategy::light, DirectStrategy::mis, DirectStrategy::hemisphere}});
    out.push_back({"box",
                   scene_from(closed_box(glowing_wall(kRho, kLe), 16)),
                   {DirectStrategy::mis, DirectStrategy::hemisphere}});
    return out;
}

}  // namespace

TEST_CASE("interior furnace: -m m -o 1 sums the first m + 1 terms, -o 0 keeps the m-th") {
    for (const Furnace& furnace : furnaces()) {
        for (DirectStrategy strategy : furnace.strategies) {
            for (int m = 0; m <= 4; ++m) {
                for (bool accumulate : {true, false}) {
                    CAPTURE(furnace.name);
                    CAPTURE(std::string(to_string(strategy)));
                    CAPTURE(m);
                    CAPTURE(accumulate);
                    RenderSettings settings = path_settings(m, 8, 10 + m);
                    settings.direct = strategy;
                    settings.accumulate_bounces = accumulate;
                    double expected[3];
                    for (int c = 0; c < 3; ++c)
                        expected[c] = accumulate
                                          ? kLe[c] * (1 - std::pow(kRho[c], m + 1)) / (1 - kRho[c])
                                          : kLe[c] * std::pow(kRho[c], m);
                    check_mean(render(furnace.scene, settings), expected);
                }
            }
        }
    }
}

TEST_CASE("interior furnace: Russian roulette without a depth cap gives Le / (1 - rho)") {
    for (const Furnace& furnace : furnaces()) {
        for (DirectStrategy strategy : furnace.strategies) {
            for (int rr_depth : {0, 3}) {
                CAPTURE(furnace.name);
                CAPTURE(std::string(to_string(strategy)));
                CAPTURE(rr_depth);
                // rho^100001 is 0 in double precision: no cap in effect.
                RenderSettings settings = path_settings(100000, 16, 30 + rr_depth);
                settings.direct = strategy;
                settings.rr_depth = rr_depth;
                double expected[3];
                for (int c = 0; c < 3; ++c)
                    expected[c] = kLe[c] / (1 - kRho[c]);
                check_mean(render(furnace.scene, settings), expected);
            }
        }
    }
}
