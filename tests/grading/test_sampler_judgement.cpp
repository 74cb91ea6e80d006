// Part 6's judgement (src/grade/sampler_judgement.h): the reference's
// answers pass every verdict; each deliberately wrong implementation below
// fails at least one. Chi-square verdicts at significance 1e-4 (fixed
// seeds: deterministic).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "grade/sampler_judgement.h"
#include "stages/sampler.h"

namespace pt {
namespace {

using StratifiedFn = std::function<Vec2(int, int, int, Vec2)>;
using RadicalFn = std::function<double(uint64_t, const DigitPermutation&)>;

struct Outcome {
    bool strata = false, uniform_2d = false, equal = false, uniform_1d = false;
};

Outcome judge(const StratifiedFn& stratified, const RadicalFn& radical) {
    Outcome o;
    // part6.1, as a runner would: evaluate the requests, send back the arrays.
    std::vector<part6::StratumRequest> requests = part6::stratum_requests(7);
    std::vector<Vec2> points;
    for (const auto& r : requests) points.push_back(stratified(r.stratum, r.nx, r.ny, r.jitter));
    o.strata = part6::judge_one_per_stratum(requests, points).passed;
    o.uniform_2d = part6::judge_uniform_in_cells(requests, points, 4, 1e-4).passed;
    // part6.2.
    std::vector<part6::RadicalInverseRequest> ri = part6::radical_inverse_requests(7);
    std::vector<double> answers, expected;
    for (const auto& r : ri) {
        DigitPermutation p = r.permutation();
        answers.push_back(radical(r.index, p));
        expected.push_back(reference::scrambled_radical_inverse(r.index, p));
    }
    o.equal = part6::judge_equal_values(ri, answers, expected).passed;
    o.uniform_1d = true;
    for (int base : {2, 3, 7}) {
        for (uint64_t index : {0ull, 5ull}) {
            std::vector<double> values;
            for (const auto& r : part6::uniformity_requests(index, base, 2000)) values.push_back(radical(r.index, r.permutation()));
            o.uniform_1d = o.uniform_1d && part6::judge_uniform_1d(values, 20, 1e-4).passed;
        }
    }
    return o;
}

const StratifiedFn kStratified = reference::stratified_sample_2d;
const RadicalFn kRadical = reference::scrambled_radical_inverse;

}  // namespace

TEST_CASE("part 6 judgement: the reference passes every verdict") {
    Outcome o = judge(kStratified, kRadical);
    CHECK(o.strata);
    CHECK(o.uniform_2d);
    CHECK(o.equal);
    CHECK(o.uniform_1d);
}

TEST_CASE("part 6 judgement: a radical inverse summed in floating point passes") {
    RadicalFn floating = [](uint64_t index, const DigitPermutation& p) {
        double value = 0, scale = 1.0 / p.base();
        for (int k = 0; k < p.digits(); ++k, index /= uint64_t(p.base()), scale /= p.base())
            value += p(k, int(index % uint64_t(p.base()))) * scale;
        return std::min(value, 0x1.fffffffffffffp-1);
    };
    CHECK(judge(kStratified, floating).equal);
}

TEST_CASE("part 6 judgement: wrong stratified points fail") {
    // Rows and columns swapped.
    CHECK_FALSE(judge([](int s, int nx, int ny, Vec2 j) { return Vec2((s / nx + j.x) / nx, (s % nx + j.y) / ny); }, kRadical).strata);
    // No stratification: the jitter alone.
    CHECK_FALSE(judge([](int, int, int, Vec2 j) { return j; }, kRadical).strata);
    // No jitter: every point at its cell's centre is stratified, but not uniform.
    Outcome centre = judge([](int s, int nx, int ny, Vec2) { return Vec2((s % nx + 0.5) / nx, (s / nx + 0.5) / ny); }, kRadical);
    CHECK(centre.strata);
    CHECK_FALSE(centre.uniform_2d);
}

TEST_CASE("part 6 judgement: wrong radical inverses fail") {
    // Stops at the index's last digit: the permuted zeros are missing.
    RadicalFn short_digits = [](uint64_t index, const DigitPermutation& p) {
        double value = 0, scale = 1.0 / p.base();
        for (int k = 0; index != 0; ++k, index /= uint64_t(p.base()), scale /= p.base())
            value += p(k, int(index % uint64_t(p.base()))) * scale;
        return value;
    };
    Outcome o = judge(kStratified, short_digits);
    CHECK_FALSE(o.equal);
    CHECK_FALSE(o.uniform_1d);  // index 0 is always 0
    // Ignores the permutation: the plain radical inverse.
    RadicalFn plain = [](uint64_t index, const DigitPermutation& p) {
        return reference::scrambled_radical_inverse(index, DigitPermutation::identity(p.base()));
    };
    Outcome q = judge(kStratified, plain);
    CHECK_FALSE(q.equal);
    CHECK_FALSE(q.uniform_1d);
    // Permutes digit k with position K - 1 - k's permutation.
    RadicalFn wrong_position = [](uint64_t index, const DigitPermutation& p) {
        uint64_t reversed = 0;
        for (int k = 0; k < p.digits(); ++k, index /= uint64_t(p.base()))
            reversed = reversed * uint64_t(p.base()) + uint64_t(p(p.digits() - 1 - k, int(index % uint64_t(p.base()))));
        return std::min(double(reversed) / double(p.power(p.digits())), 0x1.fffffffffffffp-1);
    };
    CHECK_FALSE(judge(kStratified, wrong_position).equal);
}

TEST_CASE("part 6 image cases name the two samplers that call student code") {
    const auto& cases = part6::image_cases();
    REQUIRE(cases.size() == 2);
    CHECK(cases[0].sampler == "stratified");
    CHECK(cases[1].sampler == "halton");
}

}  // namespace pt
