// Stage `adaptive` (Part 5): when may a pixel stop taking samples?
//
// CS184's rule: after every batch of `samplesPerBatch` samples, with
// x_k the illuminance (luminance) of sample k and the running sums
// s1 = sum x_k, s2 = sum x_k^2 over n samples,
//     mu = s1 / n,   sigma^2 = (s2 - s1^2 / n) / (n - 1),
//     I = 1.96 sigma / sqrt(n)          (half-width of the 95% interval)
// and the pixel has converged when I <= maxTolerance * mu. Otherwise it
// continues, up to -s samples.
//
// The reference adds one guard against rare events (see docs/adaptive.md):
// a pixel whose samples are all equal (sigma = 0, e.g. all black because a
// small bright light has not been hit yet) has not shown its variance, and
// by the rule of three an unseen outcome may still have probability up to
// 3/n at 95% confidence. The textbook rule calls such a pixel converged at
// once (I = 0 <= tol * mu); the reference never does: it continues to -s.
// So the rule can only stop a pixel that has shown variation, and
// constant pixels (the light itself, an empty background) take all -s
// samples, which the rate image shows in red.
//
// Tests: tests/unit/test_adaptive.cpp (the rule on hand-computed sums, the
// rare-event guard, image means equal to uniform sampling, determinism).
#pragma once

namespace pt {

/// Running sums of one pixel's sample illuminances.
struct PixelStatistics {
    double s1 = 0;  ///< sum of x_k
    double s2 = 0;  ///< sum of x_k^2
    int n = 0;      ///< number of samples
};

using HasConvergedFn = bool (*)(const PixelStatistics& stats, double max_tolerance);

struct AdaptiveStage {
    /// Whether a pixel with these statistics may stop sampling: true when
    /// the 95% confidence interval of its mean illuminance is within
    /// max_tolerance times the mean (and, for the reference, the guard holds).
    HasConvergedFn has_converged;
};

namespace reference {
bool has_converged(const PixelStatistics& stats, double max_tolerance);
}
namespace student {
bool has_converged(const PixelStatistics& stats, double max_tolerance);
}

}  // namespace pt
