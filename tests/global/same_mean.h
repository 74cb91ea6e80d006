// The doctest check that two independent renders estimate the same image,
// shared by the Part 4 tests that compare estimators (roulette on and off,
// the three direct-light strategies through rough glass).
#pragma once

#include <doctest/doctest.h>

#include <cmath>

#include "global/global_render.h"

namespace pt::global_test {

/// Checks that two independent renders of one scene estimate the same image:
/// the mean over pixels of their difference is 0 within 4 standard errors,
/// per channel, and the test has the power to see a relative bias of
/// `detectable_bias` (4 standard errors are below it).
inline void check_same_mean(const Image& a, const Image& b, double detectable_bias) {
    Image difference(a.width(), a.height());
    for (size_t i = 0; i < a.data().size(); ++i) difference.data()[i] = a.data()[i] - b.data()[i];
    for (int c = 0; c < 3; ++c) {
        PixelStats d = channel_stats(difference, c);
        CAPTURE(c);
        CAPTURE(d.mean);
        CAPTURE(d.standard_error);
        CHECK(std::fabs(d.z(0.0)) <= 4.0);
        CHECK(4 * d.standard_error < detectable_bias * channel_stats(a, c).mean);
    }
}

}  // namespace pt::global_test
