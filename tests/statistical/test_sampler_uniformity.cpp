// Unbiasedness of the samplers (core/sampler.h): a sampler's value for one
// (pixel, sample index, dimension) must be uniform in [0, 1) (or [0, 1)^2)
// over its randomisation (the seed: jitter, digit permutations, Owen
// scrambling), or an estimate made from it would be biased. Pearson's
// chi-square test over 1024 seeds, per sampler, in four places: the point
// in the pixel (2D, dimensions 0-1), a bounce's light sample (2D at
// dimension 5), a roulette draw (1D at dimension 9), and a padded dimension
// (2D at 300, past every sequence's own dimensions). Significance: the
// suite's Sidak-corrected level (statistical/chi2.h).
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "core/sampler.h"
#include "stages/sampler.h"
#include "statistical/chi2_check.h"

namespace pt {

TEST_CASE("every sampler's values are uniform over its randomisation, in the pixel, a bounce, and past its dimensions") {
    constexpr int kSeeds = 1024, kCells = 16;  // 4 x 4 in 2D, 16 bins in 1D: 64 expected per cell
    for (SamplerKind kind : {SamplerKind::stratified, SamplerKind::halton, SamplerKind::sobol, SamplerKind::zsobol}) {
        std::vector<std::vector<double>> counts(4, std::vector<double>(kCells, 0));
        for (uint64_t seed = 0; seed < kSeeds; ++seed) {
            SamplerSettings s;
            s.kind = kind, s.seed = seed * 7919 + 11, s.spp = 16, s.width = 40, s.height = 30;
            Sampler sampler(s, {reference::stratified_sample_2d, reference::scrambled_radical_inverse});
            PixelSample sample = sampler.start(13, 21, 6);
            auto cell2 = [](Vec2 u) { return size_t(int(u.x * 4) + 4 * int(u.y * 4)); };
            ++counts[0][cell2(sampler.get_2d(sample, 0))];
            ++counts[1][cell2(sampler.get_2d(sample, 5))];
            ++counts[2][size_t(sampler.get_1d(sample, 9) * kCells)];
            ++counts[3][cell2(sampler.get_2d(sample, 300))];
        }
        const char* where[] = {"pixel 2D", "light 2D at dimension 5", "roulette 1D at dimension 9", "padding 2D at dimension 300"};
        for (int w = 0; w < 4; ++w) {
            INFO(std::string(to_string(kind)) << ", " << where[w]);
            stats::check_passes(stats::chi2_test(counts[size_t(w)], std::vector<double>(kCells, double(kSeeds) / kCells),
                                                 stats::per_test_significance()));
        }
    }
}

}  // namespace pt
