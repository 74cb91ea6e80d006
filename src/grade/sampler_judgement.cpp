#include "grade/sampler_judgement.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/hash.h"
#include "grade/chi_square.h"

namespace pt::part6 {
namespace {

std::vector<int> first_primes(int count) {
    std::vector<int> primes;
    for (int n = 2; int(primes.size()) < count; ++n) {
        bool prime = true;
        for (int p : primes)
            if (p * p <= n && n % p == 0) prime = false;
        if (prime) primes.push_back(n);
    }
    return primes;
}

Vec2 jitter_of(uint64_t seed, uint64_t i) {
    uint64_t h = hash_values(seed, i);
    return {uniform_from_hash(h), double(uint32_t(h)) * 0x1p-32};
}

}  // namespace

std::vector<StratumRequest> stratum_requests(uint64_t seed) {
    std::vector<StratumRequest> out;
    std::vector<std::pair<int, int>> grids;
    for (int n = 1; n <= 16; ++n) grids.push_back({n, n});
    grids.insert(grids.end(), {{1, 7}, {7, 1}, {2, 8}, {4, 8}, {3, 5}, {16, 2}});
    for (auto [nx, ny] : grids)
        for (int s = 0; s < nx * ny; ++s) out.push_back({s, nx, ny, jitter_of(seed, out.size())});
    return out;
}

Verdict judge_one_per_stratum(const std::vector<StratumRequest>& requests, const std::vector<Vec2>& answers) {
    if (answers.size() != requests.size())
        return {false, "expected " + std::to_string(requests.size()) + " points, got " + std::to_string(answers.size())};
    for (size_t i = 0; i < requests.size(); ++i) {
        const StratumRequest& r = requests[i];
        const Vec2 p = answers[i];
        const int column = r.stratum % r.nx, row = r.stratum / r.nx;
        const bool inside = p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1 && int(std::floor(p.x * r.nx)) == column &&
                            int(std::floor(p.y * r.ny)) == row;
        if (!inside) {
            std::ostringstream m;
            m << "stratum " << r.stratum << " of a " << r.nx << "x" << r.ny << " grid (column " << column << ", row "
              << row << ") with jitter (" << r.jitter.x << ", " << r.jitter.y << ") gave (" << p.x << ", " << p.y
              << "), outside its cell [" << double(column) / r.nx << ", " << double(column + 1) / r.nx << ") x ["
              << double(row) / r.ny << ", " << double(row + 1) / r.ny << ")";
            return {false, m.str()};
        }
    }
    return {true, std::to_string(requests.size()) + " strata, each point in its own cell"};
}

Verdict judge_uniform_2d(const std::vector<Vec2>& points, int grid, double significance) {
    std::vector<double> observed(size_t(grid * grid), 0);
    for (Vec2 p : points) {
        if (!(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1)) return {false, "a point outside [0, 1)^2"};
        ++observed[size_t(int(p.x * grid) + grid * int(p.y * grid))];
    }
    ChiSquareResult r = chi_square_test(observed, std::vector<double>(observed.size(), double(points.size()) / observed.size()),
                                        significance);
    return {r.passed, r.message};
}

Verdict judge_uniform_in_cells(const std::vector<StratumRequest>& requests, const std::vector<Vec2>& answers,
                               int grid, double significance) {
    if (answers.size() != requests.size())
        return {false, "expected " + std::to_string(requests.size()) + " points, got " + std::to_string(answers.size())};
    std::vector<Vec2> offsets;
    for (size_t i = 0; i < requests.size(); ++i) {
        const StratumRequest& r = requests[i];
        Vec2 o(answers[i].x * r.nx - r.stratum % r.nx, answers[i].y * r.ny - r.stratum / r.nx);
        // Rounding may put a point a hair outside its cell's [0, 1).
        offsets.push_back({std::clamp(o.x, 0.0, 0x1.fffffffffffffp-1), std::clamp(o.y, 0.0, 0x1.fffffffffffffp-1)});
    }
    return judge_uniform_2d(offsets, grid, significance);
}

DigitPermutation RadicalInverseRequest::permutation() const {
    return seed == 0 ? DigitPermutation::identity(base) : DigitPermutation(base, seed);
}

std::vector<RadicalInverseRequest> radical_inverse_requests(uint64_t seed) {
    std::vector<RadicalInverseRequest> out;
    const std::vector<int> primes = first_primes(128);
    for (size_t b = 0; b < primes.size(); ++b) {
        for (uint64_t variant = 0; variant < 2; ++variant) {
            const uint64_t permutation_seed = variant == 0 ? 0 : hash_values(seed, b) | 1;
            for (uint64_t index : {uint64_t(0), uint64_t(1), uint64_t(primes[b]), uint64_t(primes[b]) * primes[b] - 1,
                                   hash_values(seed, b, variant) >> 44, hash_values(seed, b, variant, 1) >> 24})
                out.push_back({index, primes[b], permutation_seed});
        }
    }
    return out;
}

Verdict judge_equal_values(const std::vector<RadicalInverseRequest>& requests, const std::vector<double>& answers,
                           const std::vector<double>& expected) {
    if (answers.size() != requests.size() || expected.size() != requests.size())
        return {false, "expected " + std::to_string(requests.size()) + " values, got " + std::to_string(answers.size())};
    for (size_t i = 0; i < requests.size(); ++i) {
        // Within 1e-12: a radical inverse summed in floating point instead of
        // the contract's exact integer is still right; a wrong digit among
        // the first 25 base-2 (or 5 base-719) positions is not.
        if (!(std::fabs(answers[i] - expected[i]) <= 1e-12)) {
            std::ostringstream m;
            m.precision(17);
            m << "index " << requests[i].index << " in base " << requests[i].base << " with "
              << (requests[i].seed == 0 ? "the identity permutation" : "random digit permutations") << ": got "
              << answers[i] << ", expected " << expected[i];
            return {false, m.str()};
        }
    }
    return {true, std::to_string(requests.size()) + " radical inverses equal to the reference's (within 1e-12)"};
}

std::vector<RadicalInverseRequest> uniformity_requests(uint64_t index, int base, int count) {
    std::vector<RadicalInverseRequest> out;
    for (int s = 1; s <= count; ++s) out.push_back({index, base, hash_values(uint64_t(s), uint64_t(base)) | 1});
    return out;
}

Verdict judge_uniform_1d(const std::vector<double>& values, int bins, double significance) {
    std::vector<double> observed(size_t(bins), 0);
    for (double v : values) {
        if (!(v >= 0 && v < 1)) return {false, "a value outside [0, 1)"};
        ++observed[size_t(v * bins)];
    }
    ChiSquareResult r =
        chi_square_test(observed, std::vector<double>(size_t(bins), double(values.size()) / bins), significance);
    return {r.passed, r.message};
}

const std::vector<ImageCase>& image_cases() {
    // Both samplers that call the student's functions, on the scene whose
    // error they change most (the lamp's edge, the soft shadows).
    static const std::vector<ImageCase> cases{
        {"Cornell box, -m 5, -s 16, --sampler stratified", "scenes/cbox.json", "stratified", 5, 64, 64, 16},
        {"Cornell box, -m 5, -s 16, --sampler halton", "scenes/cbox.json", "halton", 5, 64, 64, 16},
    };
    return cases;
}

}  // namespace pt::part6
