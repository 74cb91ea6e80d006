// adaptive_bias: the bias of the two adaptive rules (--adaptive split and
// cs184) on the interior furnace, whose expected value is known, over
// many seeds: docs/sampling.md's table and issue 16's target ("the
// adaptive reference's furnace mean within 3 standard errors of the closed
// form over 20 seeds").
//
//   build/tests/adaptive_bias [SEEDS] [SIZE] [SPP] [BATCH] [TOL]     (20 24 512 16 0.05)
//
// The furnace: the box [-1, 1]^3 whose walls emit 0.5 and reflect 0.5,
// -m 3 -o 1: every pixel's expected value is 0.5 (1 - 0.5^4) / 0.5 = 0.9375.
// Light sampling (the default strategy), as in issue 16. Per rule: the
// image mean of each seed, the mean over seeds, its standard error from
// the spread over seeds, z = (mean - 0.9375) / standard error, and the
// mean samples per pixel.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "global/global_render.h"

using namespace pt;
using namespace pt::global_test;

int main(int argc, char** argv) {
    const int seeds = argc > 1 ? std::atoi(argv[1]) : 20;
    const int size = argc > 2 ? std::atoi(argv[2]) : 24;
    const int spp = argc > 3 ? std::atoi(argv[3]) : 512;
    const int batch = argc > 4 ? std::atoi(argv[4]) : 16;
    const double tolerance = argc > 5 ? std::atof(argv[5]) : 0.05;
    const double rho[3] = {0.5, 0.5, 0.5}, le[3] = {0.5, 0.5, 0.5};
    const double expected = 0.9375;
    Scene box = scene_from(closed_box(glowing_wall(rho, le), size));
    std::printf("| rule | seeds | mean of the image means | standard error | z | mean spp |\n|---|--:|--:|--:|--:|--:|\n");
    for (AdaptiveRule rule : {AdaptiveRule::split, AdaptiveRule::cs184}) {
        std::vector<double> means;
        double samples = 0;
        for (int seed = 1; seed <= seeds; ++seed) {
            RenderSettings settings = path_settings(3, spp, uint64_t(seed));
            settings.adaptive = true;
            settings.samples_per_batch = batch;
            settings.max_tolerance = tolerance;
            settings.adaptive_rule = rule;
            RenderResult r = render(box, settings);
            means.push_back(channel_stats(r.image, 1).mean);
            samples += double(r.counters.camera_rays) / (size * size);
        }
        double m = 0, v = 0;
        for (double x : means) m += x;
        m /= seeds;
        for (double x : means) v += (x - m) * (x - m);
        double se = std::sqrt(v / (seeds - 1) / seeds);
        std::printf("| %s | %d | %.5f | %.5f | %.2f | %.1f |\n", to_string(rule), seeds, m, se, (m - expected) / se,
                    samples / seeds);
    }
    return 0;
}
