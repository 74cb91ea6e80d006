// The random walk of BDPT's subpaths (stages/bdpt.h, random_walk), and the
// two subpaths' starts (camera_subpath, light_subpath).
#include <algorithm>
#include <cmath>

#include "scene/camera_importance.h"
#include "stages/bdpt.h"
#include "stages/global.h"
#include "stages/render_context.h"

namespace pt {
namespace reference {

int random_walk(const RenderContext& context, const Ray& ray, const Color& beta, double pdf_dir,
                int max_vertices, Transport mode, Rng& rng, std::vector<PathVertex>& path) {
    if (max_vertices <= 0) return 0;
    const RenderSettings& settings = context.settings;
    Ray r = ray;
    Color weight = beta;     // beta of the next vertex
    Color throughput(1.0);   // product of f |cos| / pdf since the start: roulette's measure
    double eta_scale = 1.0;  // radiance's eta^2 at refractions, kept out of roulette
    double pdf_omega = pdf_dir;
    int added = 0;
    for (;;) {
        std::optional<SurfaceInteraction> hit = context.intersect(r);
        if (!hit) {
            // A camera ray that leaves the scene reaches the environment: a
            // vertex at infinity for the s = 0 strategy (density per solid angle).
            if (mode == Transport::radiance && context.lights.environment()) {
                PathVertex v;
                v.kind = VertexKind::escaped;
                v.w = r.d;
                v.beta = weight;
                v.pdf_fwd = pdf_omega;
                path.push_back(v);
                ++added;
            }
            break;
        }
        path.push_back(make_surface_vertex(context, *hit, weight));
        const size_t i = path.size() - 1;
        path[i].pdf_fwd = convert_density(pdf_omega, path[i - 1], path[i]);
        if (++added >= max_vertices) break;

        // Next direction, from the BSDF: wo leads back along the walk.
        PathVertex& v = path[i];
        const BSDF& bsdf = *v.bsdf;
        const Vec3 wo = bsdf.to_local(v.isect->wo);
        BSDFSample bs = bsdf.sample_f(wo, rng.next_2d());
        if (!bs.valid() || bs.f.is_black()) break;
        const Vec3 wi = bsdf.to_world(bs.wi);
        Color f = bs.f;
        double pdf_rev_omega = bsdf.pdf(bs.wi, wo);
        if (mode == Transport::importance) {
            // The adjoint: no (n_o / n_i)^2 at a refraction, and Veach's
            // shading-normal factor (stages/bdpt_vertex.h).
            f *= bs.eta * bs.eta;
            const double denom = std::fabs(dot(v.isect->wo, v.isect->ng)) * std::fabs(dot(wi, v.ns));
            if (!(denom > 0)) break;
            f *= std::fabs(dot(v.isect->wo, v.ns)) * std::fabs(dot(wi, v.isect->ng)) / denom;
        } else {
            eta_scale *= bs.eta * bs.eta;
        }
        Color step = f * (std::fabs(bs.wi.z) / bs.pdf);
        pdf_omega = bs.pdf;
        if (bs.is_delta) {
            // A delta lobe: no other strategy can make this bounce; MIS
            // skips the vertex (its densities are 0 by convention).
            v.delta = true;
            pdf_omega = pdf_rev_omega = 0;
        }

        // Russian roulette after rr_depth vertices, on the walk's own
        // throughput (stages/global.h): survive with q, weigh by 1 / q.
        if (settings.russian_roulette && added > settings.rr_depth) {
            const double q = std::min(kMaxSurvivalProbability, (throughput * step).max_component() * eta_scale);
            if (!(q > 0) || rng.next_1d() >= q) break;
            step /= q;
        }
        throughput *= step;
        weight *= step;
        path[i - 1].pdf_rev = convert_density(pdf_rev_omega, path[i], path[i - 1]);
        r = v.isect->spawn_ray(wi);
    }
    return added;
}

}  // namespace reference

std::vector<PathVertex> camera_subpath(const RenderContext& context, const BdptStage& stage,
                                       const Ray& ray, Rng& rng) {
    std::vector<PathVertex> path;
    path.reserve(size_t(std::min(context.settings.max_depth, 16)) + 3);
    PathVertex z0;
    z0.kind = VertexKind::camera;
    z0.p = ray.o;
    z0.beta = Color(1.0);
    path.push_back(z0);
    // A camera ray has weight We cos / (pdf_pos pdf_dir) = 1 (scene/camera_importance.h).
    const double pdf_dir = camera_pdf_We(context.scene.camera, ray.o, ray.d).dir;
    stage.random_walk(context, ray, Color(1.0), pdf_dir, context.settings.max_depth + 1,
                      Transport::radiance, rng, path);
    return path;
}

std::optional<LightStart> light_start(const RenderContext& context, Rng& rng) {
    double pick = 0;
    const Light* light = context.lights.sample_by_power(rng.next_1d(), &pick);
    if (!light || !(pick > 0)) return std::nullopt;
    const Vec2 u_pos = rng.next_2d(), u_dir = rng.next_2d();
    const LightEmission e = light->sample_Le(u_pos, u_dir);
    if (!e.valid() || e.Le.is_black()) return std::nullopt;
    LightStart start;
    PathVertex& y0 = start.y0;
    y0.kind = VertexKind::light;
    y0.light = light;
    y0.p = e.p;
    y0.p_error = e.p_error;
    y0.ng = y0.ns = light->kind() == LightKind::area ? e.n : Vec3();
    y0.w = e.w;
    y0.Le = e.Le;
    y0.pdf_pos = e.pdf_pos;
    y0.pdf_dir = e.pdf_dir;
    y0.pick = pick;
    // Far lights start in direction space: their first density is the
    // direction's (pbrt-v3 section 16.3.3); the others, the point's.
    y0.pdf_fwd = light->at_infinity() ? pick * e.pdf_dir : pick * e.pdf_pos;
    y0.beta = e.Le / y0.pdf_fwd;
    start.ray = e.ray();
    start.beta = e.flux() / pick;
    start.pdf_dir = e.pdf_dir;
    return start;
}

std::vector<PathVertex> light_subpath(const RenderContext& context, const BdptStage& stage, Rng& rng) {
    std::vector<PathVertex> path;
    const std::optional<LightStart> start = light_start(context, rng);
    if (!start) return path;
    path.reserve(size_t(std::min(context.settings.max_depth, 16)) + 1);
    path.push_back(start->y0);
    const Light* light = start->y0.light;
    stage.random_walk(context, start->ray, start->beta, start->pdf_dir, context.settings.max_depth,
                      Transport::importance, rng, path);
    // The vertex after a far light: the density of the disk its rays start on.
    if (light->at_infinity() && path.size() > 1) {
        path[1].pdf_fwd = start->y0.pdf_pos;
        if (path[1].on_surface()) path[1].pdf_fwd *= std::fabs(dot(start->y0.w, path[1].ng));
    }
    return path;
}

}  // namespace pt
