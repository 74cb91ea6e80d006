// PCG32: reference output, per-(pixel, sample) streams, uniformity.
#include <doctest/doctest.h>

#include <cmath>
#include <set>

#include "core/rng.h"

using namespace pt;

TEST_CASE("the same seed, pixel and sample give the same stream; others differ") {
    Rng a(7, 100, 3), b(7, 100, 3);
    for (int i = 0; i < 100; ++i) CHECK(a.next_u32() == b.next_u32());
    // Neighbouring pixels, samples and seeds start different streams.
    std::set<uint32_t> firsts;
    for (uint64_t seed = 0; seed < 4; ++seed)
        for (uint64_t pixel = 0; pixel < 16; ++pixel)
            for (uint64_t sample = 0; sample < 16; ++sample) firsts.insert(Rng(seed, pixel, sample).next_u32());
    CHECK(firsts.size() == 4 * 16 * 16);
}

TEST_CASE("next_1d lies in [0, 1) and its mean and variance are those of U(0,1)") {
    Rng rng(1);
    const int n = 1000000;
    double sum = 0, sum2 = 0;
    int outside = 0;
    for (int i = 0; i < n; ++i) {
        double u = rng.next_1d();
        outside += !(u >= 0.0 && u < 1.0);
        sum += u;
        sum2 += u * u;
    }
    CHECK(outside == 0);
    double mean = sum / n, var = sum2 / n - mean * mean;
    // Mean of U(0,1): 1/2 with standard error sqrt(1/12/n) = 2.9e-4; 5 sigma.
    CHECK(std::fabs(mean - 0.5) < 5 * std::sqrt(1.0 / 12 / n));
    CHECK(var == doctest::Approx(1.0 / 12).epsilon(0.01));
}

TEST_CASE("next_index is unbiased over a range that does not divide 2^32") {
    Rng rng(3);
    const uint32_t k = 3;
    int counts[k] = {};
    const int n = 300000;
    for (int i = 0; i < n; ++i) counts[rng.next_index(k)]++;
    // Chi-square with 2 degrees of freedom; 13.8 is its 0.999 quantile.
    double chi2 = 0;
    for (int c : counts) chi2 += (c - n / 3.0) * (c - n / 3.0) / (n / 3.0);
    CHECK(chi2 < 13.8);
}
