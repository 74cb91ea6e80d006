// The connection of a light and a camera subpath (stages/bdpt.h, connect)
// and the densities MIS needs at the connection (strategy_weight).
//
// The contribution of strategy (s, t) is, with y = light[s-1], z = camera[t-1]
// and the edge between them (Veach 1997 eq. 10.8):
//
//     C = beta_y f_y(-> z) G(y, z) f_z(-> y) beta_z,   G = V |cos_y| |cos_z| / |y - z|^2,
//
// with the endpoints' special forms: s = 0, z's own emission; t = 1, the
// camera's importance We instead of f_z beta_z (camera_sample_Wi); s = 1,
// the light's emission at y0 divided by the density of y0.
#include <cmath>

#include "scene/camera_importance.h"
#include "stages/bdpt.h"
#include "stages/render_context.h"

namespace pt {
namespace reference {
namespace {

/// Whether nothing lies between surface vertex `from` and the point `to`
/// (moved off its own surface by `to_error` along `to_ng`, when it has one).
bool visible(const RenderContext& context, const PathVertex& from, const Vec3& to, const Vec3& to_error,
             const Vec3& to_ng) {
    Vec3 target = to;
    if (to_ng.norm2() > 0) target = offset_ray_origin(to, to_error, to_ng, from.p - to);
    return !context.occluded(from.isect->spawn_ray_to(target));
}

/// Strategy s = 1: camera vertex z joined to the light subpath's light vertex y0.
Color connect_to_light(const RenderContext& context, const PathVertex& y0, const PathVertex& z) {
    Vec3 wi;      // from z towards the light
    Color E;      // the light's contribution at z per unit of f |cos|, over y0's density
    const LightKind kind = y0.light->kind();
    if (kind == LightKind::directional || kind == LightKind::environment) {
        wi = -y0.w;
        E = kind == LightKind::directional ? y0.Le / y0.pick : y0.Le / (y0.pick * y0.pdf_dir);
    } else {
        const Vec3 d = y0.p - z.p;
        const double d2 = d.norm2();
        if (!(d2 > 0)) return Color(0);
        wi = d / std::sqrt(d2);
        if (kind == LightKind::point) {
            E = y0.Le / (d2 * y0.pick);
        } else {
            const double cos_light = -dot(y0.ng, wi);  // one-sided: its normal's side only
            if (!(cos_light > 0)) return Color(0);
            E = y0.Le * (cos_light / (d2 * y0.pick * y0.pdf_pos));
        }
    }
    Color L = z.beta * vertex_f(z, wi, Transport::radiance) * E * std::fabs(dot(wi, z.ns));
    if (L.is_black()) return L;
    const bool unblocked = y0.at_infinity() ? !context.occluded(z.isect->spawn_ray(wi))
                                            : visible(context, z, y0.p, y0.p_error, y0.ng);
    return unblocked ? L : Color(0);
}

}  // namespace

Connection connect(const RenderContext& context, const std::vector<PathVertex>& light, int s,
                   const std::vector<PathVertex>& camera, int t, Rng& rng) {
    Connection c;
    if (s == 0) {
        // The camera subpath found a light by itself.
        const PathVertex& z = camera[size_t(t) - 1];
        if (t >= 2 && (z.kind == VertexKind::escaped || z.light))
            c.L = z.beta * vertex_Le(context, z, camera[size_t(t) - 2]);
        return c;
    }
    const PathVertex& y = light[size_t(s) - 1];
    if (t == 1) {
        // Light tracing: y seen through the lens, splatted where it lands.
        if (y.kind != VertexKind::surface || !y.connectible()) return c;
        const CameraImportanceSample cs = camera_sample_Wi(context.scene.camera, y.p, rng.next_2d());
        if (!cs.valid()) return c;
        PathVertex z0;
        z0.kind = VertexKind::camera;
        z0.p = cs.p_lens;
        z0.beta = Color(cs.We / cs.pdf);
        Color L = y.beta * vertex_f(y, cs.wi, Transport::importance) * z0.beta * std::fabs(dot(cs.wi, y.ns));
        if (L.is_black() || !visible(context, y, cs.p_lens, Vec3(), Vec3())) return c;
        c.L = L;
        c.camera_vertex = z0;
        c.film = cs.film;
        return c;
    }
    const PathVertex& z = camera[size_t(t) - 1];
    if (z.kind != VertexKind::surface || !z.connectible()) return c;
    if (s == 1) {
        c.L = connect_to_light(context, y, z);
        return c;
    }
    if (y.kind != VertexKind::surface || !y.connectible()) return c;
    const Vec3 d = y.p - z.p;
    const double d2 = d.norm2();
    if (!(d2 > 0)) return c;
    const Vec3 wi = d / std::sqrt(d2);  // from z towards y
    const double G = std::fabs(dot(z.ns, wi)) * std::fabs(dot(y.ns, wi)) / d2;
    Color L = z.beta * vertex_f(z, wi, Transport::radiance) * G *
              vertex_f(y, -wi, Transport::importance) * y.beta;
    if (L.is_black() || !visible(context, z, y.p, y.isect->p_error, y.ng)) return c;
    c.L = L;
    return c;
}

}  // namespace reference

double strategy_weight(const RenderContext& context, const BdptStage& stage,
                       const std::vector<PathVertex>& light, int s,
                       const std::vector<PathVertex>& camera, int t, const Connection& c) {
    // Only (0, 2) makes a path of two vertices: (1, 1) and (2, 0) are not evaluated.
    if (s + t == 2) return 1.0;
    std::vector<MisVertex> lv(static_cast<size_t>(s)), cv(static_cast<size_t>(t));
    for (int i = 0; i < s; ++i) lv[size_t(i)] = {light[size_t(i)].pdf_fwd, light[size_t(i)].pdf_rev, light[size_t(i)].delta};
    for (int i = 0; i < t; ++i) cv[size_t(i)] = {camera[size_t(i)].pdf_fwd, camera[size_t(i)].pdf_rev, camera[size_t(i)].delta};
    const PathVertex* y = s > 0 ? &light[size_t(s) - 1] : nullptr;
    const PathVertex* y_minus = s > 1 ? &light[size_t(s) - 2] : nullptr;
    const PathVertex* z = t == 1 && c.camera_vertex ? &*c.camera_vertex : &camera[size_t(t) - 1];
    const PathVertex* z_minus = t > 1 ? &camera[size_t(t) - 2] : nullptr;

    // The densities with which each subpath would have made the other's
    // endpoint, and the vertex before it, across the new edge.
    MisVertex& zm = cv[size_t(t) - 1];
    zm = {t == 1 ? 0.0 : zm.pdf_fwd, y ? vertex_pdf(context, *y, y_minus, *z) : pdf_light_origin(context, *z), false};
    if (z_minus)
        cv[size_t(t) - 2].pdf_rev = y ? vertex_pdf(context, *z, y, *z_minus) : pdf_light(context, *z, *z_minus);
    if (y) {
        lv[size_t(s) - 1].pdf_rev = vertex_pdf(context, *z, z_minus, *y);
        lv[size_t(s) - 1].delta = false;
    }
    if (y_minus) lv[size_t(s) - 2].pdf_rev = vertex_pdf(context, *y, z, *y_minus);
    const bool delta_light = s > 0 && light[0].light && light[0].light->is_delta();
    return stage.mis_weight(lv.data(), s, cv.data(), t, delta_light, context.settings.mis_heuristic);
}

}  // namespace pt
