// Part 5, written from the TODO steps (CS184's rule).
#include <cmath>

#include "stages/adaptive.h"

namespace pt::student {

bool has_converged(const PixelStatistics& stats, double max_tolerance) {
    const double n = stats.n;
    const double mu = stats.s1 / n;
    const double sigma = std::sqrt((stats.s2 - stats.s1 * stats.s1 / n) / (n - 1));
    const double I = 1.96 * sigma / std::sqrt(n);
    return I <= max_tolerance * mu;
}

}  // namespace pt::student
