// Low-discrepancy building blocks: bit reversal, the first two dimensions
// of the Sobol sequence, Owen scrambling by hashing, the random digit
// permutations of scrambled Halton points, and Morton (Z-order) codes.
//
// The Sobol sequence (Sobol 1967) in dimension j is x_j(a) = C_j a over
// GF(2): the bits of the index a, multiplied by a generator matrix C_j,
// read as binary digits after the point. Dimension 0 has C_0 = I (the van
// der Corput sequence, a's bits mirrored); dimension 1 has Pascal's
// triangle mod 2, C_1[k][j] = binom(j, k) mod 2 (odd exactly when k & ~j
// is 0, by Lucas's theorem). Together they form a (0, 2)-sequence in base
// 2: every aligned block of 2^m points puts exactly one point in each of
// the 2^m elementary boxes of any shape 2^-p by 2^-(m-p). The project
// derives only these two matrices (it ships no table of direction
// numbers); samplers that need more dimensions pad (core/sampler.h).
//
// Owen scrambling (Owen 1995, "Randomly permuted (t,m,s)-nets and
// (t,s)-sequences") flips each digit of a point depending on the digits
// before it, at random; each scrambled point is uniform in [0, 1) and a
// scrambled net is still a net, which keeps the estimate unbiased and the
// stratification. Hashing gives it without tables: in bit-reversed order
// (the first digit in the lowest bit), any map in which bit k changes as
// a function of the bits below k only is a nested scramble (Laine and
// Karras 2011, "Stratified sampling for stochastic transparency"); Burley
// 2020 ("Practical Hash-based Owen Scrambling", JCGT 9(4)) gives the
// constants below and the shuffled index used for padding.
//
// Halton points (Halton 1960): dimension d is the radical inverse in the
// d-th prime base b: the base-b digits of the index mirrored about the
// point. Random digit permutations (Faure and Tezuka; pbrt-v4 section
// 8.6.2) replace digit k by pi_k(digit), pi_k uniform among the b!
// permutations; each point is then uniform on the b^-K grid.
//
// Tests: tests/unit/test_low_discrepancy.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/hash.h"

namespace pt {

using std::size_t;

inline uint32_t reverse_bits_32(uint32_t v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 8) & 0x00FF00FFu) | ((v & 0x00FF00FFu) << 8);
    return (v >> 16) | (v << 16);
}
inline uint64_t reverse_bits_64(uint64_t v) {
    return (uint64_t(reverse_bits_32(uint32_t(v))) << 32) | reverse_bits_32(uint32_t(v >> 32));
}

/// Columns of the generator matrix of Sobol dimension 1 as 64-bit binary
/// fractions (bit 63 is the first digit): column j is the point of index 2^j.
struct SobolDimension1 {
    std::array<uint64_t, 64> column{};
    constexpr SobolDimension1() {
        for (int j = 0; j < 64; ++j)
            for (int k = 0; k <= j; ++k)
                if ((k & ~j) == 0) column[size_t(j)] |= uint64_t(1) << (63 - k);
    }
};
inline constexpr SobolDimension1 kSobolDimension1{};

/// The same matrix byte by byte: entry [k][b] is the XOR of the columns
/// 8k ... 8k + 7 selected by the bits of b (a table look-up per index byte
/// instead of a loop per index bit: the renderer's hot path).
struct SobolDimension1Bytes {
    std::array<std::array<uint64_t, 256>, 8> table{};
    constexpr SobolDimension1Bytes() {
        for (int k = 0; k < 8; ++k)
            for (int b = 0; b < 256; ++b)
                for (int j = 0; j < 8; ++j)
                    if ((b >> j) & 1) table[size_t(k)][size_t(b)] ^= kSobolDimension1.column[size_t(8 * k + j)];
    }
};
inline constexpr SobolDimension1Bytes kSobolDimension1Bytes{};

/// Sobol dimensions 0 and 1 of index a, as 64-bit binary fractions.
inline uint64_t sobol_dimension0(uint64_t a) { return reverse_bits_64(a); }
inline uint64_t sobol_dimension1(uint64_t a) {
    uint64_t v = 0;
    for (size_t k = 0; a != 0; ++k, a >>= 8) v ^= kSobolDimension1Bytes.table[k][a & 0xFF];
    return v;
}

/// The nested scramble in bit-reversed order (the first digit in bit 0),
/// the core of owen_scramble.
inline uint32_t laine_karras(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6C50B47Cu;
    x ^= x * 0xB82F1E52u;
    x ^= x * 0xC7AFE638u;
    x ^= x * 0x8D22F6E6u;
    return x;
}
/// Owen scrambling of a 32-bit binary fraction (bit 31 the first digit) by
/// hashing in bit-reversed order: uniform for a random seed, and nested.
inline uint32_t owen_scramble(uint32_t v, uint32_t seed) {
    return reverse_bits_32(laine_karras(reverse_bits_32(v), seed));
}

/// owen_scramble of the first 32 digits of Sobol dimension 0 and 1 of index
/// a, without the two bit reversals that cancel: dimension 0's
/// digits are a's bits reversed, so its reversed digits are a itself; for
/// dimension 1 the byte tables hold the reversed digits directly.
struct SobolDimension1ReversedBytes {
    std::array<std::array<uint32_t, 256>, 8> table{};
    constexpr SobolDimension1ReversedBytes() {
        for (int k = 0; k < 8; ++k)
            for (int b = 0; b < 256; ++b) {
                uint32_t v = uint32_t(kSobolDimension1Bytes.table[size_t(k)][size_t(b)] >> 32), r = 0;
                for (int j = 0; j < 32; ++j) r |= ((v >> j) & 1u) << (31 - j);
                table[size_t(k)][size_t(b)] = r;
            }
    }
};
inline constexpr SobolDimension1ReversedBytes kSobolDimension1ReversedBytes{};

