// Part 7, tasks 1 to 3: bidirectional path tracing, written from the
// handout's steps (assignments/part7/README.md) and the contracts of
// src/stages/bdpt.h and src/stages/bdpt_vertex.h.
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "scene/camera_importance.h"
#include "stages/bdpt.h"
#include "stages/global.h"
#include "stages/render_context.h"

namespace pt::student {

int random_walk(const RenderContext& context, const Ray& ray, const Color& beta, double pdf_dir,
                int max_vertices, Transport mode, Rng& rng, std::vector<PathVertex>& path) {
    // TODO(part7.1) done.
    int added = 0;
    Ray r = ray;
    Color b = beta;
    double pdf_omega = pdf_dir;  // density of r.d, per unit solid angle
    while (added < max_vertices) {
        const std::optional<SurfaceInteraction> hit = context.intersect(r);
        if (!hit) {
            // A camera ray that leaves the scene sees the environment.
            if (mode == Transport::radiance && context.lights.environment()) {
                PathVertex v;
                v.kind = VertexKind::escaped;
                v.w = normalize(r.d);
                v.beta = b;
                v.pdf_fwd = pdf_omega;  // stays per solid angle
                path.push_back(v);
                ++added;
            }
            break;
        }
        PathVertex v = make_surface_vertex(context, *hit, b);
        v.pdf_fwd = convert_density(pdf_omega, path.back(), v);
        path.push_back(v);
        ++added;
        if (added == max_vertices) break;

        PathVertex& cur = path.back();
        const BSDF& bsdf = *cur.bsdf;
        const Vec3 wo = bsdf.to_local(hit->wo);
        const BSDFSample bs = bsdf.sample_f(wo, rng.next_2d());
        if (!bs.valid()) break;
        const Vec3 wi = bsdf.to_world(bs.wi);
        Color weight = bs.f * (std::fabs(bs.wi.z) / bs.pdf);
        if (mode == Transport::importance) {
            // The adjoint: no (n_o / n_i)^2 at a refraction (README eq. 4)
            // and Veach's shading-normal correction (README eq. 5).
            weight *= bs.eta * bs.eta;
            const double denom = std::fabs(dot(hit->wo, cur.ng)) * std::fabs(dot(wi, cur.ns));
            if (!(denom > 0)) break;
            weight *= std::fabs(dot(hit->wo, cur.ns)) * std::fabs(dot(wi, cur.ng)) / denom;
        }
        // The densities both ways; a delta bounce can be made by no other strategy.
        double pdf_rev_omega = 0;
        if (bs.is_delta) {
            cur.delta = true;
            pdf_omega = 0;
        } else {
            pdf_omega = bs.pdf;
            pdf_rev_omega = bsdf.pdf(bs.wi, wo);
        }
        PathVertex& prev = path[path.size() - 2];
        prev.pdf_rev = convert_density(pdf_rev_omega, cur, prev);
        // Russian roulette on the walk's own throughput.
        if (context.settings.russian_roulette && added >= context.settings.rr_depth) {
            const double q = std::min(kMaxSurvivalProbability, (b * weight).max_component());
            if (rng.next_1d() >= q) break;
            weight /= q;
        }
        b *= weight;
        r = hit->spawn_ray(wi);
    }
    return added;
}

Connection connect(const RenderContext& context, const std::vector<PathVertex>& light, int s,
                   const std::vector<PathVertex>& camera, int t, Rng& rng) {
    // TODO(part7.2) done.
    Connection c;
    const PathVertex& z = camera[size_t(t) - 1];
    if (s == 0) {
        // The camera subpath found a light on its own.
        if (t < 2) return c;
        c.L = z.beta * vertex_Le(context, z, camera[size_t(t) - 2]);
        return c;
    }
    const PathVertex& y = light[size_t(s) - 1];
    if (t == 1) {
        // Light tracing: join y to a point of the lens ((1, 1) is left out).
        if (s == 1 || !y.connectible()) return c;
        const CameraImportanceSample cs = camera_sample_Wi(context.scene.camera, y.p, rng.next_2d());
        if (!cs.valid()) return c;
        PathVertex lens;
        lens.kind = VertexKind::camera;
        lens.p = cs.p_lens;
        lens.beta = Color(cs.We / cs.pdf);
        c.L = y.beta * vertex_f(y, cs.wi, Transport::importance) * lens.beta *
              std::fabs(dot(cs.wi, y.ns));
        if (c.L.is_black()) return c;
        if (context.occluded(y.isect->spawn_ray_to(cs.p_lens))) {
            c.L = Color(0);
            return c;
        }
        c.camera_vertex = lens;
        c.film = cs.film;
        return c;
    }
    if (!z.connectible()) return c;
    if (s == 1) {
        // Next-event estimation with the light subpath's own light point.
        Vec3 wi;  // from z towards the light
        double g = 0;
        Ray shadow;
        if (y.at_infinity()) {
            wi = -y.w;
            g = std::fabs(dot(wi, z.ns));
            shadow = z.isect->spawn_ray(wi);
        } else {
            const Vec3 d = y.p - z.p;
            const double d2 = d.norm2();
            if (!(d2 > 0)) return c;
            wi = d / std::sqrt(d2);
            g = std::fabs(dot(wi, z.ns)) / d2;
            if (y.on_surface()) {
                // One-sided area light: it emits on the side of its normal.
                if (!(dot(y.ng, -wi) > 0)) return c;
                g *= std::fabs(dot(wi, y.ng));
                shadow = z.isect->spawn_ray_to(offset_ray_origin(y.p, y.p_error, y.ng, -wi));
            } else {
                shadow = z.isect->spawn_ray_to(y.p);
            }
        }
        c.L = z.beta * vertex_f(z, wi, Transport::radiance) * g * y.beta;
        if (!c.L.is_black() && context.occluded(shadow)) c.L = Color(0);
        return c;
    }
    // Two surface vertices: beta_y f_y G f_z beta_z (README eq. 6).
    if (!y.connectible()) return c;
    const Vec3 d = y.p - z.p;
    const double d2 = d.norm2();
    if (!(d2 > 0)) return c;
    const Vec3 wi = d / std::sqrt(d2);
    const double g = std::fabs(dot(wi, z.ns)) * std::fabs(dot(wi, y.ns)) / d2;
    c.L = y.beta * vertex_f(y, -wi, Transport::importance) * g * vertex_f(z, wi, Transport::radiance) *
          z.beta;
    if (c.L.is_black()) return c;
    const Vec3 target = offset_ray_origin(y.p, y.isect->p_error, y.ng, -wi);
    if (context.occluded(z.isect->spawn_ray_to(target))) c.L = Color(0);
    return c;
}

double mis_weight(const MisVertex* light, int s, const MisVertex* camera, int t, bool delta_light,
                  MisHeuristic heuristic) {
    // TODO(part7.3) done: the ratio recursion (README eq. 8).
    if (s + t == 2) return 1.0;
    auto nonzero = [](double p) { return p != 0 ? p : 1.0; };
    auto term = [heuristic](double r) { return heuristic == MisHeuristic::power ? r * r : r; };
    double sum = 0;
    // Towards the camera: strategy (s + t - i, i) for i = t - 1 .. 1.
    double r = 1;
    for (int i = t - 1; i >= 1; --i) {
        r *= nonzero(camera[i].pdf_rev) / nonzero(camera[i].pdf_fwd);
        if (!camera[i].delta && !camera[i - 1].delta) sum += term(r);
    }
    // Towards the light: strategy (i, s + t - i) for i = s - 1 .. 0.
    r = 1;
    for (int i = s - 1; i >= 0; --i) {
        r *= nonzero(light[i].pdf_rev) / nonzero(light[i].pdf_fwd);
        const bool before_delta = i > 0 ? light[i - 1].delta : delta_light;
        if (!light[i].delta && !before_delta) sum += term(r);
    }
    return 1.0 / (1.0 + sum);
}

}  // namespace pt::student
