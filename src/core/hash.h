// Hashing for samplers: a 64-bit mixer, hashes of several values, uniform
// numbers from a hash, and a pseudo-random permutation of [0, n) that is
// computed element by element (no table), so that every pixel and every
// sample dimension can have a permutation of its own for free.
//
// Sources: the SplitMix64 finaliser (Steele, Lea and Flood, "Fast
// Splittable Pseudorandom Number Generators", OOPSLA 2014); cycle-walking
// permutations (Black and Rogaway, "Ciphers with Arbitrary Finite Domains",
// 2002), as Kensler uses them for correlated multi-jittered sampling
// ("Correlated Multi-Jittered Sampling", Pixar technical memo 13-01, 2013).
//
// Tests: tests/unit/test_low_discrepancy.cpp (permutations are bijections
// for every n up to 300 and many seeds; hashes of neighbours differ).
#pragma once

#include <cstdint>

namespace pt {

/// SplitMix64's finaliser: a bijection of 64-bit words in which every
/// input bit changes about half of the output bits.
inline uint64_t mix_bits(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/// A hash of several 64-bit values; order matters (hash(a, b) != hash(b, a)).
inline uint64_t hash_values(uint64_t a) { return mix_bits(a + 0x9E3779B97F4A7C15ull); }
template <typename... Rest>
inline uint64_t hash_values(uint64_t a, Rest... rest) {
    return mix_bits(hash_values(rest...) ^ (a * 0xD1B54A32D192ED03ull + 0x9E3779B97F4A7C15ull));
}

/// The top 32 bits of a hash as a uniform number in [0, 1): a multiple of 2^-32.
inline double uniform_from_hash(uint64_t h) { return double(uint32_t(h >> 32)) * 0x1p-32; }

/// Element i of a pseudo-random permutation of [0, n) chosen by `seed`:
/// i -> permute_index(i, n, seed) is a bijection of [0, n) for every seed.
/// Each step below is a bijection of the w-bit words (w = bits of n - 1):
/// xor with a constant, multiplication by an odd constant, and
/// x ^= x >> s. Their composition permutes [0, 2^w); values >= n are
/// mapped again until they land in [0, n) ("cycle walking"), which keeps
/// the map a bijection of [0, n). On average fewer than 2 rounds.
inline uint32_t permute_index(uint32_t i, uint32_t n, uint64_t seed) {
    if (n <= 1) return 0;
    uint32_t mask = n - 1;
    mask |= mask >> 1, mask |= mask >> 2, mask |= mask >> 4, mask |= mask >> 8, mask |= mask >> 16;
    const uint32_t s0 = uint32_t(seed), s1 = uint32_t(seed >> 32) | 1u;
    do {
        i = (i ^ s0) & mask;
        i = (i * 0xE170893Du) & mask;
        i ^= i >> 4;
        i = (i * s1) & mask;
        i ^= i >> 7;
        i = (i * 0x0929EB3Fu) & mask;
        i = (i ^ (s0 >> 16)) & mask;
        i ^= i >> 3;
        i = (i * 0x6935FA69u) & mask;
        i ^= i >> 11;
    } while (i >= n);
    return i;
}

}  // namespace pt
