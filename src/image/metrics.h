// Image metrics: how far an image is from a reference, in numbers.
//
// All metrics compare linear values (never sRGB codes) over every pixel and
// every channel; `b` is always the reference. Definitions:
//
//   RMSE    sqrt(mean (a - b)^2)
//   relMSE  mean (a - b)^2 / (b^2 + 0.01)
//           the relative MSE of Rousselle et al. ("Adaptive rendering with
//           non-local means filtering", SIGGRAPH Asia 2012) as used in
//           denoising and sampling papers; the 0.01 keeps black reference
//           pixels from dividing by zero, so a difference of 0.1 on a black
//           pixel counts 1.0.
//   PSNR    10 log10(1 / MSE) dB, peak 1 = the white of the PNG range
//           (+infinity for identical images)
//   MAD     mean |a - b|
//   share over threshold: the fraction of pixels whose largest channel
//           difference |a - b| exceeds the threshold (linear units).
//
// Every function requires equal sizes and throws InputError otherwise.
#pragma once

#include <string>
#include <vector>

#include "image/image.h"

namespace pt {

/// The constant in the denominator of relMSE (see the file comment).
constexpr double kRelMseEpsilon = 0.01;

/// sqrt(mean over pixels and channels of (a - b)^2).
double rmse(const Image& a, const Image& b);
/// mean over pixels and channels of (a - b)^2 / (b^2 + 0.01); b is the reference.
double relmse(const Image& a, const Image& b);
/// Mean squared error over pixels and channels.
double mse(const Image& a, const Image& b);
/// 10 log10(1 / MSE) in dB; +infinity when the images are equal.
double psnr(const Image& a, const Image& b);
/// mean over pixels and channels of |a - b|.
double mean_abs_diff(const Image& a, const Image& b);
/// Fraction (0 to 1) of pixels with max over channels of |a - b| > threshold.
double share_over(const Image& a, const Image& b, double threshold);

/// All of the above at once, for reports.
struct ImageMetrics {
    double rmse = 0;
    double relmse = 0;
    double psnr = 0;  ///< dB; +infinity for identical images
    double mean_abs_diff = 0;
    double share_over = 0;   ///< fraction of pixels over `threshold`
    double threshold = 0;    ///< the per-pixel threshold of share_over
    size_t pixels_over = 0;  ///< number of pixels over `threshold`
};
ImageMetrics compare_images(const Image& a, const Image& b, double threshold = 0.01);

/// Throws InputError "what: sizes differ: WxH against WxH" unless equal.
void require_same_size(const Image& a, const Image& b, const std::string& what = "images");

/// The per-pixel relMSE (mean over the three channels), row-major: the
/// quantity the heat maps show.
std::vector<double> per_pixel_relmse(const Image& a, const Image& b);

}  // namespace pt
