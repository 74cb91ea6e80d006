// Image error metrics against a reference, over every pixel and channel
// (linear radiance; compare PFM renders, not tone-mapped PNGs):
//   rmse   = sqrt(mean (a - b)^2)
//   relmse = mean (a - b)^2 / (b^2 + 0.01)
// relMSE divides each squared error by the reference's squared value, so
// dark and bright regions count alike; the 0.01 keeps black pixels from
// dividing by zero (the convention of Rousselle et al. 2011 and of the
// denoising literature since). Both images must have the same size.
#pragma once

#include "image/image.h"

namespace pt {

double rmse(const Image& image, const Image& reference);
double relmse(const Image& image, const Image& reference);

}  // namespace pt
