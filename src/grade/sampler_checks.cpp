// Part 6, stratified_sample_2d and scrambled_radical_inverse (issue 16):
// the judgements of grade/sampler_judgement.h, run on the student's
// answers to inputs the grader draws from the seed.
//
//   stratified_sample_2d: every stratum of grids 1x1 ... 16x16 and long
//   thin ones puts its point in its own cell (the stratification property:
//   exactly one point per cell), and where in its cell the point lands is
//   uniform (chi-square at the manifest's significance), so a point pinned
//   to the cell's centre or corner fails although it is stratified.
//
//   scrambled_radical_inverse: equal to the reference's value within 1e-12
//   (the contract in stages/sampler.h defines it exactly) for the first
//   128 prime bases, identity and random permutations, indices up to 2^40;
//   known closed values (phi_2(6) = 0.375, ...); the first b^m indices
//   under one random permutation put one value in each interval
//   [j / b^m, (j + 1) / b^m) (the property that makes Halton points
//   stratified); and one index over many random permutations is uniform
//   in [0, 1) (chi-square), so a scramble that skips the zero digits past
//   the index's last one is caught even where it agrees on a few inputs.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/hash.h"
#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/sampler_judgement.h"

namespace pt {
namespace {

/// Seeds per grid for the in-cell uniformity test: 4 x 1605 points.
constexpr int kUniformitySeeds = 4;

void record(CaseLog& log, const part6::Verdict& v) {
    if (v.passed)
        log.agreed();
    else
        log.mismatch(v.message);
}

}  // namespace

TaskResult check_stratified_sample_2d(const TaskSpec& spec, const GradeEnvironment& env) {
    const double significance = param(spec, "significance", 1e-5);
    const int grid = param(spec, "grid", 8);
    CaseLog log;
    auto answer = [&](const std::vector<part6::StratumRequest>& requests) {
        std::vector<Vec2> out;
        out.reserve(requests.size());
        for (const part6::StratumRequest& r : requests)
            out.push_back(env.student.sampler.stratified_sample_2d(r.stratum, r.nx, r.ny, r.jitter));
        return out;
    };
    std::vector<part6::StratumRequest> all;
    std::vector<Vec2> answers;
    for (int s = 0; s < kUniformitySeeds; ++s) {
        std::vector<part6::StratumRequest> requests =
            part6::stratum_requests(hash_values(env.seed, uint64_t(s), uint64_t(0x5747)));
        std::vector<Vec2> a = answer(requests);
        all.insert(all.end(), requests.begin(), requests.end());
        answers.insert(answers.end(), a.begin(), a.end());
    }
    log.category("one point per stratum: each point in its own cell of [0, 1)^2");
    // Case by case, so that the report counts the strata that go wrong.
    int wrong = 0;
    std::string first;
    for (size_t i = 0; i < all.size(); ++i) {
        part6::Verdict v = part6::judge_one_per_stratum({all[i]}, {answers[i]});
        if (v.passed) {
            log.agreed();
        } else {
            log.mismatch(v.message);
            ++wrong;
        }
    }
    log.category("jitter at 0 and just below 1: still inside the cell");
    std::vector<part6::StratumRequest> corners;
    const double ones = 0x1.fffffffffffffp-1;
    for (auto [nx, ny] : {std::pair{1, 1}, {3, 5}, {7, 1}, {16, 16}})
        for (int s : {0, nx * ny - 1})
            for (Vec2 j : {Vec2(0, 0), Vec2(ones, ones), Vec2(0, ones), Vec2(ones, 0)})
                corners.push_back({s, nx, ny, j});
    std::vector<Vec2> corner_answers = answer(corners);
    for (size_t i = 0; i < corners.size(); ++i) {
        part6::Verdict v = part6::judge_one_per_stratum({corners[i]}, {corner_answers[i]});
        // (column + jitter) / nx rounds up to the next cell's edge for a
        // jitter within an ulp of 1 (the reference's too): on the edge, in
        // [0, 1), it is allowed.
        const part6::StratumRequest& q = corners[i];
        const Vec2 p = corner_answers[i];
        const double x1 = double(q.stratum % q.nx + 1) / q.nx, y1 = double(q.stratum / q.nx + 1) / q.ny;
        const bool on_edge = p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1 &&
                             std::fabs(p.x - std::min(p.x, x1)) <= 1e-12 && std::fabs(p.y - std::min(p.y, y1)) <= 1e-12 &&
                             p.x >= double(q.stratum % q.nx) / q.nx && p.y >= double(q.stratum / q.nx) / q.ny;
        if (!v.passed && on_edge)
            log.allowed();
        else
            record(log, v);
    }
    log.category("uniform within the cells (chi-square)");
    part6::Verdict uniform =
        wrong > 0 ? part6::Verdict{false, "not tested: some points lie outside their cells"}
                  : part6::judge_uniform_in_cells(all, answers, grid, significance);
    record(log, uniform);
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "the cells of their strata");
    r.details.insert(r.details.begin(), "chi-square test of where " + std::to_string(all.size()) +
                                            " points lie within their cells, " + std::to_string(grid) +
                                            " x " + std::to_string(grid) + " bins: " + uniform.message);
    if (r.status == TaskStatus::pass)
        r.message = std::to_string(all.size() + corners.size()) +
                    " strata, each point in its own cell; uniform within the cells (" + uniform.message + ")";
    return r;
}

