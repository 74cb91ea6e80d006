// Rng: the PCG32 random number generator (O'Neill 2014, pcg-random.org,
// "PCG: A Family of Simple Fast Space-Efficient Statistically Good
// Algorithms for Random Number Generation"), 64-bit state, 32-bit output.
//
// Determinism: every camera sample gets its own generator, seeded from
// (seed, pixel index, sample index). So a pixel's value never depends on
// which thread rendered it or in which order: same seed, same image, at any
// thread count. The generator is always passed explicitly, never global.
#pragma once

#include <cstdint>

#include "core/vec3.h"

namespace pt {

class Rng {
public:
    /// A generator for one camera sample (see the file comment).
    Rng(uint64_t seed, uint64_t pixel_index, uint64_t sample_index)
        : Rng(seed, pixel_index, sample_index, 0) {}
    /// The generator of a camera sample's lens position: a stream of its
    /// own, so that a pinhole camera, which draws no lens sample, leaves
    /// every other random number of the sample where it was.
    static Rng lens(uint64_t seed, uint64_t pixel_index, uint64_t sample_index) {
        return Rng(seed, pixel_index, sample_index, 0x6C656E73ull);  // "lens"
    }
    /// A generator for a single stream, for tests and tools.
    explicit Rng(uint64_t seed = 0) { set_sequence(mix(seed), mix(seed + 1)); }

    /// Uniform 32-bit integer.
    uint32_t next_u32() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    /// Uniform in [0, 1): multiples of 2^-32, so never exactly 1.
    double next_1d() { return next_u32() * 0x1p-32; }
    Vec2 next_2d() {
        double u = next_1d();
        return {u, next_1d()};
    }
    /// Uniform integer in [0, n) for n > 0 (Lemire's unbiased range reduction).
    uint32_t next_index(uint32_t n) {
        uint64_t m = uint64_t(next_u32()) * n;
        uint32_t low = static_cast<uint32_t>(m);
        if (low < n) {
            uint32_t threshold = (0u - n) % n;
            while (low < threshold) {
                m = uint64_t(next_u32()) * n;
                low = static_cast<uint32_t>(m);
            }
        }
        return static_cast<uint32_t>(m >> 32);
    }

private:
    Rng(uint64_t seed, uint64_t pixel_index, uint64_t sample_index, uint64_t stream) {
        // Two independent hashes: one picks the stream (increment), one the
        // starting state, so neighbouring pixels and samples are uncorrelated.
        uint64_t a = mix(seed ^ mix(pixel_index + 0x9E3779B97F4A7C15ull));
        if (stream != 0) a = mix(a ^ mix(stream));
        uint64_t b = mix(a ^ mix(sample_index + 0xD1B54A32D192ED03ull));
        set_sequence(b, a);
    }
    /// SplitMix64 finaliser (Steele et al. 2014): a bijective 64-bit hash.
    static uint64_t mix(uint64_t z) {
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// The seeding procedure of the PCG reference implementation.
    void set_sequence(uint64_t init_state, uint64_t stream) {
        state_ = 0;
        inc_ = (stream << 1u) | 1u;
        next_u32();
        state_ += init_state;
        next_u32();
    }

    uint64_t state_ = 0;  ///< the LCG state
    uint64_t inc_ = 1;    ///< the stream selector; always odd
};

}  // namespace pt
