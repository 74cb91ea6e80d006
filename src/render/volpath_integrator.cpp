// The volume path tracer (`--integrator volpath`; Part 9): the path tracer
// of stage `global` (stages/global.h) with participating media between the
// surfaces, estimating the volume rendering equation (stages/media.h).
//
// Along each ray the path first flies freely through the medium it is in
// (stages/medium_tracking.h): a collision before the next surface is a
// scattering vertex, with Henyey-Greenstein as its "BSDF"; otherwise the
// path reaches the surface. At every vertex, surface or medium:
//
//   1. next-event estimation: a sample of each light, its shadow ray
//      carrying the transmittance of the media it crosses (through null
//      boundaries; glass and other surfaces block it, as in the path tracer);
//   2. the next direction from the phase function (sampled exactly, weight
//      1) or the BSDF, and Russian roulette.
//
// `--direct` chooses how emission is found, as in the path tracer: `light`
// (the default) counts light by next-event estimation and emission found by
// sampled directions only after a delta bounce (or straight from the
// camera); `mis` weighs both by --mis-heuristic (power by default) on the directions'
// densities (light pdf against phase or BSDF pdf; the distance sampling is
// the same in both strategies, so it cancels); `hemisphere` samples
// directions only (phase sampling alone, for `bench accuracy`).
//
// The depth convention is Part 4's: a scattering in a medium is a bounce,
// like a reflection or a refraction; crossing a null boundary is not. -m,
// -o and --rr-depth mean what they mean for the path tracer, so with no
// medium in the scene the two integrators estimate the same image (a test
// checks their means agree).
//
// Which medium a path starts in is the medium around the camera
// (medium_at): inside a cloud or a glass of milk if the camera is.
//
// Tests: tests/global/test_media_render.cpp (single scattering against
// quadrature, the medium furnace, volpath = path without media, no NaN in
// the hard cases, determinism).
#include "render/integrators.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <optional>

#include "core/sampling.h"
#include "stages/media.h"
#include "stages/medium_tracking.h"
#include "stages/mis.h"
#include "stages/render_context.h"

namespace pt {
namespace {

/// A scattering vertex of a path: a point in a medium or on a surface.
struct Vertex {
    Vec3 p;                                     ///< world space
    Vec3 wo;                                    ///< unit, world: back along the path
    int medium = -1;                            ///< the medium on wo's side (-1: vacuum)
    const SurfaceInteraction* isect = nullptr;  ///< the surface, or null for a medium collision
    const BSDF* bsdf = nullptr;                 ///< its BSDF (surfaces)
    double g = 0;                               ///< HG asymmetry (medium collisions)

