// Photons and photon maps (stages/photon.h):
//   - the flux of emitted photons sums to the lights' power, for area,
//     point, directional and environment lights together (z-test at 4.5
//     standard errors, two-sided 7e-6);
//   - each kernel integrates to 1: the density estimate of photons spread
//     uniformly over a plane is their density times their flux (z-test,
//     4.5 standard errors);
//   - under a point light above a diffuse plane, the map's radiance
//     estimate converges to the closed form albedo/pi * I cos / d^2 as the
//     photons grow and the radius shrinks (bias and spread reported);
//   - only specular-then-diffuse paths reach the caustic map; the photons
//     are the same at any thread count.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>

#include "core/math.h"
#include "render/integrators.h"
#include "scene/scene_loader.h"
#include "stages/photon.h"
#include "stages/render_context.h"

using namespace pt;

namespace {

/// A scene, its accelerator and a render context over the reference stages.
struct Setup {
    Scene scene;
    Stages stages = make_stages(StageSet::none());
    RenderSettings settings;
    std::unique_ptr<Accelerator> accelerator;
    std::unique_ptr<Integrator> integrator = make_path_integrator();
    std::unique_ptr<RenderContext> context;

    explicit Setup(const std::string& json) : scene(parse_json_scene(json, "photons.json")) {
        accelerator = build_accelerator(scene, stages, AcceleratorSettings());
        context = std::make_unique<RenderContext>(scene, *accelerator, stages, settings, *integrator);
    }
};

/// A diffuse floor y = 0 of albedo 0.5 (40 x 40 around the origin) and `lights`.
std::string floor_scene(const std::string& extra_objects, const std::string& lights) {
    return R"({"camera": {"position": [0, 5, -10], "look_at": [0, 0, 0]}, "film": {"width": 8, "height": 8},
        "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
                      "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [4, 2, 1]},
                      "chrome": {"type": "mirror", "reflectance": [1, 1, 1]}},
        "objects": [{"type": "quad", "corner": [-20, 0, -20], "edge1": [0, 0, 40], "edge2": [40, 0, 0], "material": "grey"})" +
           extra_objects + R"(],
        "lights": [)" + lights + "]}";
}

}  // namespace

TEST_CASE("emitted photon flux sums to the power of every light kind") {
    Setup s(floor_scene(R"(, {"type": "quad", "corner": [-1, 3, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "lamp"})",
                        R"({"type": "point", "position": [0, 2, 0], "intensity": [3, 3, 3]},
                           {"type": "directional", "direction": [0, -1, 0.2], "irradiance": [0.5, 1, 0.5]},
                           {"type": "environment", "radiance": [0.1, 0.2, 0.3]})"));
    Color power;
    for (const auto& light : s.context->lights.all()) power += light->power();
    const uint64_t n = 200000;
    Rng rng(3);
    Color sum, sum2;
    for (uint64_t i = 0; i < n; ++i) {
        double p = 0;
        const Light* light = s.context->lights.sample_by_power(rng.next_1d(), &p);
        REQUIRE(light);
        Vec2 u_pos = rng.next_2d(), u_dir = rng.next_2d();
        EmittedPhoton e = reference::emit_photon(*light, p, n, u_pos, u_dir);
        if (!e.valid) continue;
        sum += e.flux;
        sum2 += e.flux * e.flux * double(n);  // n * flux = one sample of the power
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c];  // sum of flux = mean of n * flux
        const double variance = (sum2[c] - mean * mean) / double(n);
        CAPTURE(c);
        CHECK(std::fabs(mean - power[c]) <= 4.5 * std::sqrt(variance) + 1e-9 * power[c]);
    }
}

TEST_CASE("every kernel integrates to 1: a uniform photon density is estimated without bias") {
    // Photons uniform on [0, 10]^2 with density rho per unit area and flux
    // phi each; at the centre, E[estimate] = rho phi (the kernel's integral)
    // and Var = rho phi^2 integral K^2 (Poisson points): a z-test per kernel.
    Rng rng(5);
    const int n = 200000;
    const double side = 10, rho = n / (side * side), phi = 0.01, radius2 = 0.3 * 0.3;
    std::vector<Vec3> points(n);
    for (Vec3& p : points) p = {side * rng.next_1d(), side * rng.next_1d(), 0};
    KdTree tree = reference::build_kdtree(points);
    // integral of K^2 over the disk, times pi r^2 ... per kernel (closed forms):
    // box 1/(pi r^2), cone 3 * 9/(pi r^2) * (1/6) = 9/(2 pi r^2) (K = 3(1-s)/(pi r^2)),
    // Epanechnikov 4/(pi r^2) * (1/3) = 4/(3 pi r^2).
    struct Case { PhotonKernel kernel; double k2; };
    const Case cases[] = {{PhotonKernel::box, 1.0}, {PhotonKernel::cone, 4.5}, {PhotonKernel::epanechnikov, 4.0 / 3.0}};
    for (const Case& c : cases) {
        Color total;
        int queries = 0;
        std::vector<Neighbor> found;
        std::vector<PhotonContribution> contributions;
        // Queries 1 apart: disjoint disks, independent estimates.
        for (int qx = 2; qx <= 8; ++qx)
            for (int qy = 2; qy <= 8; ++qy) {
                within_radius(tree, Vec3(qx, qy, 0), radius2, found);
                contributions.clear();
                for (const Neighbor& nb : found) contributions.push_back({nb.dist2, Color(phi)});
                total += reference::density_estimate(contributions, radius2, c.kernel);
                ++queries;
            }
        const double mean = total.r / queries, expected = rho * phi;
        const double sigma = std::sqrt(rho * phi * phi * c.k2 / (kPi * radius2) / queries);
        CAPTURE(to_string(c.kernel));
        CHECK(std::fabs(mean - expected) <= 4.5 * sigma);
    }
    CHECK(reference::density_estimate({}, radius2, PhotonKernel::cone).is_black());
}

