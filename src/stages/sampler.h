// Stage `sampler` (Part 6): stratified and low-discrepancy sample points.
//
// A Monte Carlo estimate of I = integral over [0,1)^s of f is the mean of
// f at N points. With independent uniform points its mean squared error is
// Var[f] / N: O(N^-1), whatever f is. Points that are spread more evenly
// than independent ones do better:
//
//   jittered (stratified) sampling: split [0,1)^2 into N = nx * ny cells
//   and put one uniform point in each. MSE = (1/N^2) sum of the variances
//   of f within the cells: O(N^-2) for a smooth f (each cell's variance is
//   O(cell size^2) = O(1/N)), O(N^-1.5) across an edge (only the O(sqrt N)
//   cells that the edge crosses have any variance) (Mitchell 1996,
//   "Consequences of Stratified Sampling in Graphics").
//
//   quasi-Monte Carlo: points of a low-discrepancy sequence, such as
//   Halton's radical inverses. The Koksma-Hlawka inequality bounds the
//   error by V(f) D*_N with discrepancy D*_N = O((log N)^s / N), so the
//   squared error approaches O(N^-2). Randomised (random digit permutations,
//   Owen scrambling) every point is uniform, so the estimate is unbiased,
//   and for Owen-scrambled nets and smooth f the variance is
//   O(N^-3 (log N)^(s-1)) (Owen 1997, "Scrambled net variance for
//   integrals of smooth functions").
//
// The two functions below are what a student writes; the samplers of
// core/sampler.h (`--sampler stratified`, `--sampler halton`) call them
// for every 2D value and every Halton dimension.
//
// Radical inverse: write the index in base b, a = sum_k d_k b^k, and mirror
// its digits about the point: phi_b(a) = sum_k d_k b^-(k+1). The Halton
// point of index a has phi_2(a), phi_3(a), phi_5(a), ... as coordinates.
// Scrambled: digit k becomes pi_k(d_k) for a random permutation pi_k of
// the digits (DigitPermutation). The digits past the index's last one are
// zeros that pi_k still maps, so all K = permutation.digits() positions
// count:
//     reversed = sum_{k < K} pi_k(d_k) b^(K-1-k),   phi = reversed / b^K
// computed in exact integers (b^K <= 2^53) and divided once, returned as
// min(phi, 1 - 2^-53).
//
// Tests: tests/unit/test_sampler_stage.cpp (one point per stratum, exact
// radical inverses, chi-square uniformity), tests/unit/test_sampler.cpp.
#pragma once

#include <cstdint>

#include "core/low_discrepancy.h"
#include "core/sampler.h"
#include "core/vec3.h"

namespace pt {

using StratifiedSample2DFn = Vec2 (*)(int stratum, int nx, int ny, Vec2 jitter);
using ScrambledRadicalInverseFn = double (*)(uint64_t index, const DigitPermutation& permutation);

struct SamplerStage {
    /// The point of stratum `stratum` of an nx by ny grid over [0, 1)^2,
    /// numbered row by row (stratum = row * nx + column, 0 <= stratum <
    /// nx * ny), placed in its cell by `jitter` in [0, 1)^2: column
    /// (stratum mod nx) spans [column / nx, (column + 1) / nx) in x, row
    /// (stratum div nx) spans [row / ny, (row + 1) / ny) in y.
    StratifiedSample2DFn stratified_sample_2d;
    /// The radical inverse of `index` in base permutation.base() with digit
    /// k replaced by permutation(k, digit) for k < permutation.digits(), as
    /// the file comment gives it: a value in [0, 1).
    ScrambledRadicalInverseFn scrambled_radical_inverse;

    SamplerFunctions functions() const { return {stratified_sample_2d, scrambled_radical_inverse}; }
};

namespace reference {
Vec2 stratified_sample_2d(int stratum, int nx, int ny, Vec2 jitter);
double scrambled_radical_inverse(uint64_t index, const DigitPermutation& permutation);
}  // namespace reference

namespace student {
Vec2 stratified_sample_2d(int stratum, int nx, int ny, Vec2 jitter);
double scrambled_radical_inverse(uint64_t index, const DigitPermutation& permutation);
}  // namespace student

}  // namespace pt