    /// What the vertex passes on of light arriving from world direction wi:
    /// the phase function, or f |cos theta_i| on a surface.
    Color f(const MediaStage& stage, const Vec3& wi) const {
        if (!isect) return Color(stage.hg_phase(-dot(wo, wi), g));
        const Vec3 wo_local = bsdf->to_local(wo), wi_local = bsdf->to_local(wi);
        const double cos_i = bsdf->is_transmissive() ? std::fabs(wi_local.z) : wi_local.z;
        if (!(cos_i > 0)) return Color(0);
        return bsdf->f(wo_local, wi_local) * cos_i;
    }
    /// The density with which the vertex's own sampling draws wi.
    double pdf(const MediaStage& stage, const Vec3& wi) const {
        if (!isect) return stage.hg_phase(-dot(wo, wi), g);
        return bsdf->pdf(bsdf->to_local(wo), bsdf->to_local(wi));
    }
    LightSampleContext light_context() const {
        return isect ? light_sample_context(*isect, *bsdf) : LightSampleContext{p, Vec3(0, 0, 0)};
    }
    /// A shadow ray to `target`, stopping just short of it.
    Ray ray_to(const Vec3& target) const {
        return isect ? isect->spawn_ray_to(target) : Ray(p, target - p, kSpawnTMin, 1.0 - kShadowEpsilon);
    }
    /// The medium a ray leaving in world direction w travels in.
    int medium_towards(const Scene& scene, const Vec3& w) const {
        return isect ? medium_after(scene, *isect, w, medium) : medium;
    }
};

/// Next-event estimation at v: -l samples per light (one per delta light),
/// each times the transmittance of its shadow ray, weighted against v's own
/// sampling (mis_weight: --mis-heuristic) when `mis`.
Color sample_lights(const RenderContext& context, const Vertex& v, bool mis, Rng& rng) {
    const MediaStage& stage = context.stages.media;
    const LightSampleContext ref = v.light_context();
    Color L;
    for (const std::unique_ptr<Light>& light : context.lights.all()) {
        const int n = light->sample_count(context.settings.light_samples);
        Color sum;
        for (int i = 0; i < n; ++i) {
            LightSample s = light->sample_Li(ref, rng.next_2d());
            if (!s.valid() || s.L.is_black()) continue;
            const Color f = v.f(stage, s.wi);
            if (f.is_black()) continue;
            // The shadow ray last: it is the expensive part.
            const Color T = shadow_transmittance(context, v.ray_to(s.p), v.medium_towards(context.scene, s.wi), rng);
            if (T.is_black()) continue;
            // The heuristic --mis-heuristic names, as the emission found by sampled
            // directions is weighted (bsdf_sample_mis_weight): the two weights sum to 1.
            const double w = s.is_delta || !mis ? 1.0 : mis_weight(context, n, s.pdf, 1, v.pdf(stage, s.wi));
            sum += f * s.L * T * (w / s.pdf);
        }
        L += sum / double(n);
    }
    return L;
}

/// Whether any material holds a medium (else every ray is in the scene's medium).
bool has_interiors(const Scene& scene) {
    for (const Material& m : scene.materials)
        if (m.interior >= 0) return true;
    return false;
}

class VolPathIntegrator final : public Integrator {
  public:
    Color Li(const RenderContext& context, const Ray& camera_ray, Rng& rng) const override {
        const Scene& scene = context.scene;
        const RenderSettings& settings = context.settings;
        const MediaStage& stage = context.stages.media;
        const bool mis = settings.direct == DirectStrategy::mis;
        const bool nee = settings.direct != DirectStrategy::hemisphere && context.code_paths.light_sampling;
        const bool sampled_emission = settings.direct != DirectStrategy::light;  // found by sampled directions
        // Part 9 (--student media): the student's light sampling at medium
        // collisions, plain (no MIS), so emission found from them is not counted.
        const bool student = context.stages.is_student(Stage::media);
        if (student) probe_.run_once(context);

        // The radiance found; the path's throughput over its hero channel's
        // pdf (beta) and the other channels' pdfs relative to the hero's (r):
        // it contributes beta / mean(r) (stages/medium_tracking.h).
        Color L, beta(1.0), r(1.0);
        const int hero = std::min(2, int(rng.next_1d() * 3.0));
        auto spectral_mis = [&]() { return 3.0 / (r.r + r.g + r.b); };
        double eta_scale = 1.0;  // product of eta^2 of refractions: kept out of roulette
        int depth = 0;           // scattering vertices so far: light found now has `depth` bounces
        bool after_delta = true;  // the camera or a delta bounce: emission found counts in full
        bool after_plain_nee = false;  // the last vertex counted its light by NEE alone (student)
        bool last = false;        // this ray only looks for emission (the -m-th bounce)
        LightSampleContext previous;  // the last vertex, for the MIS weight of emission found
        double previous_pdf = 0;      // the density its sampling drew the ray's direction with
        Ray ray = camera_ray;
        int medium = has_interiors(scene) ? medium_at(context, ray.o) : scene.outside_medium;

        // Emission (or the sky) found along the current ray, weighted by strategy.
        auto add_emission = [&](const Color& Le, const std::optional<SurfaceInteraction>& hit) {
            if (Le.is_black() || !(settings.accumulate_bounces || depth == settings.max_depth)) return;
            double w = 1.0;
            if (!after_delta) {
                if (!sampled_emission || after_plain_nee) return;  // next-event estimation counted it
                if (mis) w = bsdf_sample_mis_weight(context, previous, ray.d, hit, previous_pdf, 1);
            }
            L += beta * Le * (w * spectral_mis());
        };
        // Russian roulette on the throughput the path would have; false ends the path.
        auto survives = [&](Color& weight, int bounces) {
            if (!settings.russian_roulette || bounces <= settings.rr_depth) return true;
            const double q =
                std::min(kMaxSurvivalProbability, (beta * weight).max_component() * spectral_mis() * eta_scale);
            if (rng.next_1d() >= q) return false;
            weight /= q;
            return true;
        };

        for (int step = 0; step < 1 << 20; ++step) {
            std::optional<SurfaceInteraction> hit = context.intersect(ray);
            // 1. The medium up to the hit: a collision there is a vertex.
            if (medium >= 0) {
                const Medium& m = scene.media[size_t(medium)];
                FreeFlight flight = sample_free_flight(context, m, ray, hit ? hit->t : ray.t_max, hero, rng);
                beta *= flight.weight;
                r *= flight.pdf_ratio;
                if (beta.is_black()) break;
                if (flight.scattered) {
                    if (last) break;  // this ray looked only for emission
                    const Vertex v{ray.at(flight.t), -ray.d, medium, nullptr, nullptr, m.g};
                    const int bounces = depth + 1;
                    const bool counted = bounces <= settings.max_depth && (settings.accumulate_bounces || bounces == settings.max_depth);
                    if (nee && counted)
                        L += beta * spectral_mis() *
                             (student ? stage.in_scattered_radiance(context, v.p, v.wo, medium, rng)
                                      : sample_lights(context, v, mis, rng));
                    const bool continues = bounces < settings.max_depth;
                    if (!continues && !(counted && sampled_emission && !student)) break;
                    const Vec3 wi = stage.sample_hg(v.wo, m.g, rng.next_2d());
                    Color weight(1.0);  // HG is sampled exactly: p / pdf = 1
                    if (!survives(weight, bounces)) break;
                    beta *= weight;
                    previous = v.light_context();
                    previous_pdf = stage.hg_phase(-dot(v.wo, wi), m.g);
                    after_delta = false;
                    after_plain_nee = student;
                    last = !continues;
                    depth = bounces;
                    ray = Ray(v.p, wi, kSpawnTMin);
                    continue;
                }
            }
            // 2. The surface (or the sky): its emission, then scattering.
            if (!hit) {
                add_emission(context.lights.environment_radiance(ray.d), hit);
                break;
            }
            add_emission(context.stages.direct.zero_bounce_radiance(context, ray, *hit), hit);
            if (hit->material->type == MaterialType::null) {  // no surface: on through it
                medium = medium_after(scene, *hit, ray.d, medium);
                ray = hit->spawn_ray(ray.d);
                continue;
            }
            if (last) break;
            const BSDF bsdf = context.bsdf_at(*hit);
            const Vertex v{hit->p, hit->wo, medium, &*hit, &bsdf, 0.0};
            const int bounces = depth + 1;
            const bool counted = bounces <= settings.max_depth && (settings.accumulate_bounces || bounces == settings.max_depth);
            if (nee && counted && !bsdf.is_delta()) L += beta * spectral_mis() * sample_lights(context, v, mis, rng);
            const bool continues = bounces < settings.max_depth;
            if (!continues && !(counted && (sampled_emission || bsdf.is_delta()))) break;
            BSDFSample bs = bsdf.sample_f(bsdf.to_local(hit->wo), rng.next_2d());
            if (!bs.valid() || bs.f.is_black()) break;
            Color weight = bs.f * (std::fabs(bs.wi.z) / bs.pdf);
            if (context.code_paths.refraction) eta_scale *= bs.eta * bs.eta;
            if (!survives(weight, bounces)) break;
            beta *= weight;
            const Vec3 wi = bsdf.to_world(bs.wi);
            previous = light_sample_context(*hit, bsdf);
            previous_pdf = bs.pdf;
            after_delta = bs.is_delta;
            after_plain_nee = false;
            last = !continues;
            depth = bounces;
            medium = medium_after(scene, *hit, wi, medium);
            ray = hit->spawn_ray(wi);
        }
        return L;
    }
    IntegratorKind kind() const override { return IntegratorKind::volpath; }

