// Chi-square test of the environment-map light (scene/lights.cpp over
// scene/environment_map.h): the directions sample_Li draws against pdf_Li,
// binned by the map's own pixels in (u, v). Radiance and the sampling
// density are constant over a pixel, so the expected count of a cell,
// n * integral pdf_Li(w) dw = n * integral pdf_Li 2 pi^2 sin(theta) du dv,
// is integrated exactly by the Gauss rule (the sin is smooth): a wrong
// sin(theta) or 2 pi^2 in the solid-angle conversion, or a wrong row or
// column choice, fails. 1 test.
#include <doctest/doctest.h>

#include <cmath>

#include "core/bbox.h"
#include "core/math.h"
#include "image/image_io.h"
#include "scene/environment_map.h"
#include "scene/lights.h"
#include "statistical/chi2_check.h"
#include "statistical/latlong_grid.h"
#include "test_util.h"

using namespace pt;
using namespace pt::stats;

TEST_CASE("chi2: environment map light, importance sampling by luminance") {
    std::string dir = test::scratch_dir("environment_sampling");
    std::string path = dir + "/sky.pfm";
    write_pfm(make_sky_image(64, 32, 30, 70), path);
    EnvironmentLight env;
    env.file = path;
    env.radiance = Color(1, 0.5, 2);
    env.scale = 3;
    BBox bounds(Vec3(-1), Vec3(1));
    std::unique_ptr<Light> light = make_environment_light(env, bounds);
    LightSampleContext ref{Vec3(0.1, 0.2, 0.3), Vec3(0, 1, 0)};
    EnvironmentMap map = EnvironmentMap::load(path, Color(3, 1.5, 6));
    int inconsistent = 0;
    auto sample = [&](Rng& rng) -> std::optional<Vec3> {
        LightSample s = light->sample_Li(ref, rng.next_2d());
        if (!s.valid()) return std::nullopt;
        // Radiance and pdf agree with Le and pdf_Li; the shadow-ray target
        // lies along wi, outside the scene.
        if (!(s.L == light->Le(s.wi)) || !(s.L == map.Le(s.wi))) ++inconsistent;
        if (std::fabs(s.pdf - light->pdf_Li(ref, s.wi, {}, {})) > 1e-9 * s.pdf) ++inconsistent;
        if (dot((s.p - ref.p).unit(), s.wi) < 1 - 1e-9 || (s.p - ref.p).norm() < 2) ++inconsistent;
        return s.wi;
    };
    Chi2Result r = chi2_sampling_test(
        LatLongGrid{}, sample, [&](const Vec3& w) { return light->pdf_Li(ref, w, {}, {}); },
        1000000, 77);
    check_passes(r);
    CHECK(inconsistent == 0);
}
