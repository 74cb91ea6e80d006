// The samplers of core/sampler.h and their building blocks
// (core/hash.h, core/low_discrepancy.h): exact properties, checked exactly.
// Uniformity (chi-square) and convergence rates are in tests/statistical.
#include <doctest/doctest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "core/low_discrepancy.h"
#include "core/rng.h"
#include "core/sampler.h"
#include "stages/sampler.h"

namespace pt {
namespace {

const SamplerFunctions kReference{reference::stratified_sample_2d, reference::scrambled_radical_inverse};

SamplerSettings settings_of(SamplerKind kind, int spp, int width = 16, int height = 12, uint64_t seed = 3) {
    SamplerSettings s;
    s.kind = kind, s.spp = spp, s.width = width, s.height = height, s.seed = seed;
    return s;
}

/// Whether `points` (2^m of them in [0,1)^2) put exactly one point in each
/// elementary box 2^-p by 2^-(m-p), for every p: a (0, m, 2)-net in base 2.
bool is_02_net(const std::vector<Vec2>& points) {
    int m = 0;
    while ((size_t(1) << m) < points.size()) ++m;
    for (int p = 0; p <= m; ++p) {
        std::vector<int> count(points.size(), 0);
        for (Vec2 u : points) {
            size_t cx = size_t(u.x * double(1 << p)), cy = size_t(u.y * double(1 << (m - p)));
            if (++count[cy * (size_t(1) << p) + cx] > 1) return false;
        }
    }
    return true;
}

}  // namespace

TEST_CASE("permute_index is a bijection of [0, n) for every n and seed") {
    for (uint32_t n = 1; n <= 300; ++n) {
        for (uint64_t seed : {0ull, 1ull, 0xDEADBEEFull, 0x123456789ABCDEFull}) {
            std::vector<bool> seen(n, false);
            for (uint32_t i = 0; i < n; ++i) {
                uint32_t j = permute_index(i, n, seed);
                REQUIRE(j < n);
                REQUIRE(!seen[j]);
                seen[j] = true;
            }
        }
    }
    // Different seeds give different permutations.
    int differ = 0;
    for (uint32_t i = 0; i < 64; ++i) differ += permute_index(i, 64, 1) != permute_index(i, 64, 2);
    CHECK(differ > 32);
}

TEST_CASE("Sobol dimensions 0 and 1: the first points, and a (0,2)-sequence") {
    auto point = [](uint64_t a) {
        return Vec2(double(sobol_dimension0(a) >> 11) * 0x1p-53, double(sobol_dimension1(a) >> 11) * 0x1p-53);
    };
    CHECK(point(0).x == 0);
    CHECK(point(1).x == 0.5);
    CHECK(point(1).y == 0.5);
    CHECK(point(2).x == 0.25);
    CHECK(point(2).y == 0.75);
    CHECK(point(3).x == 0.75);
    CHECK(point(3).y == 0.25);
    // Every aligned block of 2^m points is a (0, m, 2)-net.
    for (int m : {4, 6, 8}) {
        for (uint64_t block : {0ull, 1ull, 5ull}) {
            std::vector<Vec2> points;
            for (uint64_t a = block << m; a < ((block + 1) << m); ++a) points.push_back(point(a));
            CHECK(is_02_net(points));
        }
    }
}

TEST_CASE("Owen scrambling keeps a net a net, and changes the points") {
    std::vector<Vec2> scrambled;
    int moved = 0;
    for (uint64_t a = 0; a < 256; ++a) {
        uint32_t x = uint32_t(sobol_dimension0(a) >> 32), y = uint32_t(sobol_dimension1(a) >> 32);
        uint32_t sx = owen_scramble(x, 0x1234567u), sy = owen_scramble(y, 0x89ABCDEu);
        moved += sx != x;
        scrambled.push_back({binary_fraction(sx), binary_fraction(sy)});
    }
    CHECK(is_02_net(scrambled));
    CHECK(moved > 200);
}

TEST_CASE("radical inverses: exact values, the identity permutation, and the digit tail") {
    DigitPermutation base2 = DigitPermutation::identity(2), base3 = DigitPermutation::identity(3);
    CHECK(base2.digits() == 53);
    CHECK(base3.digits() == 33);
    CHECK(reference::scrambled_radical_inverse(6, base2) == 0.375);          // 110 -> 0.011
    CHECK(reference::scrambled_radical_inverse(5, base3) == doctest::Approx(2.0 / 3 + 1.0 / 9).epsilon(1e-15));  // 12 -> 0.21
    CHECK(reference::scrambled_radical_inverse(0, base3) == 0);
    // With random permutations, the shortcut over the zero digits equals the
    // full loop over every position (the contract of stages/sampler.h).
    for (int base : {2, 3, 5, 7, 29, 1619}) {
        DigitPermutation perm(base, 99);
        for (uint64_t index : {0ull, 1ull, 2ull, 12345ull, 987654321ull}) {
            uint64_t reversed = 0, a = index;
            for (int k = 0; k < perm.digits(); ++k, a /= uint64_t(base))
                reversed = reversed * uint64_t(base) + uint64_t(perm(k, int(a % uint64_t(base))));
            double full = std::min(double(reversed) / double(perm.power(perm.digits())), 0x1.fffffffffffffp-1);
            CHECK(reference::scrambled_radical_inverse(index, perm) == full);
        }
        // Each position is a permutation of the digits.
        for (int k = 0; k < perm.digits(); ++k) {
            std::set<int> images;
            for (int d = 0; d < base; ++d) images.insert(perm(k, d));
            CHECK(int(images.size()) == base);
        }
    }
}

TEST_CASE("stratified: each pixel's N samples put one point in each of the nx by ny strata, in every 2D dimension") {
    for (int spp : {1, 2, 7, 16, 32, 36}) {
        Sampler sampler(settings_of(SamplerKind::stratified, spp), kReference);
        CHECK(sampler.strata_x() * sampler.strata_y() == spp);
        CHECK(sampler.strata_x() <= sampler.strata_y());
        for (uint32_t dim : {0u, 2u, 7u, 40u}) {
            std::vector<int> count(size_t(spp), 0);
            std::vector<int> count1d(size_t(spp), 0);
            for (int i = 0; i < spp; ++i) {
                PixelSample s = sampler.start(5, 3, uint64_t(i));
                Vec2 u = sampler.get_2d(s, dim);
                int cx = int(u.x * sampler.strata_x()), cy = int(u.y * sampler.strata_y());
                ++count[size_t(cy * sampler.strata_x() + cx)];
                ++count1d[size_t(sampler.get_1d(s, dim) * spp)];
            }
            CHECK(std::all_of(count.begin(), count.end(), [](int c) { return c == 1; }));
            CHECK(std::all_of(count1d.begin(), count1d.end(), [](int c) { return c == 1; }));
        }
    }
}

TEST_CASE("sobol and zsobol: 16 samples of a pixel are a (0,4,2)-net in the pixel and in later 2D dimensions") {
    for (SamplerKind kind : {SamplerKind::sobol, SamplerKind::zsobol}) {
        Sampler sampler(settings_of(kind, 16), kReference);
        for (uint32_t dim : {0u, 4u, 9u, 300u}) {
            std::vector<Vec2> points;
            for (int i = 0; i < 16; ++i) points.push_back(sampler.get_2d(sampler.start(7, 2, uint64_t(i)), dim));
            INFO(to_string(kind) << " dimension " << dim);
            CHECK(is_02_net(points));
        }
    }
}

TEST_CASE("the global samplers find the pixel: halton's and sobol's global index lands in its pixel") {
    Sampler halton(settings_of(SamplerKind::halton, 8, 300, 200), kReference);
    Sampler sobol(settings_of(SamplerKind::sobol, 8, 300, 200), kReference);
    for (uint32_t y : {0u, 1u, 77u, 199u}) {
        for (uint32_t x : {0u, 5u, 127u, 128u, 299u}) {
            for (uint64_t i : {0ull, 1ull, 7ull}) {
                // Halton: the first base-2 digits mirror x mod 128, the first base-3 digits y mod 243.
                uint64_t h = halton.start(x, y, i).global_index;
                double phi2 = reference::scrambled_radical_inverse(h, DigitPermutation::identity(2));
                double phi3 = reference::scrambled_radical_inverse(h, DigitPermutation::identity(3));
                CHECK(uint32_t(phi2 * 128) == x % 128);
                CHECK(uint32_t(phi3 * 243) == y % 243);
                // Sobol: the first 9 digits (512 >= 300) of dimensions 0 and 1 are x and y.
                uint64_t a = sobol.start(x, y, i).global_index;
                CHECK((sobol_dimension0(a) >> 55) == x);
                CHECK((sobol_dimension1(a) >> 55) == y);
                CHECK((a >> 18) == i);
            }
        }
    }
}

TEST_CASE("every sampler is a function of (seed, pixel, sample, dimension): any order, same values; other seeds differ") {
    for (SamplerKind kind : all_sampler_kinds()) {
        Sampler a(settings_of(kind, 16), kReference), b(settings_of(kind, 16), kReference);
        Sampler other(settings_of(kind, 16, 16, 12, 4), kReference);
        int differ = 0;
        for (int i = 15; i >= 0; --i) {
            PixelSample s = a.start(3, 4, uint64_t(i)), t = b.start(3, 4, uint64_t(i));
            for (uint32_t dim = 40; dim-- > 0;) {
                CHECK(a.get_1d(s, dim) == b.get_1d(t, dim));
                CHECK(a.get_2d(s, dim).x == b.get_2d(t, dim).x);
                double v = a.get_1d(s, dim);
                CHECK(v >= 0);
                CHECK(v < 1);
                differ += v != other.get_1d(other.start(3, 4, uint64_t(i)), dim);
            }
        }
        INFO(to_string(kind));
        CHECK(differ > 600);  // of 640
    }
}

TEST_CASE("zsobol: a pixel's cached digits give the values of a fresh computation, at every spp") {
    // zsobol keeps per thread what a pixel's draws share (its permuted Morton
    // digits, the first two sample digits' permutations, its part of Sobol
    // dimension 1). Drawing from two samplers in turn empties that cache
    // before every draw of `fresh`; `cached` draws a pixel's samples in a row.
    for (int spp : {1, 2, 4, 8, 16, 32, 64, 256}) {
        Sampler fresh(settings_of(SamplerKind::zsobol, spp, 64, 48), kReference),
            other(settings_of(SamplerKind::zsobol, spp, 64, 48), kReference),
            cached(settings_of(SamplerKind::zsobol, spp, 64, 48), kReference);
        std::vector<double> want;
        for (uint32_t y : {0u, 17u}) {
            for (uint32_t x : {0u, 5u, 63u}) {
                for (uint64_t i = 0; i < uint64_t(spp); ++i) {
                    PixelSample s = fresh.start(x, y, i), o = other.start(x, y, i);
                    for (uint32_t dim : {0u, 2u, 5u, 9u, 127u, 128u, 200u}) {
                        want.push_back(fresh.get_1d(s, dim));
                        (void)other.get_1d(o, dim);
                        Vec2 u = fresh.get_2d(s, dim);
                        (void)other.get_2d(o, dim);
                        want.push_back(u.x);
                        want.push_back(u.y);
                    }
                }
            }
        }
        size_t k = 0;
        for (uint32_t y : {0u, 17u}) {
            for (uint32_t x : {0u, 5u, 63u}) {
                for (uint64_t i = 0; i < uint64_t(spp); ++i) {
                    PixelSample s = cached.start(x, y, i);
                    for (uint32_t dim : {0u, 2u, 5u, 9u, 127u, 128u, 200u}) {
                        CAPTURE(spp);
                        CAPTURE(dim);
                        CHECK(cached.get_1d(s, dim) == want[k++]);
                        Vec2 u = cached.get_2d(s, dim);
                        CHECK(u.x == want[k++]);
                        CHECK(u.y == want[k++]);
                    }
                }
            }
        }
    }
}

TEST_CASE("Rng with a sampler: dimensions in order, seek never goes back, integers stay PCG32") {
    Sampler sampler(settings_of(SamplerKind::zsobol, 16), kReference);
    Rng rng(sampler, 2, 3, 3 * 16 + 2, 5);
    PixelSample s = sampler.start(2, 3, 5);
    Vec2 pixel = rng.next_2d();
    CHECK(pixel.x == sampler.get_2d(s, 0).x);
    CHECK(rng.dimension() == 2);
    rng.seek(0, SampleSlot::light);  // block of depth 0 starts at 4; light at +1
    CHECK(rng.dimension() == 5);
    CHECK(rng.next_1d() == sampler.get_1d(s, 5));
    rng.seek_dimension(3);  // never back
    CHECK(rng.dimension() == 6);
    CHECK(sampler.slot_dimension(1, SampleSlot::light_choice) == 10);  // stride 4 + 2 * 1
    CHECK(sampler.slot_dimension(2, SampleSlot::roulette) == 4 + 2 * 6 + 5);
    // Integers come from the PCG32 stream of (seed, pixel, sample).
    Rng plain(3, 3 * 16 + 2, 5);
    CHECK(rng.next_u32() == plain.next_u32());
    // Without a sampler, seek does nothing and the values are PCG32's.
    Rng a(3, 50, 5), b(3, 50, 5);
    a.seek(4, SampleSlot::roulette);
    CHECK(a.next_1d() == b.next_1d());
}

}  // namespace pt
