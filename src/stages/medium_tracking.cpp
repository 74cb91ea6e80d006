#include "stages/medium_tracking.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "stages/media.h"
#include "stages/render_context.h"

namespace pt {

namespace {

/// The media stage's functions this render uses (student or reference).
const MediaStage& media_stage(const RenderContext& context) { return context.stages.media; }

bool crosses_boundary(const Material& m) {
    return m.type == MaterialType::glass || m.type == MaterialType::rough_dielectric || m.type == MaterialType::null;
}

/// The part [t0, t1] of ray inside box b, or nothing (the slab test).
std::optional<std::pair<double, double>> clip_to_box(const BBox& b, const Ray& ray, double t0, double t1) {
    for (int a = 0; a < 3; ++a) {
        double o = a == 0 ? ray.o.x : (a == 1 ? ray.o.y : ray.o.z);
        double d = a == 0 ? ray.d.x : (a == 1 ? ray.d.y : ray.d.z);
        double lo = a == 0 ? b.min.x : (a == 1 ? b.min.y : b.min.z);
        double hi = a == 0 ? b.max.x : (a == 1 ? b.max.y : b.max.z);
        if (d == 0) {
            if (o < lo || o > hi) return std::nullopt;
            continue;
        }
        double ta = (lo - o) / d, tb = (hi - o) / d;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 >= t1) return std::nullopt;
    }
    return std::make_pair(t0, t1);
}

double mean(const Color& c) { return (c.r + c.g + c.b) / 3.0; }

/// -ln(1 - u) / rate: the exponential step of tracking.
double exponential_step(double rate, Rng& rng) { return -std::log1p(-rng.next_1d()) / rate; }

}  // namespace

int medium_after(const Scene& scene, const SurfaceInteraction& isect, const Vec3& w, int current) {
    const bool same_side = (dot(w, isect.ng) > 0) == (dot(isect.wo, isect.ng) > 0);
    const Material& m = *isect.material;
    if (same_side || !crosses_boundary(m)) return current;  // reflected: the same medium
    if (m.type == MaterialType::null && m.interior < 0) return current;  // nothing there
    return dot(w, isect.ng) < 0 ? m.interior : scene.outside_medium;
}

int medium_at(const RenderContext& context, const Vec3& p) {
    // An arbitrary direction that no axis-aligned wall is parallel to.
    const Vec3 d = Vec3(0.5773, 0.5774, 0.5775).unit();
    Ray ray(p, d);
    for (int step = 0; step < 256; ++step) {
        std::optional<SurfaceInteraction> hit = context.intersect(ray);
        if (!hit) break;
        const Material& m = *hit->material;
        if (crosses_boundary(m) && !(m.type == MaterialType::null && m.interior < 0))
            return dot(d, hit->ng) > 0 ? m.interior : context.scene.outside_medium;  // leaving: p was inside
        ray = hit->spawn_ray(d);
    }
    return context.scene.outside_medium;
}

Color segment_transmittance(const RenderContext& context, const Medium& m, const Ray& ray, double t0, double t1,
                            Rng& rng, TrackingEstimator estimator) {
    const double speed = ray.d.norm();  // scene units per unit of t
    if (m.homogeneous()) return media_stage(context).homogeneous_transmittance(m.sigma_t(), (t1 - t0) * speed);
    const DensityGrid& grid = *m.density;
    const double majorant = grid.max_density() * m.sigma_t().max_component();
    std::optional<std::pair<double, double>> inside = clip_to_box(grid.bounds(), ray, t0, t1);
    if (!inside || !(majorant > 0)) return Color(1.0);
    Color T(1.0);
    const double rate = majorant * speed;  // tentative collisions per unit of t
    for (double t = inside->first;;) {
        t += exponential_step(rate, rng);
        if (t >= inside->second) break;
        const Color null_fraction = Color(1.0) - m.sigma_t() * (grid.density(ray.at(t)) / majorant);
        if (estimator == TrackingEstimator::ratio) {
            T *= null_fraction;
        } else {
            // Delta tracking: stop with the mean collision probability; the
            // channels' own null fractions, divided by it, weight survivors.
            const double go_on = mean(null_fraction);
            if (rng.next_1d() >= go_on) return Color(0);
            T *= null_fraction / go_on;
        }
        if (T.is_black()) break;
    }
    return T;
}