TaskResult check_scrambled_radical_inverse(const TaskSpec& spec, const GradeEnvironment& env) {
    const double significance = param(spec, "significance", 1e-5);
    const int permutations = param(spec, "permutations", 4000);
    CaseLog log;
    auto values = [&](const std::vector<part6::RadicalInverseRequest>& requests) {
        std::vector<double> out;
        out.reserve(requests.size());
        for (const part6::RadicalInverseRequest& q : requests)
            out.push_back(env.student.sampler.scrambled_radical_inverse(q.index, q.permutation()));
        return out;
    };
    auto reference = [&](const std::vector<part6::RadicalInverseRequest>& requests) {
        std::vector<double> out;
        for (const part6::RadicalInverseRequest& q : requests)
            out.push_back(env.reference.sampler.scrambled_radical_inverse(q.index, q.permutation()));
        return out;
    };

    log.category("closed values of the plain radical inverse (identity permutation)");
    struct Known {
        uint64_t index;
        int base;
        double value;
    };
    const Known known[] = {{0, 2, 0.0},         {1, 2, 0.5},          {2, 2, 0.25},
                           {3, 2, 0.75},        {6, 2, 0.375},        {1, 3, 1.0 / 3},
                           {5, 3, 7.0 / 9},     {8, 3, 8.0 / 9},      {1, 5, 0.2},
                           {7, 5, 0.44},  // 7 = 12 in base 5: 2/5 + 1/25
                           {uint64_t(1) << 40, 2, std::ldexp(1.0, -41)}};
    for (const Known& k : known) {
        const double want = k.value;
        const double got = env.student.sampler.scrambled_radical_inverse(k.index, DigitPermutation::identity(k.base));
        if (std::fabs(got - want) <= 1e-12) {
            log.agreed();
        } else {
            std::ostringstream m;
            m.precision(17);
            m << "phi_" << k.base << "(" << k.index << ") = " << got << ", expected " << want;
            log.mismatch(m.str());
        }
    }

    log.category("equal to the reference's value: 128 prime bases, identity and random permutations");
    const std::vector<part6::RadicalInverseRequest> requests = part6::radical_inverse_requests(env.seed);
    const std::vector<double> got = values(requests), want = reference(requests);
    for (size_t i = 0; i < requests.size(); ++i)
        record(log, part6::judge_equal_values({requests[i]}, {got[i]}, {want[i]}));

    log.category("the first b^m indices under one random permutation: one value per interval of width b^-m");
    for (auto [base, m] : {std::pair{2, 8}, {3, 5}, {5, 3}, {7, 2}, {11, 2}}) {
        const uint64_t count = uint64_t(std::llround(std::pow(base, m)));
        const uint64_t seed = hash_values(env.seed, uint64_t(base), uint64_t(0x57A7)) | 1;
        std::vector<part6::RadicalInverseRequest> first;
        for (uint64_t i = 0; i < count; ++i)
            first.push_back({i, base, seed});
        const std::vector<double> v = values(first);
        std::vector<int> in(count, 0);
        std::string problem;
        for (size_t i = 0; i < v.size() && problem.empty(); ++i) {
            if (!(v[i] >= 0 && v[i] < 1)) {
                problem = "index " + std::to_string(i) + " gave " + format_num(v[i]) + ", outside [0, 1)";
                break;
            }
            const uint64_t j = std::min(count - 1, uint64_t(v[i] * double(count)));
            if (++in[j] > 1)
                problem = "indices 0 .. " + std::to_string(count - 1) + " in base " + std::to_string(base) +
                          ": two values in the interval [" + std::to_string(j) + " / " + std::to_string(count) +
                          ", " + std::to_string(j + 1) + " / " + std::to_string(count) + ") (index " +
                          std::to_string(i) + ", value " + format_num(v[i]) + ")";
        }
        if (problem.empty())
            log.agreed();
        else
            log.mismatch(problem);
    }

    log.category("one index over random permutations: uniform in [0, 1) (chi-square)");
    std::string chi_messages;
    for (auto [index, base] : {std::pair{uint64_t(0), 2}, {uint64_t(37), 3}, {uint64_t(1000003), 5}}) {
        const std::vector<part6::RadicalInverseRequest> u = part6::uniformity_requests(index, base, permutations);
        part6::Verdict v = part6::judge_uniform_1d(values(u), 20, significance);
        if (!v.passed)
            v.message = "index " + std::to_string(index) + " in base " + std::to_string(base) + " over " +
                        std::to_string(permutations) + " random permutations: " + v.message;
        chi_messages += (chi_messages.empty() ? "" : "; ") + std::string("base ") + std::to_string(base) + ": " +
                        v.message;
        record(log, v);
    }
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "the exact values");
    r.details.insert(r.details.begin(), "chi-square tests of one index over random permutations: " + chi_messages);
    return r;
}

}  // namespace pt
