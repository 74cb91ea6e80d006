// Rng: the PCG32 random number generator (O'Neill 2014, pcg-random.org,
// "PCG: A Family of Simple Fast Space-Efficient Statistically Good
// Algorithms for Random Number Generation"), 64-bit state, 32-bit output.
//
// Determinism: every camera sample gets its own generator, seeded from
// (seed, pixel index, sample index). So a pixel's value never depends on
// which thread rendered it or in which order: same seed, same image, at any
// thread count. The generator is always passed explicitly, never global.
//
// With a sampler (`--sampler`, core/sampler.h), next_1d and next_2d hand out
// the sampler's values instead, one dimension after the other from a
// counter, in the order that core/sampler.h documents; seek() jumps to a
// bounce's slot. Integers (next_u32, next_index) always come from PCG32.
// Without a sampler (independent sampling) the values are exactly those of
// PCG32, as before samplers existed.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/sampler.h"
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
    /// The generator of stream `stream` (not 0) of a camera sample: for
    /// numbers that must be independent of the sample's own, such as the
    /// samples that adaptive sampling's stopping rule looks at.
    static Rng substream(uint64_t seed, uint64_t pixel_index, uint64_t sample_index, uint64_t stream) {
        return Rng(seed, pixel_index, sample_index, stream);
    }
    /// A generator for a single stream, for tests and tools.
    explicit Rng(uint64_t seed = 0) { set_sequence(mix(seed), mix(seed + 1)); }
    /// The generator of camera sample `sample_index` of pixel (x, y) that
    /// draws from `sampler` (see the file comment); pixel_index = y * width + x.
    Rng(const Sampler& sampler, uint32_t x, uint32_t y, uint64_t pixel_index, uint64_t sample_index)
        : Rng(sampler.settings().seed, pixel_index, sample_index, 0) {
        sampler_ = &sampler;
        sample_ = sampler.start(x, y, sample_index);
    }

    /// The sampler this generator draws from, or null (independent sampling).
    const Sampler* sampler() const { return sampler_; }
    /// The next dimension a sampler's value comes from.
    uint32_t dimension() const { return dimension_; }
    /// Continues at `dimension` unless dimensions at or past it were
    /// already used (a dimension is never used twice in one sample).
    void seek_dimension(uint32_t dimension) { dimension_ = std::max(dimension_, dimension); }
    /// Continues at the first dimension of `slot` in the block of the
    /// vertex of depth `depth` (core/sampler.h); nothing without a sampler.
    void seek(int depth, SampleSlot slot) {
        if (sampler_) seek_dimension(sampler_->slot_dimension(depth, slot));
    }

    /// Uniform 32-bit integer.
    uint32_t next_u32() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    /// Uniform in [0, 1): multiples of 2^-32, so never exactly 1 (with a
    /// sampler: its next dimension).
    double next_1d() {
        if (sampler_) return sampler_->get_1d(sample_, dimension_++);
        return next_u32() * 0x1p-32;
    }
    /// The next two dimensions as one 2D point.
    Vec2 next_2d() {
        if (sampler_) {
            Vec2 u = sampler_->get_2d(sample_, dimension_);
            dimension_ += 2;
            return u;
        }
        double u = next_u32() * 0x1p-32;
        return {u, next_u32() * 0x1p-32};
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
    const Sampler* sampler_ = nullptr;  ///< null: independent PCG32 values
    PixelSample sample_;                ///< with a sampler: which sample of which pixel
    uint32_t dimension_ = 0;            ///< with a sampler: the next dimension
};

}  // namespace pt
