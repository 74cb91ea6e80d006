// Reference implementation of stage `sampler`. See stages/sampler.h.
#include "stages/sampler.h"

#include <algorithm>

namespace pt::reference {

namespace {
constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;  // 1 - 2^-53, the largest double below 1
}

Vec2 stratified_sample_2d(int stratum, int nx, int ny, Vec2 jitter) {
    const int column = stratum % nx, row = stratum / nx;
    return {std::min((column + jitter.x) / nx, kOneMinusEpsilon), std::min((row + jitter.y) / ny, kOneMinusEpsilon)};
}

double scrambled_radical_inverse(uint64_t index, const DigitPermutation& permutation) {
    const uint64_t base = uint64_t(permutation.base());
    const int digits = permutation.digits();
    // The index's own digits, first one first; then every remaining
    // position holds a zero digit, whose permuted images zero_tail adds at
    // once: the same integer as running the loop to the last position.
    uint64_t reversed = 0;
    int k = 0;
    for (; index != 0 && k < digits; ++k, index /= base)
        reversed = reversed * base + uint64_t(permutation(k, int(index % base)));
    reversed = reversed * permutation.power(digits - k) + permutation.zero_tail(k);
    return std::min(double(reversed) / double(permutation.power(digits)), kOneMinusEpsilon);
}

}  // namespace pt::reference
