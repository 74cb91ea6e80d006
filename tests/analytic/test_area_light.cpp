// A point under a rectangular area light: irradiance by the polygon
// formula, radiance Lo = albedo / pi * E for a Lambertian receiver, against
// light, hemisphere and MIS sampling (each within 4 standard errors).
//
// Lambert's formula for a polygon of constant radiance L (Lambert 1760; in
// vector form Arvo, "Applications of Irradiance Tensors to the Simulation
// of Non-Lambertian Phenomena", SIGGRAPH 1995, eq. 5): with u_i the unit
// vectors from the receiver x to the polygon's vertices,
//     E = L / 2 * | sum_i Theta_i (n . Gamma_i) |,
// Theta_i = acos(u_i . u_i+1) the angle the i-th edge subtends at x and
// Gamma_i = unit(u_i x u_i+1) the normal of the plane through x and that
// edge. The light is tilted and off-centre, so a wrong cos(theta') or r^2
// in the area-to-solid-angle change of variables shows at once.
#include <doctest/doctest.h>

#include <vector>

#include "analytic/tiny_render.h"
#include "core/math.h"

using namespace pt;
using namespace pt::analytic;

namespace {

double polygon_irradiance(const Vec3& x, const Vec3& n, const std::vector<Vec3>& vertices,
                          double L) {
    double sum = 0;
    for (size_t i = 0; i < vertices.size(); ++i) {
        Vec3 a = (vertices[i] - x).unit(), b = (vertices[(i + 1) % vertices.size()] - x).unit();
        double theta = std::acos(clamp(dot(a, b), -1.0, 1.0));
        sum += theta * dot(n, cross(a, b).unit());
    }
    return 0.5 * L * std::fabs(sum);
}

// The light: corner c, edges e1 and e2 (normal e1 x e2 must face the receiver).
const Vec3 kCorner(-0.6, 1.6, -0.4), kEdge1(1.3, -0.2, 0), kEdge2(0, 0.35, 1.1);
const Vec3 kReceiver(0.15, 0, 0.1);
const double kAlbedo = 0.8, kLe = 3.0;

std::string scene_json() {
    auto v = [](const Vec3& p) {
        return "[" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
               "]";
    };
    // A very narrow camera from the side (below the light) aimed at the
    // receiver: every pixel sees the same point to within 1e-5 units.
    return R"({
    "camera": {"position": [3, 0.6, 2.5], "look_at": )" +
           v(kReceiver) + R"(, "vfov": 0.0002},
    "film": {"width": 32, "height": 32},
    "materials": {"floor": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]},
                  "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [3, 3, 3]}},
    "objects": [
        {"type": "quad", "corner": [-10, 0, -10], "edge1": [0, 0, 20], "edge2": [20, 0, 0], "material": "floor"},
        {"type": "quad", "corner": )" +
           v(kCorner) + R"(, "edge1": )" + v(kEdge1) + R"(, "edge2": )" + v(kEdge2) +
           R"(, "material": "lamp"}]
})";
}

double expected_radiance() {
    std::vector<Vec3> polygon = {kCorner, kCorner + kEdge1, kCorner + kEdge1 + kEdge2,
                                 kCorner + kEdge2};
    return kAlbedo / kPi * polygon_irradiance(kReceiver, Vec3(0, 1, 0), polygon, kLe);
}

PixelStats render_stats(DirectStrategy strategy, int spp, int light_samples,
                        MisHeuristic heuristic = MisHeuristic::power) {
    RenderSettings settings = settings_for(strategy, spp, light_samples, 7);
    settings.mis_heuristic = heuristic;
    RenderResult r = render_json(scene_json(), settings);
    CHECK(r.counters.nonfinite_samples == 0);
    return channel_stats(r.image, 0);
}

}  // namespace

TEST_CASE("the polygon formula itself: a small square far away") {
    // A 1e-3 square at distance 10 straight above: E ~ L * A * cos * cos / r^2.
    double h = 0.5e-3;
    std::vector<Vec3> square = {{-h, 10, -h}, {h, 10, -h}, {h, 10, h}, {-h, 10, h}};
    CHECK(polygon_irradiance(Vec3(0, 0, 0), Vec3(0, 1, 0), square, 1.0) ==
          doctest::Approx(1e-6 / 100).epsilon(1e-6));
    // An infinite plane above (approximated by a huge square): E = pi L.
    double big = 1e7;
    std::vector<Vec3> sky = {{-big, 1, -big}, {big, 1, -big}, {big, 1, big}, {-big, 1, big}};
    CHECK(polygon_irradiance(Vec3(0, 0, 0), Vec3(0, 1, 0), sky, 1.0) ==
          doctest::Approx(kPi).epsilon(1e-6));
}

TEST_CASE("rectangle light: light, hemisphere and MIS sampling match Lambert's formula") {
    REQUIRE(dot(cross(kEdge1, kEdge2), kReceiver - kCorner) > 0);  // the lamp faces the receiver
    const double expected = expected_radiance();
    CAPTURE(expected);
    for (auto [strategy, spp, l] :
         {std::tuple{DirectStrategy::light, 4, 4}, std::tuple{DirectStrategy::mis, 4, 4},
          std::tuple{DirectStrategy::hemisphere, 16, 4}}) {
        PixelStats s = render_stats(strategy, spp, l);
        CAPTURE(to_string(strategy));
        CAPTURE(s.mean);
        CAPTURE(s.standard_error);
        CHECK(s.standard_error > 0);
        CHECK(std::fabs(s.z(expected)) <= 4.0);
        // The test has power: its standard error is under 2% of the value.
        CHECK(s.standard_error < 0.02 * expected);
    }
}

TEST_CASE("rectangle light: MIS with the balance heuristic matches Lambert's formula too") {
    const double expected = expected_radiance();
    PixelStats s = render_stats(DirectStrategy::mis, 4, 4, MisHeuristic::balance);
    CAPTURE(expected);
    CAPTURE(s.mean);
    CAPTURE(s.standard_error);
    CHECK(std::fabs(s.z(expected)) <= 4.0);  // significance 6.3e-5 (tiny_render.h)
    CHECK(s.standard_error < 0.02 * expected);
    // The heuristic is in use: the same seed gives another image than the power heuristic.
    CHECK(s.mean != render_stats(DirectStrategy::mis, 4, 4).mean);
}
