// Part 6, tasks 1 and 2: stratified points and scrambled radical inverses.
// Read assignments/part6/README.md first; the contract of each function is
// in src/stages/sampler.h.
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "stages/sampler.h"

namespace pt::student {

Vec2 stratified_sample_2d(int stratum, int nx, int ny, Vec2 jitter) {
    // TODO(part6.1) done: cells numbered row by row.
    // (cell + u) / n, kept inside [cell / n, (cell + 1) / n): for u within
    // an ulp of 1 the quotient rounds up to the next cell's edge.
    auto in_cell = [](int cell, int n, double u) {
        const double lo = double(cell) / n, hi = double(cell + 1) / n;
        const double x = (cell + u) / n;
        if (x >= hi) return std::nextafter(hi, lo);
        return x;
    };
    const int column = stratum % nx;
    const int row = stratum / nx;
    return Vec2(in_cell(column, nx, jitter.x), in_cell(row, ny, jitter.y));
}

double scrambled_radical_inverse(uint64_t index, const DigitPermutation& permutation) {
    // TODO(part6.2) done: every one of the K digit positions, the zeros past
    // the index's last digit included, goes through its permutation.
    const uint64_t b = uint64_t(permutation.base());
    const int K = permutation.digits();
    uint64_t reversed = 0;
    for (int k = 0; k < K; ++k) {
        const uint64_t digit = index % b;
        index /= b;
        reversed = reversed * b + uint64_t(permutation(k, int(digit)));
    }
    const double phi = double(reversed) / double(permutation.power(K));
    return std::min(phi, 0x1.fffffffffffffp-1);
}

}  // namespace pt::student
