// Reference implementation of stage `media`. See stages/media.h.
#include "stages/media.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/frame.h"
#include "core/math.h"

namespace pt::reference {

namespace {
/// e^(-s d) with 0 * infinity taken as 0 (no medium in that channel).
double beer_lambert(double sigma_t, double distance) {
    return sigma_t > 0 ? std::exp(-sigma_t * distance) : 1.0;
}
}  // namespace

Color homogeneous_transmittance(const Color& sigma_t, double distance) {
    return {beer_lambert(sigma_t.r, distance), beer_lambert(sigma_t.g, distance), beer_lambert(sigma_t.b, distance)};
}

DistanceSample sample_distance(double sigma_t, double t_max, double u) {
    DistanceSample s;
    // -log1p(-u) keeps precision for small u; u < 1 keeps t finite.
    const double t = sigma_t > 0 ? -std::log1p(-u) / sigma_t : std::numeric_limits<double>::infinity();
    if (t < t_max) {
        s.t = t;
        s.pdf = sigma_t * std::exp(-sigma_t * t);
        s.scattered = true;
    } else {
        s.t = t_max;
        s.pdf = beer_lambert(sigma_t, t_max);
    }
    return s;
}

double hg_phase(double cos_theta, double g) {
    // 1 + g^2 - 2 g cos theta as a sum of terms >= 0, so that rounding
    // cannot make it negative for |g| near 1.
    const double denominator = g >= 0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - cos_theta)
                                      : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + cos_theta);
    return kInvFourPi * (1.0 - g * g) / (denominator * std::sqrt(denominator));
}

Vec3 sample_hg(const Vec3& wo, double g, Vec2 u) {
    // cos theta between the path's direction of travel, -wo, and wi.
    double cos_theta;
    if (std::fabs(g) < 1e-3) {
        cos_theta = 1.0 - 2.0 * u.x;  // isotropic to within 1e-3
    } else {
        const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
        cos_theta = (1.0 + g * g - s * s) / (2.0 * g);
    }
    cos_theta = std::clamp(cos_theta, -1.0, 1.0);
    const double sin_theta = safe_sqrt(1.0 - cos_theta * cos_theta);
    const double phi = kTwoPi * u.y;
    return Frame(-wo).to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
}

}  // namespace pt::reference
