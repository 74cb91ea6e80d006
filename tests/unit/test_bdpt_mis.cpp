// BDPT's MIS weight by the ratio recursion (stages/bdpt.h, mis_weight)
// against a brute-force evaluation: for random paths of 2 to 8 vertices,
// random densities in both directions and random delta vertices, the
// weight of each strategy equals p_s^b / sum_i p_i^b with every p_i
// computed as the product of its own densities, and the weights of the
// strategies that can make the path sum to 1. Exact up to rounding.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "stages/bdpt.h"

using namespace pt;

namespace {

/// A path x0 (light) .. x(n-1) (camera): pf[i] the density of x_i sampled
/// from the light's side, pr[i] from the camera's; delta[i] a delta vertex
/// (x0: a delta light).
struct RandomPath {
    std::vector<double> pf, pr;
    std::vector<bool> delta;
    int n = 0;
};

RandomPath random_path(Rng& rng, int n) {
    RandomPath p;
    p.n = n;
    for (int i = 0; i < n; ++i) {
        const bool d = i < n - 1 && rng.next_1d() < 0.25;  // the camera is never a delta
        // Densities over several orders of magnitude; a delta vertex has its
        // lobe's probability c both ways (it cancels).
        const double c = 0.3 + rng.next_1d();
        p.pf.push_back(d ? c : std::exp(8 * (rng.next_1d() - 0.5)));
        p.pr.push_back(d ? c : std::exp(8 * (rng.next_1d() - 0.5)));
        p.delta.push_back(d);
    }
    return p;
}

/// Whether strategy (s, n - s) can make the path (stages/bdpt.h).
bool can_make(const RandomPath& p, int s) {
    const int t = p.n - s;
    if (t < 1 || (s == 1 && t == 1)) return false;
    // The edge joins x(s-1) and x(s); s = 0: the camera subpath hits x0,
    // which a delta light forbids; a delta light joins edges (s = 1) like any light.
    if (s == 0) return !p.delta[0];
    return (s == 1 || !p.delta[size_t(s) - 1]) && !p.delta[size_t(s)];
}

double density(const RandomPath& p, int s) {
    double d = 1;
    for (int i = 0; i < p.n; ++i) d *= i < s ? p.pf[size_t(i)] : p.pr[size_t(i)];
    return d;
}

double brute_force_weight(const RandomPath& p, int s, double b) {
    double sum = 0;
    for (int i = 0; i <= p.n; ++i)
        if (can_make(p, i)) sum += std::pow(density(p, i), b);
    return std::pow(density(p, s), b) / sum;
}

double recursive_weight(const RandomPath& p, int s, MisHeuristic h) {
    const int t = p.n - s;
    std::vector<MisVertex> light(static_cast<size_t>(s)), camera(static_cast<size_t>(t));
    for (int i = 0; i < s; ++i) {
        const bool d = i > 0 && p.delta[size_t(i)];
        light[size_t(i)] = {d ? 0.0 : p.pf[size_t(i)], d ? 0.0 : p.pr[size_t(i)], d};
    }
    for (int j = 0; j < t; ++j) {
        const size_t i = size_t(p.n - 1 - j);
        const bool d = i > 0 && p.delta[i];
        camera[size_t(j)] = {d ? 0.0 : p.pr[i], d ? 0.0 : p.pf[i], d};
    }
    return reference::mis_weight(light.data(), s, camera.data(), t, p.delta[0], h);
}

}  // namespace

TEST_CASE("bdpt mis_weight: the ratio recursion equals the brute-force weights, which sum to 1") {
    Rng rng(2026);
    for (int trial = 0; trial < 2000; ++trial) {
        const int n = 2 + int(rng.next_index(7));
        RandomPath p = random_path(rng, n);
        for (MisHeuristic h : {MisHeuristic::balance, MisHeuristic::power}) {
            const double b = h == MisHeuristic::power ? 2 : 1;
            double sum = 0;
            bool any = false;
            for (int s = 0; s < n; ++s) {
                if (!can_make(p, s)) continue;
                any = true;
                CAPTURE(trial);
                CAPTURE(n);
                CAPTURE(s);
                const double w = recursive_weight(p, s, h);
                CHECK(w == doctest::Approx(brute_force_weight(p, s, b)).epsilon(1e-9));
                sum += w;
            }
            if (any) CHECK(sum == doctest::Approx(1.0).epsilon(1e-9));
        }
    }
}
