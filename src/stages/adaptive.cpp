// Reference implementation of stage `adaptive`. See stages/adaptive.h.
#include "stages/adaptive.h"

#include <cmath>

namespace pt::reference {

bool has_converged(const PixelStatistics& stats, double max_tolerance) {
    if (stats.n < 2) return false;
    const double n = stats.n;
    const double mu = stats.s1 / n;
    // The unbiased sample variance; rounding can make it slightly negative.
    const double variance = (stats.s2 - stats.s1 * stats.s1 / n) / (n - 1);
    // Rare-event guard: all samples equal (up to rounding) says nothing
    // about the variance, so the pixel is not converged.
    if (!(variance > 1e-12 * (mu * mu + 1e-300))) return false;
    const double interval = 1.96 * std::sqrt(variance) / std::sqrt(n);
    return interval <= max_tolerance * mu;
}

}  // namespace pt::reference