Color shadow_transmittance(const RenderContext& context, Ray ray, int medium, Rng& rng) {
    return shadow_transmittance(context, ray, medium, rng,
                                context.settings.delta_tracking_shadows ? TrackingEstimator::delta
                                                                        : TrackingEstimator::ratio);
}

Color shadow_transmittance(const RenderContext& context, Ray ray, int medium, Rng& rng,
                           TrackingEstimator estimator) {
    Color T(1.0);
    for (int crossing = 0; crossing < 256; ++crossing) {
        std::optional<SurfaceInteraction> hit = context.intersect(ray);
        const double end = hit ? hit->t : ray.t_max;
        if (medium >= 0) T *= segment_transmittance(context, context.scene.media[size_t(medium)], ray, 0.0, end, rng, estimator);
        if (!hit) return T;
        if (hit->material->type != MaterialType::null || T.is_black()) return Color(0);
        // Through the null surface, towards the same end point.
        const Vec3 target = ray.at(ray.t_max / (1.0 - kShadowEpsilon));
        medium = medium_after(context.scene, *hit, ray.d, medium);
        ray = hit->spawn_ray_to(target);
    }
    return T;
}

FreeFlight sample_free_flight(const RenderContext& context, const Medium& m, const Ray& ray, double t_max,
                              int hero, Rng& rng) {
    FreeFlight f;
    f.t = t_max;
    const Color sigma_t = m.sigma_t();
    const MediaStage& stage = media_stage(context);
    if (m.homogeneous()) {
        if (!m.scatters()) {  // absorption only: no collision can scatter
            f.weight = stage.homogeneous_transmittance(sigma_t, t_max);
            return f;
        }
        // The hero channel's distance; its pdf divided out, the others' kept as ratios.
        DistanceSample s = stage.sample_distance(sigma_t[hero], t_max, rng.next_1d());
        const Color T = stage.homogeneous_transmittance(sigma_t, s.t);
        if (!(s.pdf > 0)) {
            f.weight = Color(0);
            return f;
        }
        f.scattered = s.scattered;
        f.t = s.t;
        const Color pdf = s.scattered ? sigma_t * T : T;  // each channel's density (or probability) of this event
        f.weight = (s.scattered ? T * m.sigma_s : T) / s.pdf;
        f.pdf_ratio = pdf / s.pdf;
        return f;
    }
    const DensityGrid& grid = *m.density;
    const double majorant = grid.max_density() * sigma_t.max_component();
    std::optional<std::pair<double, double>> inside = clip_to_box(grid.bounds(), ray, 0.0, t_max);
    if (!inside || !(majorant > 0)) return f;
    for (double t = inside->first;;) {
        t += exponential_step(majorant, rng);  // ray.d is unit: t is a distance
        if (t >= inside->second) return f;
        const double density = grid.density(ray.at(t));
        const Color sigma_s = m.sigma_s * density, sigma_n = Color(majorant) - sigma_t * density;
        const double ms = mean(sigma_s), mn = mean(sigma_n);
        if (!(ms + mn > 0)) {  // pure absorption at the majorant: nothing survives
            f.weight = Color(0);
            return f;
        }
        const double p_scatter = ms / (ms + mn);
        if (rng.next_1d() < p_scatter) {
            f.scattered = true;
            f.t = t;
            f.weight *= sigma_s / (majorant * p_scatter);
            return f;
        }
        f.weight *= sigma_n / (majorant * (1.0 - p_scatter));
    }
}

}  // namespace pt
