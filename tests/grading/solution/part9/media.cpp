// Part 9, tasks 1 to 5, written from the handout's steps: Beer-Lambert,
// free flights by inverting the exponential's cdf, Henyey-Greenstein and
// its sampling by equation 6, and single scattering by light sampling.
#include <algorithm>
#include <cmath>
#include <memory>

#include "core/frame.h"
#include "core/math.h"
#include "scene/interaction.h"
#include "scene/light_set.h"
#include "stages/media.h"
#include "stages/medium_tracking.h"
#include "stages/render_context.h"

namespace pt::student {

Color homogeneous_transmittance(const Color& sigma_t, double distance) {
    // sigma_t = 0 transmits everything, also over an infinite distance
    // (where e^(-0 * inf) would be NaN).
    auto channel = [distance](double s) { return s == 0 ? 1.0 : std::exp(-s * distance); };
    return Color(channel(sigma_t.r), channel(sigma_t.g), channel(sigma_t.b));
}

DistanceSample sample_distance(double sigma_t, double t_max, double u) {
    if (sigma_t == 0) return DistanceSample{t_max, 1.0, false};  // nothing to collide with
    const double t = -std::log1p(-u) / sigma_t;
    if (t < t_max) return DistanceSample{t, sigma_t * std::exp(-sigma_t * t), true};
    return DistanceSample{t_max, std::exp(-sigma_t * t_max), false};
}

double hg_phase(double cos_theta, double g) {
    const double denom = 1 + g * g - 2 * g * cos_theta;
    return (1 - g * g) / (4 * kPi * denom * std::sqrt(denom));
}

Vec3 sample_hg(const Vec3& wo, double g, Vec2 u) {
    double mu;
    if (std::fabs(g) < 1e-3) {
        mu = 1 - 2 * u.x;  // isotropic: equation 6 divides by g
    } else {
        const double s = (1 - g * g) / (1 - g + 2 * g * u.x);
        mu = (1 + g * g - s * s) / (2 * g);
    }
    mu = std::clamp(mu, -1.0, 1.0);  // rounding may leave [-1, 1] by an ulp
    const double sin_theta = std::sqrt(std::max(0.0, 1 - mu * mu));
    const double phi = 2 * kPi * u.y;
    // theta is measured from the direction of travel, -wo.
    return Frame(-wo).to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu));
}

Color in_scattered_radiance(const RenderContext& context, const Vec3& p, const Vec3& wo, int medium, Rng& rng) {
    const double g = context.scene.media[size_t(medium)].g;
    const LightSampleContext ref{p, Vec3(0, 0, 0)};  // no surface: every direction counts
    Color L;
    for (const auto& light : context.lights.all()) {
        const int n = light->sample_count(context.settings.light_samples);
        Color sum;
        for (int i = 0; i < n; ++i) {
            const LightSample s = light->sample_Li(ref, rng.next_2d());
            if (!s.valid()) continue;
            const Ray shadow(p, s.p - p, kSpawnTMin, 1 - kShadowEpsilon);
            const Color T = shadow_transmittance(context, shadow, medium, rng);
            sum += s.L * T * (context.stages.media.hg_phase(-dot(wo, s.wi), g) / s.pdf);
        }
        L += sum / double(n);
    }
    return L;
}

}  // namespace pt::student
