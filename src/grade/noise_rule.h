// The noise-aware pass rule of the image checks: is a student's render at
// n samples per pixel as close to the converged reference as the
// reference implementation's own renders at n spp are, and is it free of
// bias everywhere?
//
// Inputs: the student's render S at n spp (the grade seed) and S' at
// m = bias_spp (more samples: the bias test), the converged reference R
// (N spp, rendered once and cached) with the per-sample variance s2 of
// every pixel and channel (estimated from the 64 batches R was rendered
// in), and K reference renders Q_1..Q_K at n spp with fixed seeds. A case
// passes when BOTH tests pass:
//
// 1. Error ratio at n spp (catches excess noise and global bias):
//        relMSE(S, R) <= k * mean_k relMSE(Q_k, R) + floor
//    relMSE as in image/metrics.h. k (default 1.5) is calibrated by
//    grading the reference as a student over many seeds (docs/grading.md);
//    the floor (default 1e-6) makes the rule a tight tolerance where the
//    image has no noise at all (e.g. 1 spp through the pixel centres).
//
// 2. Per-tile z-test at m spp with Sidak correction (catches bias confined
//    to a region, which a global average dilutes): the image is cut into
//    tiles of `tile` x `tile` pixels; for each tile T and channel c,
//        z = mean_T(S' - R) / sqrt(sum_T s2_p (1/m + 1/N) / |T|^2 + tau_T^2)
//    (with adaptive sampling, 1/n_p for 1/m: n_p the samples pixel p took)
//    where tau_T = tau_rel * (mean_T |R| + 0.01) absorbs rounding where
//    there is no noise. In a noisy image s2_p is at least 3 c_p^2 / N, c_p
//    the largest difference between R_p and a neighbour: an edge pixel that
//    a sliver of geometry covers with probability below 1/N can show no
//    spread in N reference samples (3/N is the 95% bound on a probability
//    when no event was seen in N trials), yet the student may catch it. Pixels are independent (one
//    random stream per pixel), so under a correct student z is close to standard normal; the test
//    runs at m = 16n by default because at few samples an edge pixel that a sliver of geometry
//    covers is a rare event, and its tile mean is far from normal. With M tests (tiles times 3
//    channels) each is run at the Sidak level
//        alpha_1 = 1 - (1 - alpha)^(1/M)
//    so that the chance of any false alarm is alpha (default 1e-4). The
//    case fails when some p-value erfc(|z| / sqrt 2) < alpha_1.
#pragma once

#include <string>
#include <vector>

#include "image/image.h"

namespace pt {

struct NoiseRule {
    double k = 1.5;         ///< allowed factor over the reference's own relMSE
    double floor = 1e-6;    ///< added to the relMSE limit
    double alpha = 1e-4;    ///< family-wise false-alarm rate of the tile z-test
    int tile = 8;           ///< tile side in pixels
    double tau_rel = 1e-4;  ///< relative rounding allowance on a tile mean
};

struct NoiseVerdict {
    double student_relmse = 0;    ///< relMSE(S, R)
    double reference_relmse = 0;  ///< mean_k relMSE(Q_k, R)
    double relmse_limit = 0;      ///< k * reference_relmse + floor
    bool ratio_ok = false;
    int tests = 0;                           ///< tiles times channels
    double sidak_alpha = 0;                  ///< alpha_1, the per-test level
    double worst_z = 0;                      ///< the largest |z|
    double worst_p = 1;                      ///< its two-sided p-value
    int worst_tile_x = 0, worst_tile_y = 0;  ///< its tile's top-left pixel
    int worst_channel = 0;                   ///< 0 red, 1 green, 2 blue
    int tiles_failed = 0;                    ///< tests with p < sidak_alpha
    bool z_ok = false;
    bool pass = false;
    std::string message;  ///< the verdict in one sentence
};

/// What the rule compares (see the file comment for the symbols).
struct NoiseInputs {
    const Image& student;       ///< S: the student's render at n spp
    const Image& student_bias;  ///< S': the student's render at bias_spp (may be S)
    int bias_spp = 1;           ///< m
    const Image& converged;     ///< R
    int converged_spp = 1;      ///< N
    const Image&
        sample_variance;  ///< s2: per-sample variance of the reference, per pixel and channel
    const std::vector<Image>& runs;  ///< Q_1..Q_K: the reference at n spp
    /// Adaptive sampling: the samples each pixel of S' took (row major), so
    /// that pixel p's variance is s2_p (1/n_p + 1/N); null: every pixel took m.
    const std::vector<uint32_t>* bias_counts = nullptr;
};

/// Applies the rule; throws InputError when sizes differ or `runs` is empty.
NoiseVerdict apply_noise_rule(const NoiseInputs& in, const NoiseRule& rule);

}  // namespace pt
