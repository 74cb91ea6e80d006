// Part 9, tasks 1 to 5: light in participating media.
// Read assignments/part9/README.md first; the contract of each function is
// in src/stages/media.h.
#include <memory>

#include "core/error.h"
#include "stages/media.h"
#include "stages/medium_tracking.h"
#include "stages/render_context.h"

namespace pt::student {

Color homogeneous_transmittance(const Color& sigma_t, double distance) {
    // TODO(part9.1): homogeneous_transmittance, as src/stages/media.h states its contract.
    // [guided]
    // Beer-Lambert, channel by channel: T = e^(-sigma_t distance).
    // A channel with sigma_t = 0 transmits 1 even at an infinite distance
    // (0 * infinity is NaN: do not compute it).
    // [/guided]
    (void)sigma_t, (void)distance;
    throw NotImplemented(9, "1", "homogeneous_transmittance");
}

DistanceSample sample_distance(double sigma_t, double t_max, double u) {
    // TODO(part9.2): sample_distance, as src/stages/media.h states its contract.
    // [guided]
    // Invert the cdf 1 - e^(-sigma_t t): t = -ln(1 - u) / sigma_t
    // (std::log1p(-u) keeps precision for small u; sigma_t = 0 means t is
    // infinite). If t < t_max: a collision, {t, sigma_t e^(-sigma_t t), true}.
    // Else the path passes: {t_max, e^(-sigma_t t_max), false}, the
    // probability of passing.
    // [/guided]
    (void)sigma_t, (void)t_max, (void)u;
    throw NotImplemented(9, "2", "sample_distance");
}

double hg_phase(double cos_theta, double g) {
    // TODO(part9.3): hg_phase, as src/stages/media.h states its contract.
    // [guided]
    // Henyey-Greenstein,
    // (1 / 4 pi) (1 - g^2) / (1 + g^2 - 2 g cos_theta)^(3/2).
    // [/guided]
    (void)cos_theta, (void)g;
    throw NotImplemented(9, "3", "hg_phase");
}

Vec3 sample_hg(const Vec3& wo, double g, Vec2 u) {
    // TODO(part9.4): sample_hg, as src/stages/media.h states its contract.
    // [guided]
    // Draw cos theta by the inverted cdf (README, "Sampling
    // HG"; isotropic, 1 - 2 u.x, when |g| < 1e-3), phi = 2 pi u.y, and
    // build the direction about the axis -wo (the path's direction of
    // travel) with Frame(-wo).to_world(...) (core/frame.h).
    // [/guided]
    (void)wo, (void)g, (void)u;
    throw NotImplemented(9, "4", "sample_hg");
}

Color in_scattered_radiance(const RenderContext& context, const Vec3& p, const Vec3& wo, int medium, Rng& rng) {
    // TODO(part9.5): in_scattered_radiance, as src/stages/media.h states its contract.
    // [guided]
    // Like Part 3's estimate_direct_lighting_importance, with
    // the phase function in place of f cos: for every light of
    // context.lights.all(), n = light->sample_count(context.settings.light_samples)
    // samples s = light->sample_Li({p, Vec3(0, 0, 0)}, rng.next_2d()); each adds
    //     s.L * T * hg_phase(-dot(wo, s.wi), g) / s.pdf
    // with g = context.scene.media[medium].g and T the transmittance of the
    // shadow ray Ray(p, s.p - p, kSpawnTMin, 1 - kShadowEpsilon) from
    // shadow_transmittance(context, ray, medium, rng). Average per light, sum over lights.
    // [/guided]
    (void)context, (void)p, (void)wo, (void)medium, (void)rng;
    throw NotImplemented(9, "5", "in_scattered_radiance");
}

}  // namespace pt::student