inline uint32_t scrambled_sobol_dimension0(uint64_t a, uint32_t seed) {
    return reverse_bits_32(laine_karras(uint32_t(a), seed));
}
/// The first 32 digits of Sobol dimension 1 of index a, in reverse order
/// (the first digit in bit 0). Linear over GF(2): the value of a ^ b is the
/// XOR of the values of a and b, so a sampler can keep the part of a fixed
/// prefix of the index and add the rest.
inline uint32_t sobol_dimension1_reversed(uint64_t a) {
    uint32_t reversed = 0;
    for (size_t k = 0; a != 0; ++k, a >>= 8) reversed ^= kSobolDimension1ReversedBytes.table[k][a & 0xFF];
    return reversed;
}
/// owen_scramble of Sobol dimension 1 given sobol_dimension1_reversed of the index.
inline uint32_t scrambled_sobol_dimension1_from_reversed(uint32_t reversed, uint32_t seed) {
    return reverse_bits_32(laine_karras(reversed, seed));
}
inline uint32_t scrambled_sobol_dimension1(uint64_t a, uint32_t seed) {
    return scrambled_sobol_dimension1_from_reversed(sobol_dimension1_reversed(a), seed);
}

/// A 32-bit binary fraction as a double in [0, 1).
inline double binary_fraction(uint32_t v) { return double(v) * 0x1p-32; }

/// The largest K with base^K <= 2^53: the number of base-b digits that the
/// radical inverse keeps, so that the mirrored integer is exact in a double.
inline int radical_inverse_digits(int base) {
    int k = 0;
    for (uint64_t p = uint64_t(base); p <= (uint64_t(1) << 53); p *= uint64_t(base)) ++k;
    return k;
}

/// One random permutation of the digits {0, ..., base - 1} per digit
/// position k = 0 (the first digit after the point), 1, ...,
/// radical_inverse_digits(base) - 1, chosen by a seed; stored as a table
/// (base x digits entries) because the radical inverse reads it per digit.
class DigitPermutation {
public:
    DigitPermutation() = default;
    /// The identity permutation at every position: the plain radical inverse.
    static DigitPermutation identity(int base) { return DigitPermutation(base, 0, false); }
    /// Uniformly random permutations (one per digit position) chosen by `seed`.
    DigitPermutation(int base, uint64_t seed) : DigitPermutation(base, seed, true) {}

    int base() const { return base_; }
    int digits() const { return digits_; }
    /// The image of `digit` (0 <= digit < base) at digit position k (0 <= k < digits()).
    int operator()(int k, int digit) const { return table_[size_t(k) * size_t(base_) + size_t(digit)]; }
    /// base^n for 0 <= n <= digits().
    uint64_t power(int n) const { return powers_[size_t(n)]; }
    /// The digits k, ..., digits() - 1 of a number whose digits there are
    /// all 0, permuted and mirrored: sum_{j >= k} pi_j(0) base^(digits() - 1 - j).
    /// A radical inverse can stop at the index's last non-zero digit and add this.
    uint64_t zero_tail(int k) const { return zero_tails_[size_t(k)]; }

private:
    DigitPermutation(int base, uint64_t seed, bool random) : base_(base), digits_(radical_inverse_digits(base)) {
        table_.resize(size_t(base_) * size_t(digits_));
        for (int k = 0; k < digits_; ++k) {
            uint16_t* p = &table_[size_t(k) * size_t(base_)];
            for (int d = 0; d < base_; ++d) p[d] = uint16_t(d);
            // Fisher-Yates: every permutation equally likely (up to the hash).
            for (int j = base_ - 1; random && j > 0; --j)
                std::swap(p[j], p[hash_values(seed, uint64_t(k), uint64_t(j)) % uint64_t(j + 1)]);
        }
        powers_.assign(size_t(digits_) + 1, 1);
        for (int n = 1; n <= digits_; ++n) powers_[size_t(n)] = powers_[size_t(n) - 1] * uint64_t(base_);
        zero_tails_.assign(size_t(digits_) + 1, 0);
        for (int k = digits_ - 1; k >= 0; --k)
            zero_tails_[size_t(k)] = zero_tails_[size_t(k) + 1] + uint64_t((*this)(k, 0)) * powers_[size_t(digits_ - 1 - k)];
    }
    int base_ = 2;
    int digits_ = 0;
    std::vector<uint16_t> table_;
    std::vector<uint64_t> powers_, zero_tails_;
};

/// Interleaves the low 16 bits of x and y (x in the even bits): the Morton
/// (Z-order) code, which keeps pixels that are close in the image close in
/// the code.
inline uint32_t morton_code(uint32_t x, uint32_t y) {
    auto spread = [](uint32_t v) {
        v &= 0xFFFFu;
        v = (v | (v << 8)) & 0x00FF00FFu;
        v = (v | (v << 4)) & 0x0F0F0F0Fu;
        v = (v | (v << 2)) & 0x33333333u;
        v = (v | (v << 1)) & 0x55555555u;
        return v;
    };
    return spread(x) | (spread(y) << 1);
}

}  // namespace pt
