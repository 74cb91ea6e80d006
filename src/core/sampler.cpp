// The five samplers of core/sampler.h. Each get_1d / get_2d is one switch
// on the kind (no virtual call); the student's functions of stage
// `sampler` are called through SamplerFunctions.
#include "core/sampler.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "core/error.h"

namespace pt {
namespace {

constexpr int kHaltonDimensions = 128;     // primes with a digit permutation; later dimensions are padded
constexpr uint32_t kHaltonMaxResolution = 128;  // the pixel tile of pbrt-v4's HaltonSampler
constexpr uint32_t kCachedKeys = 128;  // zsobol: dimensions whose hash keys are computed once

std::atomic<uint64_t> next_sampler_id{1};  // Sampler::id_

std::vector<int> first_primes(int count) {
    std::vector<int> primes;
    for (int n = 2; int(primes.size()) < count; ++n) {
        bool prime = true;
        for (int p : primes) {
            if (p * p > n) break;
            if (n % p == 0) {
                prime = false;
                break;
            }
        }
        if (prime) primes.push_back(n);
    }
    return primes;
}

/// x with 0 <= x < m and a * x = 1 (mod m), for a and m coprime.
uint64_t inverse_mod(uint64_t a, uint64_t m) {
    int64_t t = 0, new_t = 1, r = int64_t(m), new_r = int64_t(a % m);
    while (new_r != 0) {
        int64_t q = r / new_r;
        t -= q * new_t, std::swap(t, new_t);
        r -= q * new_r, std::swap(r, new_r);
    }
    return uint64_t(t < 0 ? t + int64_t(m) : t);
}

int ceil_log2(uint64_t n) {
    int k = 0;
    while ((uint64_t(1) << k) < n) ++k;
    return k;
}

/// The 24 permutations of {0, 1, 2, 3}: zsobol permutes base-4 digits.
struct Base4Permutations {
    std::array<std::array<uint8_t, 4>, 24> table{};
    Base4Permutations() {
        std::array<uint8_t, 4> p{0, 1, 2, 3};
        for (auto& entry : table) {
            entry = p;
            std::next_permutation(p.begin(), p.end());
        }
    }
};

}  // namespace

/// What a sampler precomputes once per render.
struct Sampler::Tables {
    // halton
    std::vector<DigitPermutation> permutations;  // one per dimension < kHaltonDimensions
    int exponent2 = 0, exponent3 = 0;             // the pixel tile: 2^exponent2 by 3^exponent3
    uint64_t scale2 = 1, scale3 = 1, inverse2 = 0, inverse3 = 0;
    // sobol: the inverse of the m x m block of C_1 that the pixel's row leaves to solve
    int log2_resolution = 0;
    std::vector<uint64_t> pixel_row_inverse;  // column k: the unknown bits that flip when row bit k flips
    // zsobol: per dimension, the keys of the index permutation and of the
    // scrambles (hashes of the seed and the dimension), for the first ones
    int morton_bits = 0, sample_bits = 0;
    std::vector<uint64_t> index_keys, scramble_keys_1d, scramble_keys_2d;
    Base4Permutations base4;
};

const char* to_string(SamplerKind kind) {
    switch (kind) {
        case SamplerKind::independent: return "independent";
        case SamplerKind::stratified: return "stratified";
        case SamplerKind::halton: return "halton";
        case SamplerKind::sobol: return "sobol";
        case SamplerKind::zsobol: return "zsobol";
    }
    return "?";
}

const std::vector<SamplerKind>& all_sampler_kinds() {
    static const std::vector<SamplerKind> kinds{SamplerKind::independent, SamplerKind::stratified,
                                                SamplerKind::halton, SamplerKind::sobol, SamplerKind::zsobol};
    return kinds;
}

SamplerKind parse_sampler_kind(const std::string& name, const std::string& flag) {
    for (SamplerKind kind : all_sampler_kinds())
        if (name == to_string(kind)) return kind;
    throw InputError(flag + ": expected one of independent, stratified, halton, sobol, zsobol, got '" + name + "'");
}

Sampler::Sampler(const SamplerSettings& settings, const SamplerFunctions& functions)
    : settings_(settings), functions_(functions), id_(next_sampler_id++), tables_(std::make_unique<Tables>()) {
    settings_.spp = std::max(1, settings_.spp);
    settings_.light_samples_per_vertex = std::max(0, settings_.light_samples_per_vertex);
    Tables& t = *tables_;
    const uint32_t w = uint32_t(std::max(1, settings_.width)), h = uint32_t(std::max(1, settings_.height));
    switch (settings_.kind) {
        case SamplerKind::independent: break;
        case SamplerKind::stratified:
            for (int d = 1; d * d <= settings_.spp; ++d)
                if (settings_.spp % d == 0) strata_x_ = d;
            strata_y_ = settings_.spp / strata_x_;
            break;
        case SamplerKind::halton: {
            std::vector<int> primes = first_primes(kHaltonDimensions);
            for (int d = 0; d < kHaltonDimensions; ++d)
                t.permutations.emplace_back(primes[size_t(d)], hash_values(settings_.seed, uint64_t(d), 0x48616C74ull));
            while (t.scale2 < std::min(w, kHaltonMaxResolution)) t.scale2 *= 2, ++t.exponent2;
            while (t.scale3 < std::min(h, kHaltonMaxResolution)) t.scale3 *= 3, ++t.exponent3;
            // The Chinese remainder theorem joins "index = a mod 2^j" and
            // "index = b mod 3^k" (pbrt-v3 section 7.4.1).
            t.inverse2 = t.scale3 * inverse_mod(t.scale3, t.scale2);  // 1 mod 2^j, 0 mod 3^k
            t.inverse3 = t.scale2 * inverse_mod(t.scale2, t.scale3);  // 0 mod 2^j, 1 mod 3^k
            break;
        }
        case SamplerKind::sobol: {
            const int m = ceil_log2(std::max(w, h));
            t.log2_resolution = m;
            // Row bits y_k (k < m, the first digits of dimension 1) are
            // linear in the index bits m .. 2m - 1 once the others are
            // known; the (0,2)-sequence property makes that m x m system
            // invertible. Gauss-Jordan over GF(2) on [A | I].
            std::vector<uint64_t> a(static_cast<size_t>(m)), inv(static_cast<size_t>(m));
            for (int k = 0; k < m; ++k) {  // row k of A: which unknown bits flip y_k
                for (int j = 0; j < m; ++j)
                    if ((kSobolDimension1.column[size_t(m + j)] >> (63 - k)) & 1) a[size_t(k)] |= uint64_t(1) << j;
                inv[size_t(k)] = uint64_t(1) << k;
            }
            for (int col = 0; col < m; ++col) {
                int pivot = col;
                while (pivot < m && !((a[size_t(pivot)] >> col) & 1)) ++pivot;
                if (pivot == m) throw std::logic_error("Sobol pixel system is singular");
                std::swap(a[size_t(col)], a[size_t(pivot)]);
                std::swap(inv[size_t(col)], inv[size_t(pivot)]);
                for (int r = 0; r < m; ++r)
                    if (r != col && ((a[size_t(r)] >> col) & 1)) a[size_t(r)] ^= a[size_t(col)], inv[size_t(r)] ^= inv[size_t(col)];
            }
            // Row j of inv now gives unknown bit j from the row bits: store it.
            t.pixel_row_inverse = inv;
            break;
        }
        case SamplerKind::zsobol:
            t.morton_bits = 2 * ceil_log2(std::max(w, h));
            t.sample_bits = ceil_log2(uint64_t(settings_.spp));
            for (uint32_t d = 0; d < kCachedKeys; ++d) {
                t.index_keys.push_back(zsobol_key(d, 0));
                t.scramble_keys_1d.push_back(zsobol_key(d, 1));
                t.scramble_keys_2d.push_back(zsobol_key(d, 2));
            }
            break;
    }
}

Sampler::~Sampler() = default;

uint64_t Sampler::zsobol_key(uint32_t dimension, int purpose) const {
    return hash_values(settings_.seed, dimension, 0x5A536Full + uint64_t(purpose));
}

uint32_t Sampler::slot_dimension(int depth, SampleSlot slot) const {
    const uint32_t lights = uint32_t(settings_.light_samples_per_vertex);
    const uint32_t stride = 4 + 2 * lights;
    uint32_t offset = 0;
    switch (slot) {
        case SampleSlot::light_choice: offset = 0; break;
        case SampleSlot::light: offset = 1; break;
        case SampleSlot::bsdf: offset = 1 + 2 * lights; break;
        case SampleSlot::roulette: offset = 3 + 2 * lights; break;
    }
    return 4 + uint32_t(std::max(depth, 0)) * stride + offset;
}

PixelSample Sampler::start(uint32_t x, uint32_t y, uint64_t index) const {
    PixelSample s;
    s.x = x, s.y = y, s.index = index;
    s.pixel_key = hash_values(settings_.seed, x, y);
    const Tables& t = *tables_;
    if (settings_.kind == SamplerKind::halton) {
        // The index whose first base-2 digits mirror x mod 2^j and whose
        // first base-3 digits mirror y mod 3^k, then every tile-th one.
        uint64_t a = t.exponent2 == 0 ? 0 : reverse_bits_64(x % t.scale2) >> (64 - t.exponent2);
        uint64_t b = 0;
        for (uint64_t v = y % t.scale3, k = 0; k < uint64_t(t.exponent3); ++k, v /= 3) b = b * 3 + v % 3;
        const uint64_t tile = t.scale2 * t.scale3;
        s.global_index = (a * t.inverse2 + b * t.inverse3) % tile + index * tile;
    } else if (settings_.kind == SamplerKind::zsobol) {
        s.global_index = (uint64_t(morton_code(x, y)) << t.sample_bits) | index;
    } else if (settings_.kind == SamplerKind::sobol) {
        // Index bits 0..m-1 mirror x; bits 2m.. are the sample index; bits
        // m..2m-1 are solved so that dimension 1's first m digits spell y.
        const int m = t.log2_resolution;
        uint64_t known = (m == 0 ? 0 : reverse_bits_64(x) >> (64 - m)) | (index << (2 * m));
        uint64_t row = m == 0 ? 0 : sobol_dimension1(known) >> (64 - m);  // digits, first in bit m-1
        uint64_t want = m == 0 ? 0 : y;
        uint64_t diff = row ^ want;  // bit (m-1-k) is digit k
        uint64_t unknown = 0;
        for (int j = 0; j < m; ++j) {
            uint64_t bit = 0;
            for (int k = 0; k < m; ++k)
                if ((t.pixel_row_inverse[size_t(j)] >> k) & 1) bit ^= (diff >> (m - 1 - k)) & 1;
            unknown |= bit << j;
        }
        s.global_index = known | (unknown << m);
    }
    return s;
}

double Sampler::halton_value(const PixelSample& s, uint32_t dimension) const {
    const Tables& t = *tables_;
    if (dimension >= uint32_t(kHaltonDimensions))
        return uniform_from_hash(hash_values(s.pixel_key, s.index, dimension));  // padding
    uint64_t index = s.global_index;
    if (dimension == 0) index >>= t.exponent2;  // the digits past the pixel's: the point in the pixel
    if (dimension == 1) index /= t.scale3;
    return functions_.scrambled_radical_inverse(index, t.permutations[dimension]);
}

uint32_t Sampler::sobol_pixel_fraction(const PixelSample& s, int axis) const {
    const int m = tables_->log2_resolution;
    uint64_t v = axis == 0 ? sobol_dimension0(s.global_index) : sobol_dimension1(s.global_index);
    uint32_t fraction = uint32_t((v << m) >> 32);  // the digits past the pixel's
    return owen_scramble(fraction, uint32_t(hash_values(s.pixel_key, uint64_t(axis), 0x536F62ull)));
}

namespace {

/// The index of one of the 24 permutations for the base-4 digit below
/// `prefix` (the digits above it with a marker bit on top): one mix.
inline uint32_t base4_permutation_choice(uint64_t key, uint64_t prefix) {
    return uint32_t((uint32_t(mix_bits(key ^ (prefix * 0x9E3779B97F4A7C15ull))) * uint64_t(24)) >> 32);
}

/// zsobol: the digits at shifts from `from` down to `to` (steps of 2) of
/// the nested permutation of `code` (`bits` long) under `key`. From the
/// first digit down, each base-4 digit is permuted by one of the 24
/// permutations, chosen by a hash of the digits above it: a random nested
/// permutation of the pixels' Morton order and of the samples within each
/// pixel. One mix per digit: the prefix with a marker bit above it, so that
/// prefixes of different lengths never collide.
uint64_t permute_base4_digits(uint64_t code, int bits, int from, int to, uint64_t key,
                              const Base4Permutations& base4) {
    uint64_t out = 0;
    for (int shift = from; shift >= to; shift -= 2) {
        uint64_t digit = (code >> shift) & 3;
        uint64_t prefix = (code >> (shift + 2)) | (uint64_t(1) << (bits - shift - 2));
        out |= uint64_t(base4.table[base4_permutation_choice(key, prefix)][digit]) << shift;
    }
    return out;
}

/// zsobol: what one pixel's draws share, per dimension. The nested
/// permutation of the pixel's Morton digits depends on the pixel and the
/// dimension only, and so do the permutations of the first two base-4
/// sample digits (the first one's hash sees the pixel's digits, the second
/// one's those and one of 4 first digits); the samples of a pixel are
/// rendered one after the other on one thread, so each thread keeps those
/// of its current pixel, with the permuted sample digits of every sample
/// when there are at most two (up to 32 spp): a draw then mixes no digit
/// (but the lone base-2 digit of 2, 8 or 32 spp) instead of 11 (512x512),
/// and the values are the same. Sobol dimension 1 is linear in the index,
/// so the pixel's part of it is kept too.
struct ZSobolPixelCache {
    uint64_t sampler_id = 0;  ///< 0: empty
    uint32_t x = 0, y = 0;
    std::array<uint64_t, kCachedKeys / 64> valid{};  ///< bit d: entry d is set
    struct Entry {
        uint64_t owner = 0;       ///< the sampler whose digits these are (0: none); valid says whether for this pixel
        uint64_t pixel = 0;       ///< the Morton code of the pixel they are for
        uint64_t digits;          ///< the pixel's permuted digits (shifts morton_bits + sample_bits - 2 .. sample_bits)
        uint32_t reversed_dim1;   ///< sobol_dimension1_reversed(digits)
        std::array<uint8_t, 16> low;  ///< up to two sample digits: the permuted ones, by the sample's
    };
    std::array<Entry, kCachedKeys> entries{};
};
thread_local ZSobolPixelCache zsobol_pixel_cache;

/// Sample digits (base 4, above a lone base-2 digit) that the cache permutes in advance.
constexpr int kCachedSampleLevels = 2;

/// Fills an entry of the cache for the pixel of Morton code `pixel_code`
/// (kept out of line: it runs once per pixel and dimension). A permuted
/// digit depends on the digits above it, so when the entry holds sampler
/// `owner`'s digits of another pixel, only the digits from the highest one
/// in which the two Morton codes differ down are permuted anew: in a 16x16
/// tile, rendered row by row, usually just the last one or two of nine.
[[gnu::noinline]] void fill_zsobol_entry(ZSobolPixelCache::Entry& e, uint64_t owner, uint64_t pixel_code,
                                        int morton_bits, int sample_bits, int lone, uint64_t key,
                                        const Base4Permutations& base4) {
    const int bits = morton_bits + sample_bits;
    const uint64_t code = pixel_code << sample_bits;
    if (e.owner != owner) {
        e.digits = permute_base4_digits(code, bits, bits - 2, sample_bits, key, base4);
        e.reversed_dim1 = sobol_dimension1_reversed(e.digits);
    } else if (const uint64_t diff = e.pixel ^ pixel_code; diff != 0) {
        const int from = ((63 - __builtin_clzll(diff)) & ~1) + sample_bits;  // the highest digit that differs
        const uint64_t redone = ((uint64_t(1) << (from + 2)) - 1) & ~((uint64_t(1) << sample_bits) - 1);
        const uint64_t old = e.digits;
        e.digits = (old & ~redone) | permute_base4_digits(code, bits, from, sample_bits, key, base4);
        e.reversed_dim1 ^= sobol_dimension1_reversed(old ^ e.digits);  // linear
    }
    e.owner = owner;
    e.pixel = pixel_code;
    const int levels = (sample_bits - lone) / 2;
    if (levels > kCachedSampleLevels) return;
    // The sample digits above the lone one, j = 4 a + b (or j = b for one
    // digit): digit a permuted as the pixel's digits choose (one mix), b as
    // those and a choose (one mix per a): permute_base4_digits, its prefixes
    // shared.
    e.low[0] = 0;
    if (levels == 0) return;
    const uint64_t pixel = code >> sample_bits;
    const auto& top = base4.table[base4_permutation_choice(key, pixel | (uint64_t(1) << morton_bits))];
    if (levels == 1) {
        for (int a = 0; a < 4; ++a) e.low[size_t(a)] = top[size_t(a)];
        return;
    }
    for (uint64_t a = 0; a < 4; ++a) {
        const auto& below = base4.table[base4_permutation_choice(key, ((pixel << 2) | a) | (uint64_t(1) << (morton_bits + 2)))];
        for (uint64_t b = 0; b < 4; ++b) e.low[size_t(4 * a + b)] = uint8_t((top[a] << 2) | below[b]);
    }
}

}  // namespace

// Inlined into get_1d and get_2d (its only callers): a draw's hot path.
[[gnu::always_inline]] inline uint64_t Sampler::zsobol_index(const PixelSample& s, uint32_t dimension,
                                                             uint32_t* reversed_dim1) const {
    const Tables& t = *tables_;
    const int bits = t.morton_bits + t.sample_bits;
    const uint64_t code = s.global_index;  // start(): the Morton code, then the sample index
    const int lone = bits & 1;  // an odd count leaves one base-2 digit at the bottom
    uint64_t out = 0, pixel_part = 0;
    uint32_t reversed = 0;
    if (dimension < kCachedKeys) {
        ZSobolPixelCache& cache = zsobol_pixel_cache;
        if (cache.sampler_id != id_ || cache.x != s.x || cache.y != s.y) {
            cache.sampler_id = id_, cache.x = s.x, cache.y = s.y;
            cache.valid.fill(0);
        }
        uint64_t& valid = cache.valid[dimension / 64];
        const uint64_t bit = uint64_t(1) << (dimension % 64);
        ZSobolPixelCache::Entry& e = cache.entries[dimension];
        const uint64_t key = t.index_keys[dimension];
        if (!(valid & bit)) {
            fill_zsobol_entry(e, id_, code >> t.sample_bits, t.morton_bits, t.sample_bits, lone, key, t.base4);
            valid |= bit;
        }
        out = pixel_part = e.digits;
        reversed = e.reversed_dim1;
        const uint64_t sample_mask = (uint64_t(1) << t.sample_bits) - 1;
        if ((t.sample_bits - lone) / 2 <= kCachedSampleLevels)
            out |= uint64_t(e.low[(code & sample_mask) >> lone]) << lone;
        else
            out |= permute_base4_digits(code, bits, t.sample_bits - 2, lone, key, t.base4);
    } else {
        out = permute_base4_digits(code, bits, bits - 2, lone, zsobol_key(dimension, 0), t.base4);
    }
    if (lone) {
        const uint64_t key = dimension < kCachedKeys ? t.index_keys[dimension] : zsobol_key(dimension, 0);
        out |= (code & 1) ^ (mix_bits(key ^ ((code >> 1) * 0xD1B54A32D192ED03ull)) & 1);
    }
    // Linearity: the pixel's part from the cache, the rest (all of it past
    // the cached dimensions) from the tables.
    if (reversed_dim1) *reversed_dim1 = reversed ^ sobol_dimension1_reversed(out ^ pixel_part);
    return out;
}

Vec2 Sampler::padded_sobol_2d(uint64_t index, uint64_t key) const {
    return {binary_fraction(scrambled_sobol_dimension0(index, uint32_t(key))),
            binary_fraction(scrambled_sobol_dimension1(index, uint32_t(key >> 32)))};
}

double Sampler::get_1d(const PixelSample& s, uint32_t dimension) const {
    switch (settings_.kind) {
        case SamplerKind::independent: break;
        case SamplerKind::stratified: {
            const uint64_t n = uint64_t(settings_.spp);
            double jitter = uniform_from_hash(hash_values(s.pixel_key, s.index, dimension, 1));
            if (s.index >= n) return jitter;
            uint32_t stratum = permute_index(uint32_t(s.index), uint32_t(n), hash_values(s.pixel_key, dimension, 2));
            return std::min((stratum + jitter) / double(n), 0x1.fffffffffffffp-1);
        }
        case SamplerKind::halton: return halton_value(s, dimension);
        case SamplerKind::sobol: {
            if (dimension < 2) return binary_fraction(sobol_pixel_fraction(s, int(dimension)));
            uint64_t key = hash_values(s.pixel_key, dimension, 0x50616Dull);
            uint32_t index = owen_scramble(uint32_t(s.index), uint32_t(key >> 32));  // shuffled order
            return binary_fraction(owen_scramble(uint32_t(sobol_dimension0(index) >> 32), uint32_t(key)));
        }
        case SamplerKind::zsobol: {
            uint64_t key = dimension < kCachedKeys ? tables_->scramble_keys_1d[dimension] : zsobol_key(dimension, 1);
            return binary_fraction(scrambled_sobol_dimension0(zsobol_index(s, dimension), uint32_t(key)));
        }
    }
    return uniform_from_hash(hash_values(s.pixel_key, s.index, dimension));
}

Vec2 Sampler::get_2d(const PixelSample& s, uint32_t dimension) const {
    switch (settings_.kind) {
        case SamplerKind::independent: break;
        case SamplerKind::stratified: {
            const uint64_t n = uint64_t(settings_.spp);
            uint64_t h = hash_values(s.pixel_key, s.index, dimension, 3);
            Vec2 jitter(uniform_from_hash(h), double(uint32_t(h)) * 0x1p-32);
            if (s.index >= n) return jitter;
            uint32_t stratum = permute_index(uint32_t(s.index), uint32_t(n), hash_values(s.pixel_key, dimension, 4));
            return functions_.stratified_sample_2d(int(stratum), strata_x_, strata_y_, jitter);
        }
        case SamplerKind::halton: return {halton_value(s, dimension), halton_value(s, dimension + 1)};
        case SamplerKind::sobol: {
            if (dimension < 2) return {get_1d(s, dimension), get_1d(s, dimension + 1)};
            uint64_t key = hash_values(s.pixel_key, dimension, 0x50616Dull);
            uint32_t index = owen_scramble(uint32_t(s.index), uint32_t(key >> 32) ^ 0x9E3779B9u);
            return padded_sobol_2d(index, hash_values(key));
        }
        case SamplerKind::zsobol: {
            uint32_t reversed_dim1 = 0;
            const uint64_t index = zsobol_index(s, dimension, &reversed_dim1);
            const uint64_t key = dimension < kCachedKeys ? tables_->scramble_keys_2d[dimension] : zsobol_key(dimension, 2);
            return {binary_fraction(scrambled_sobol_dimension0(index, uint32_t(key))),
                    binary_fraction(scrambled_sobol_dimension1_from_reversed(reversed_dim1, uint32_t(key >> 32)))};
        }
    }
    uint64_t h = hash_values(s.pixel_key, s.index, dimension);
    return {uniform_from_hash(h), double(uint32_t(h)) * 0x1p-32};
}

}  // namespace pt
