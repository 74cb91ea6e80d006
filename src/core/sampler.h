// Samplers: where the random numbers of a camera sample come from
// (`--sampler`, pbrt-v4's names and meanings, pbrt-v4 chapter 8).
//
//   independent  PCG32, one stream per (seed, pixel, sample): O(N^-1) MSE
//   stratified   per pixel and dimension, N jittered strata (nx by ny in 2D)
//                in an order shuffled per dimension (pbrt-v4 StratifiedSampler)
//   halton       Halton points over the whole image, the pixel found from
//                dimensions 0 and 1 (bases 2 and 3), random digit
//                permutations in every dimension (pbrt-v4 HaltonSampler)
//   sobol        Sobol points over the whole image, the pixel found from
//                dimensions 0 and 1, Owen-scrambled within the pixel; later
//                dimensions padded (below)
//   zsobol       per pixel: the Sobol (0,2)-sequence indexed in Morton order
//                of the pixels with random base-4 digit permutations (Ahmed
//                and Wonka 2020, "Screen-Space Blue-Noise Diffusion of Monte
//                Carlo Sampling Error via Hierarchical Ordering of Pixels";
//                pbrt-v4 ZSobolSampler), Owen-scrambled
//
// Every value is a function of (seed, pixel, sample index, dimension) only:
// the same at any thread count and in any order of pixels.
//
// Dimensions, in one documented order (docs/sampling.md): 0-1 the point in
// the pixel, 2-3 the lens, then one block per bounce (vertex depth d, the
// camera ray's hit has d = 0) starting at 4 + d * stride:
//     +0 light choice (reserved: the reference samples every light)
//     +1 light 2D (the first light sample; further ones follow it)
//     +1 + 2L BSDF 2D, +3 + 2L Russian roulette,
// with L the light samples per shading point and stride = 4 + 2L, so the
// same decision meets the same dimension in every path. A stage seeks its
// slot (Rng::seek); code that does not seek reads dimensions in order.
//
// Unbiased: each sampler randomises (jitter, digit permutations, Owen
// scrambling), so every single sample is uniform in [0, 1)^dims and every
// estimate keeps its expected value; only the correlation between the N
// samples of a pixel changes, and with it the convergence rate.
//
// Padding: the project derives only Sobol dimensions 0 and 1, so sobol
// and zsobol draw every 1D or 2D value from those two with an index
// shuffled per dimension and a scramble per dimension (Burley 2020,
// "Practical Hash-based Owen Scrambling"; pbrt-v4 PaddedSobolSampler):
// each draw is a scrambled (0,2)-sequence on its own, decorrelated from the
// others. Halton pads past its 128th prime (719) with independent values.
//
// Tests: tests/unit/test_sampler.cpp (determinism, one sample per stratum,
// uniformity by chi-square, the pixel mapping of the global samplers),
// tests/statistical/test_sampler_rates.cpp (convergence rates).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/low_discrepancy.h"
#include "core/vec3.h"

namespace pt {

enum class SamplerKind : uint8_t { independent, stratified, halton, sobol, zsobol };

const char* to_string(SamplerKind kind);
/// "independent" ... "zsobol"; throws InputError naming `flag` otherwise.
SamplerKind parse_sampler_kind(const std::string& name, const std::string& flag = "--sampler");
/// Every kind, in the order of the --sampler help.
const std::vector<SamplerKind>& all_sampler_kinds();

/// Where a stage's draws start within a bounce's block of dimensions (above).
enum class SampleSlot : uint8_t { light_choice, light, bsdf, roulette };

/// The functions of stage `sampler` (stages/sampler.h) that a sampler calls:
/// the reference's, or a student's.
struct SamplerFunctions {
    /// The point of stratum `stratum` (row-major, 0 <= stratum < nx * ny) of
    /// an nx by ny grid over [0, 1)^2, moved within it by `jitter` in [0, 1)^2.
    Vec2 (*stratified_sample_2d)(int stratum, int nx, int ny, Vec2 jitter) = nullptr;
    /// The radical inverse of `index` in base permutation.base(), digit k
    /// replaced by permutation(k, digit), in [0, 1).
    double (*scrambled_radical_inverse)(uint64_t index, const DigitPermutation& permutation) = nullptr;
};

/// What a sampler needs to know about the render.
struct SamplerSettings {
    SamplerKind kind = SamplerKind::independent;
    uint64_t seed = 0;
    int spp = 1;                  ///< samples per pixel (the maximum with -a)
    int width = 1, height = 1;    ///< the film
    int light_samples_per_vertex = 1;  ///< L above: light 2D draws at a shading point
};

/// Which sample of which pixel a generator serves.
struct PixelSample {
    uint32_t x = 0, y = 0;
    uint64_t index = 0;      ///< sample index within the pixel
    uint64_t pixel_key = 0;  ///< hash of (seed, pixel): the per-pixel randomisation
    uint64_t global_index = 0;  ///< halton, sobol: index of the point in the global sequence;
                                ///< zsobol: the pixel's Morton code, then the sample index's bits
};

class Sampler {
public:
    Sampler(const SamplerSettings& settings, const SamplerFunctions& functions);
    ~Sampler();
    Sampler(const Sampler&) = delete;
    Sampler& operator=(const Sampler&) = delete;

    SamplerKind kind() const { return settings_.kind; }
    const SamplerSettings& settings() const { return settings_; }
    /// The first dimension of `slot` in the block of vertex depth `depth`.
    uint32_t slot_dimension(int depth, SampleSlot slot) const;

    /// Starts sample `index` of pixel (x, y).
    PixelSample start(uint32_t x, uint32_t y, uint64_t index) const;
    /// The value of dimension `dimension` of that sample, in [0, 1).
    double get_1d(const PixelSample& sample, uint32_t dimension) const;
    /// Dimensions `dimension` and `dimension + 1` drawn as one 2D point
    /// (stratified in 2D where the sampler can).
    Vec2 get_2d(const PixelSample& sample, uint32_t dimension) const;

    /// stratified: the grid of 2D strata for spp samples, nx * ny = spp with
    /// nx the largest divisor of spp not above its square root.
    int strata_x() const { return strata_x_; }
    int strata_y() const { return strata_y_; }

private:
    struct Tables;
    double halton_value(const PixelSample& sample, uint32_t dimension) const;
    uint32_t sobol_pixel_fraction(const PixelSample& sample, int axis) const;
    /// zsobol: the permuted index of the sample in dimension `dimension`;
    /// `reversed_dim1`, when not null, receives the first 32 digits of Sobol
    /// dimension 1 of that index in reverse order (what its scramble needs).
    uint64_t zsobol_index(const PixelSample& sample, uint32_t dimension, uint32_t* reversed_dim1 = nullptr) const;
    /// zsobol's hash key of a dimension: 0 the index permutation, 1 and 2 the scrambles of 1D and 2D draws.
    uint64_t zsobol_key(uint32_t dimension, int purpose) const;
    Vec2 padded_sobol_2d(uint64_t index, uint64_t key) const;

    SamplerSettings settings_;
    SamplerFunctions functions_;
    int strata_x_ = 1, strata_y_ = 1;
    uint64_t id_ = 0;  ///< unique per sampler of the process: zsobol's per-thread cache knows whose digits it holds
    std::unique_ptr<Tables> tables_;
};

}  // namespace pt
