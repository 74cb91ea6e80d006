// BDPT's MIS weight by the ratio recursion (stages/bdpt.h, mis_weight)
// against the brute-force oracle the Part 7 grader uses (grade/mis_oracle.h):
// for random paths of 2 to 8 vertices, random densities in both directions
// and random delta vertices, the weight of each strategy equals
// p_s^b / sum_i p_i^b with every p_i computed as the product of its own
// densities, and the weights of the strategies that can make the path sum
// to 1. Exact up to rounding (relative 1e-9). The oracle itself is checked
// first on a path worked by hand.
#include <doctest/doctest.h>

#include <vector>

#include "core/rng.h"
#include "grade/mis_oracle.h"
#include "stages/bdpt.h"

using namespace pt;
using namespace pt::mis_oracle;

TEST_CASE("bdpt mis oracle: a path of three vertices worked by hand") {
    // pf = (2, 4, 8), pr = (1, 1, 1): p_0 = 1, p_1 = 2, p_2 = 2 * 4 = 8
    // (s = 3 has no camera vertex); balance 2 / 11, power 4 / 69.
    RandomPath p{{2, 4, 8}, {1, 1, 1}, {false, false, false}, 3};
    CHECK(!can_make(p, 3));
    CHECK(brute_force_weight(p, 1, MisHeuristic::balance) == doctest::Approx(2.0 / 11).epsilon(1e-15));
    CHECK(brute_force_weight(p, 1, MisHeuristic::power) == doctest::Approx(4.0 / 69).epsilon(1e-15));
    CHECK(brute_force_weight(p, 2, MisHeuristic::power) == doctest::Approx(64.0 / 69).epsilon(1e-15));
    // x1 a delta vertex: no edge may end at it, so only s = 0 makes the path.
    p.delta[1] = true;
    CHECK(!can_make(p, 1));
    CHECK(!can_make(p, 2));
    CHECK(brute_force_weight(p, 0, MisHeuristic::power) == 1.0);
    // A delta light: no camera subpath hits it (s = 0), a light subpath starts there.
    p.delta = {true, false, false};
    CHECK(!can_make(p, 0));
    CHECK(can_make(p, 1));
}

TEST_CASE("bdpt mis_weight: the ratio recursion equals the brute-force weights, which sum to 1") {
    struct Family {
        double decades, delta_chance;
        bool delta_light;
    };
    const Family families[] = {{3, 0.25, false}, {3, 0.25, true}, {16, 0.1, false}};
    Rng rng(2026);
    for (const Family& f : families) {
        for (int trial = 0; trial < 700; ++trial) {
            const int n = 2 + int(rng.next_index(7));
            RandomPath p = random_path(rng, n, f.decades, f.delta_chance);
            if (f.delta_light) p.delta[0] = true, p.pf[0] = p.pr[0] = 1;
            for (MisHeuristic h : {MisHeuristic::balance, MisHeuristic::power}) {
                double sum = 0;
                bool any = false;
                for (int s = 0; s < n; ++s) {
                    if (!can_make(p, s)) continue;
                    any = true;
                    CAPTURE(f.decades);
                    CAPTURE(trial);
                    CAPTURE(n);
                    CAPTURE(s);
                    std::vector<MisVertex> light, camera;
                    mis_arrays(p, s, light, camera);
                    const double w =
                        reference::mis_weight(light.data(), s, camera.data(), n - s, p.delta[0], h);
                    CHECK(w == doctest::Approx(brute_force_weight(p, s, h)).epsilon(1e-9));
                    sum += w;
                }
                if (any) CHECK(sum == doctest::Approx(1.0).epsilon(1e-9));
            }
        }
    }
}
