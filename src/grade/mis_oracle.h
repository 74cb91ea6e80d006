// The brute-force oracle for BDPT's MIS weight (stages/bdpt.h, mis_weight),
// shared by the Part 7 grader (bdpt_checks.cpp) and the reference's unit
// test (tests/unit/test_bdpt_mis.cpp). A path of n vertices x0 (light) ..
// x(n-1) (camera) can be made by the strategies (s, n - s); strategy s
// samples x0..x(s-1) from the light's side and the rest from the camera's,
// so its density is p_s = prod_{i<s} pf[i] * prod_{i>=s} pr[i], and its
// weight is p_s^b / sum_i p_i^b over the strategies that can make the path
// (Veach 1997, chapter 10; b = 1 balance, b = 2 power heuristic). Each
// p_i is its own product here, in long double: no ratio recursion, so a
// recursion's mistake cannot cancel against the oracle's.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/rng.h"
#include "stages/bdpt_vertex.h"
#include "stages/settings.h"

namespace pt::mis_oracle {

/// A path x0 (light) .. x(n-1) (camera): pf[i] the density of x_i sampled
/// from the light's side, pr[i] from the camera's; delta[i] a delta vertex
/// (x0: a delta light, which no camera subpath hits).
struct RandomPath {
    std::vector<double> pf, pr;
    std::vector<bool> delta;
    int n = 0;
};

/// n vertices with densities spread log-uniformly over `decades` decades
/// around 1; each vertex but the camera's is a delta with `delta_chance`.
inline RandomPath random_path(Rng& rng, int n, double decades, double delta_chance) {
    RandomPath p;
    p.n = n;
    for (int i = 0; i < n; ++i) {
        const bool d = i < n - 1 && rng.next_1d() < delta_chance;  // the camera is never a delta
        const double c = 0.3 + rng.next_1d();  // a delta lobe's chance, the same both ways (it cancels)
        p.pf.push_back(d ? c : std::pow(10.0, decades * (rng.next_1d() - 0.5)));
        p.pr.push_back(d ? c : std::pow(10.0, decades * (rng.next_1d() - 0.5)));
        p.delta.push_back(d);
    }
    return p;
}

/// Whether strategy (s, n - s) can make the path: no t = 0, no (1, 1), no
/// edge at a delta vertex, no s = 0 onto a delta light (a delta light joins
/// edges, s = 1, like any light).
inline bool can_make(const RandomPath& p, int s) {
    const int t = p.n - s;
    if (t < 1 || (s == 1 && t == 1)) return false;
    if (s == 0) return !p.delta[0];
    return (s == 1 || !p.delta[size_t(s) - 1]) && !p.delta[size_t(s)];
}

/// p_s: the product of the densities of the path's vertices as strategy s makes them.
inline long double density(const RandomPath& p, int s) {
    long double d = 1;
    for (int i = 0; i < p.n; ++i)
        d *= i < s ? p.pf[size_t(i)] : p.pr[size_t(i)];
    return d;
}

/// p_s^b / sum_i p_i^b over the strategies that can make the path.
inline double brute_force_weight(const RandomPath& p, int s, MisHeuristic h) {
    auto power = [h](long double d) { return h == MisHeuristic::power ? d * d : d; };
    long double sum = 0;
    for (int i = 0; i <= p.n; ++i)
        if (can_make(p, i)) sum += power(density(p, i));
    return double(power(density(p, s)) / sum);
}

/// The arrays mis_weight takes for strategy s (stages/bdpt.h): the light
/// subpath x0..x(s-1), the camera subpath x(n-1)..x(s) in its own order
/// (its forward density is pr); delta vertices carry densities 0.
inline void mis_arrays(const RandomPath& p, int s, std::vector<MisVertex>& light,
                       std::vector<MisVertex>& camera) {
    const int t = p.n - s;
    light.assign(size_t(s), {});
    camera.assign(size_t(t), {});
    for (int i = 0; i < s; ++i) {
        const bool d = i > 0 && p.delta[size_t(i)];
        light[size_t(i)] = {d ? 0.0 : p.pf[size_t(i)], d ? 0.0 : p.pr[size_t(i)], d};
    }
    for (int j = 0; j < t; ++j) {
        const size_t i = size_t(p.n - 1 - j);
        const bool d = i > 0 && p.delta[i];
        camera[size_t(j)] = {d ? 0.0 : p.pr[i], d ? 0.0 : p.pf[i], d};
    }
}

}  // namespace pt::mis_oracle