TEST_CASE("photon map radiance on a plane under a point light converges to the closed form") {
    // I = 10 W/sr at height 2: E(x) = I h / d^3, L = (0.5 / pi) E. At the
    // point below the light, E = 2.5 and L = 0.3979. Bias falls with r^2
    // (E is curved there), noise with the photons in the disk.
    Setup s(floor_scene("", R"({"type": "point", "position": [0, 2, 0], "intensity": [10, 10, 10]})"));
    const double expected = 0.5 / kPi * 10 * 2 / 8;
    std::optional<SurfaceInteraction> hit = s.context->intersect(Ray(Vec3(0, 1, 0), Vec3(0, -1, 0)));
    REQUIRE(hit);
    SurfaceInteraction x = *hit;
    x.p = Vec3(0, 0, 0);
    const BSDF bsdf = s.context->bsdf_at(x);
    double previous_error = 1e300;
    // The tolerance of each step covers its bias (about r^2 relative) and
    // 4 standard errors of its noise (the ring's spread / sqrt 8).
    struct Step { uint64_t photons; double radius, tolerance; };
    for (Step step : {Step{20000, 0.4, 0.15}, Step{200000, 0.15, 0.06}}) {
        PhotonMap map = make_photon_map(*s.context, trace_photons(*s.context, {step.photons, PhotonPaths::all, 9}, 2),
                                        step.photons);
        // Several points on the circle of radius 0.5 share the closed form
        // E = I h / d^3: their spread estimates the noise.
        const double d = std::sqrt(4 + 0.25), closed = 0.5 / kPi * 10 * 2 / (d * d * d);
        double sum = 0, sum2 = 0;
        const int points = 8;
        for (int i = 0; i < points; ++i) {
            SurfaceInteraction y = x;
            y.p = Vec3(0.5 * std::cos(kTwoPi * i / points), 0, 0.5 * std::sin(kTwoPi * i / points));
            const double L = photon_radiance(*s.context, map, y, bsdf, {0, step.radius * step.radius, PhotonKernel::box}).r;
            sum += L / closed;
            sum2 += (L / closed) * (L / closed);
        }
        const double mean = sum / points, spread = std::sqrt(std::max(0.0, sum2 / points - mean * mean));
        const double centre = photon_radiance(*s.context, map, x, bsdf, {0, step.radius * step.radius, PhotonKernel::box}).r;
        const double error = std::fabs(centre / expected - 1);
        MESSAGE("photons " << step.photons << ", r " << step.radius << ": centre L / closed form = " << centre / expected
                           << ", ring mean " << mean << " (spread " << spread << ")");
        CHECK(error < step.tolerance);
        CHECK(std::fabs(mean - 1) < step.tolerance);
        CHECK(error < previous_error);
        previous_error = error;
    }
}

TEST_CASE("the caustic map holds only specular-then-diffuse paths; photons do not depend on the threads") {
    const std::string light = R"({"type": "point", "position": [0, 2, 0], "intensity": [10, 10, 10]})";
    Setup diffuse_only(floor_scene("", light));
    CHECK(trace_photons(*diffuse_only.context, {20000, PhotonPaths::caustic, 1}, 2).empty());

    // A mirror above the light throws light onto the floor: caustic photons,
    // all of whose paths bounced once on the mirror before the floor.
    Setup mirror(floor_scene(R"(, {"type": "quad", "corner": [-3, 4, -3], "edge1": [6, 0, 0], "edge2": [0, 0, 6], "material": "chrome"})", light));
    std::vector<Photon> caustic = trace_photons(*mirror.context, {20000, PhotonPaths::caustic, 1}, 1);
    CHECK(caustic.size() > 1000);
    for (const Photon& p : caustic) {
        CHECK(p.bounces == 2);
        CHECK(std::fabs(p.p.y) < 1e-9);
    }
    std::vector<Photon> again = trace_photons(*mirror.context, {20000, PhotonPaths::caustic, 1}, 3);
    REQUIRE(again.size() == caustic.size());
    for (size_t i = 0; i < caustic.size(); ++i) {
        CHECK(again[i].p == caustic[i].p);
        CHECK(again[i].flux.r == caustic[i].flux.r);
    }
}
