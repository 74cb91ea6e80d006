// Unbiased in the renderer: every sampler (core/sampler.h), and the
// `split` adaptive rule, render the interior furnace's closed form; CS184's
// adaptive rule does not (issue 16).
//
// The furnace (test_interior_furnace.cpp): a closed surface whose walls
// emit Le and reflect rho; with -m 3 and -o 1 every pixel's expected value
// is Le (1 - rho^4) / (1 - rho). Means within 4 standard errors of the
// pixel spread (a correct estimator fails one check with probability
// 6.3e-5; the seeds are fixed).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "global/global_render.h"

using namespace pt;
using namespace pt::global_test;

namespace {

const double kRho[3] = {0.5, 0.5, 0.5};
const double kLe[3] = {0.5, 0.5, 0.5};
const double kExpected = 0.5 * (1 - std::pow(0.5, 4)) / 0.5;  // 0.9375, -m 3

Scene furnace_box(int size) { return scene_from(closed_box(glowing_wall(kRho, kLe), size)); }

}  // namespace

TEST_CASE("every sampler renders the furnace's closed form, with and without Russian roulette's draws") {
    Scene box = furnace_box(16);
    for (SamplerKind kind : all_sampler_kinds()) {
        for (int rr_depth : {3, 0}) {
            RenderSettings settings = path_settings(3, 16, 5);
            settings.direct = DirectStrategy::mis;  // light sampling alone has infinite variance in a box
            settings.sampler = kind;
            settings.rr_depth = rr_depth;
            RenderResult r = render(box, settings);
            PixelStats s = channel_stats(r.image, 1);
            INFO(std::string(to_string(kind)) << ", rr-depth " << rr_depth << ": mean " << s.mean << " +- "
                                              << s.standard_error << ", expected " << kExpected);
            CHECK(std::fabs(s.z(kExpected)) <= 4.0);
            CHECK(s.standard_error < 0.01);
        }
    }
}

TEST_CASE("adaptive sampling: the split rule is unbiased, CS184's rule is biased low on the furnace") {
    // Issue 16's case: -a 16 0.05 -m 3. CS184's rule stops the pixels whose
    // first samples ran low more often than the others, so its image is too
    // dark; the split rule decides from samples it never averages.
    Scene box = furnace_box(24);
    for (AdaptiveRule rule : {AdaptiveRule::split, AdaptiveRule::cs184}) {
        RenderSettings settings = path_settings(3, 512, 17);
        settings.adaptive = true;
        settings.samples_per_batch = 16;
        settings.max_tolerance = 0.05;
        settings.adaptive_rule = rule;
        RenderResult r = render(box, settings);
        PixelStats s = channel_stats(r.image, 1);
        double z = s.z(kExpected);
        INFO(std::string(to_string(rule)) << ": mean " << s.mean << " +- " << s.standard_error << " (z " << z << "), expected "
                             << kExpected);
        MESSAGE(std::string(to_string(rule)) << ": mean " << s.mean << " +- " << s.standard_error << " (z " << z << ")");
        if (rule == AdaptiveRule::split) {
            CHECK(std::fabs(z) <= 4.0);
        } else {
            CHECK(z < -5.0);
        }
    }
}
