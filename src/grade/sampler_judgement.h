// Part 6's judgement (issue 16), written as pure functions over raw sample
// arrays: what a student's sampler functions returned for inputs that
// trusted code chose goes in, a verdict comes out. Nothing here calls
// student code, so the functions fit a grader in which a sandboxed runner
// evaluates the student's functions on a request and trusted code judges
// the arrays it sends back (docs/sampling.md "Grading"; the manifest
// assignments/part6/grading.json is left for when that framework lands).
//
//   part6.1  stratified_sample_2d: for each grid, the points of all its
//            strata put exactly one point in each cell (the stratification
//            property), and the points are uniform within their cells
//            (chi-square).
//   part6.2  scrambled_radical_inverse: equal to the reference's values
//            within 1e-12 for every request (the contract in
//            stages/sampler.h defines the value exactly), and uniform over random permutations
//            (chi-square) so that an unscrambled or half-scrambled answer
//            is caught even where it happens to agree on a few inputs.
//   part6.3  the image task: the settings of the render, for the framework's
//            noise-aware image rule (docs/grading.md).
//
// Tests: tests/grading/test_sampler_judgement.cpp (the reference passes;
// six wrong implementations each fail).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/low_discrepancy.h"
#include "core/vec3.h"

namespace pt::part6 {

struct Verdict {
    bool passed = false;
    std::string message;  ///< the figures, or the first input that failed
};

/// One call of stratified_sample_2d that the runner makes.
struct StratumRequest {
    int stratum = 0, nx = 1, ny = 1;
    Vec2 jitter;
};
/// The calls of task part6.1: every stratum of grids 1x1 ... 16x16 and
/// some long thin ones, each with a jitter from `seed`; grid by grid.
std::vector<StratumRequest> stratum_requests(uint64_t seed);

/// Whether the answers (answers[i] for requests[i]) put each point in the
/// cell of its stratum (row by row, column = stratum mod nx) and in [0, 1)^2.
Verdict judge_one_per_stratum(const std::vector<StratumRequest>& requests, const std::vector<Vec2>& answers);

/// Pearson's chi-square test of points in [0, 1)^2 against the uniform
/// density on a grid x grid histogram, at `significance`.
Verdict judge_uniform_2d(const std::vector<Vec2>& points, int grid, double significance);
/// The same test of where each answer lies within its own cell,
/// (x nx - column, y ny - row): uniform when the jitter places the point
/// (a point always at its cell's centre is stratified, but not uniform).
Verdict judge_uniform_in_cells(const std::vector<StratumRequest>& requests, const std::vector<Vec2>& answers,
                               int grid, double significance);

/// One call of scrambled_radical_inverse: an index and the permutation (by base and seed; seed 0: identity).
struct RadicalInverseRequest {
    uint64_t index = 0;
    int base = 2;
    uint64_t seed = 0;
    DigitPermutation permutation() const;
};
/// The calls of task part6.2: the first 128 prime bases, the identity and
/// random permutations, indices from 0 to 2^40.
std::vector<RadicalInverseRequest> radical_inverse_requests(uint64_t seed);

/// Whether every answer equals `expected` (the reference's) within 1e-12.
Verdict judge_equal_values(const std::vector<RadicalInverseRequest>& requests, const std::vector<double>& answers,
                           const std::vector<double>& expected);

/// Requests whose answers must be uniform in [0, 1): one index, many
/// random permutations (seed 1 ... count) in base `base`.
std::vector<RadicalInverseRequest> uniformity_requests(uint64_t index, int base, int count);
/// Pearson's chi-square test of values in [0, 1) in `bins` equal bins.
Verdict judge_uniform_1d(const std::vector<double>& values, int bins, double significance);

/// Task part6.3's render, for the framework's image rule.
struct ImageCase {
    std::string label, scene, sampler;
    int max_depth = 1, width = 64, height = 64, spp = 16;
};
const std::vector<ImageCase>& image_cases();

}  // namespace pt::part6