  private:
    /// Calls each student function of the media stage once, in task order,
    /// before the first pixel: the first one missing is the one reported.
    class MediaProbe {
      public:
        void run_once(const RenderContext& context) const {
            if (done_.load(std::memory_order_acquire)) return;
            std::lock_guard<std::mutex> lock(mutex_);
            if (done_.load(std::memory_order_relaxed)) return;
            const MediaStage& stage = context.stages.media;
            Rng rng(1);
            (void)stage.homogeneous_transmittance(Color(1.0), 1.0);
            (void)stage.sample_distance(1.0, 1.0, 0.5);
            (void)stage.hg_phase(0.5, 0.3);
            (void)stage.sample_hg(Vec3(0, 0, 1), 0.3, Vec2(0.5, 0.5));
            if (!context.scene.media.empty())
                (void)stage.in_scattered_radiance(context, context.scene.camera.position, Vec3(0, 0, 1), 0, rng);
            done_.store(true, std::memory_order_release);
        }

      private:
        mutable std::atomic<bool> done_{false};
        mutable std::mutex mutex_;
    };
    MediaProbe probe_;
};

}  // namespace

std::unique_ptr<Integrator> make_volpath_integrator() {
    return std::make_unique<VolPathIntegrator>();
}

}  // namespace pt
