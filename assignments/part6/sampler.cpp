// Part 6, tasks 1 and 2: stratified points and scrambled radical inverses.
// Read assignments/part6/README.md first; the contract of each function is
// in src/stages/sampler.h.
#include "core/error.h"
#include "stages/sampler.h"

namespace pt::student {

Vec2 stratified_sample_2d(int stratum, int nx, int ny, Vec2 jitter) {
    // TODO(part6.1): stratified_sample_2d, as src/stages/sampler.h states its contract.
    // [guided]
    // the cells of the nx by ny grid are numbered row by
    // row: column = stratum % nx, row = stratum / nx. Return the point of
    // that cell that `jitter` (uniform in [0, 1)^2) picks: x in
    // [column / nx, (column + 1) / nx), y in [row / ny, (row + 1) / ny).
    // [/guided]
    (void)stratum, (void)nx, (void)ny, (void)jitter;
    throw NotImplemented(6, "1", "stratified_sample_2d");
}

double scrambled_radical_inverse(uint64_t index, const DigitPermutation& permutation) {
    // TODO(part6.2): scrambled_radical_inverse, as src/stages/sampler.h states its contract.
    // [guided]
    // with b = permutation.base() and K = permutation.digits(),
    // take the K lowest base-b digits d_0, d_1, ... of index (d_0 = index % b,
    // then divide by b; positions past the index's last digit hold 0),
    // replace each d_k by permutation(k, d_k), and mirror them about the
    // point: accumulate reversed = reversed * b + permutation(k, d_k) for
    // k = 0 .. K - 1 in a uint64_t, then return reversed / b^K as a double
    // (b^K is permutation.power(K)), at most 1 - 2^-53.
    // [/guided]
    (void)index, (void)permutation;
    throw NotImplemented(6, "2", "scrambled_radical_inverse");
}

}  // namespace pt::student
