// Directions binned by the pixel of a lat-long map they fall in, for the
// chi-square tests of environment-map sampling (test_environment_sampling,
// test_light_emission): radiance and the sampling density are constant
// over a pixel, so the Gauss rule integrates the expected counts exactly.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "scene/environment_map.h"
#include "statistical/chi2.h"

namespace pt::stats {

/// Directions binned by the pixel of a lat-long map they fall in.
struct LatLongGrid {
    int nu = 64, nv = 32;

    int cells() const { return nu * nv; }
    int cell(const Vec3& w) const {
        if (!w.is_finite() || std::fabs(w.norm() - 1.0) > 1e-9) return -1;
        Vec2 uv = EnvironmentMap::direction_to_uv(w);
        int x = std::clamp(int(uv.x * nu), 0, nu - 1), y = std::clamp(int(uv.y * nv), 0, nv - 1);
        return y * nu + x;
    }
    template <class Pdf>
    double integrate(int c, Pdf pdf) const {
        int x = c % nu, y = c / nu;
        // Gauss nodes stay inside the cell, clear of its edges where the pdf steps.
        return DirectionGrid::gauss_2d(double(x) / nu, double(x + 1) / nu, double(y) / nv,
                                       double(y + 1) / nv, [&](double u, double v) {
                                           return pdf(EnvironmentMap::uv_to_direction({u, v})) * 2 *
                                                  kPi * kPi * std::sin(kPi * v);
                                       });
    }
};


}  // namespace pt::stats
