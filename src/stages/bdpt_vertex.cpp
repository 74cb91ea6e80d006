// Densities and values of BDPT's path vertices (stages/bdpt_vertex.h).
#include "stages/bdpt_vertex.h"

#include <cmath>

#include "scene/camera_importance.h"
#include "scene/material.h"
#include "stages/render_context.h"

namespace pt {

bool PathVertex::connectible() const {
    switch (kind) {
        case VertexKind::camera: return true;
        case VertexKind::light: return true;  // a far light joins by its direction
        case VertexKind::escaped: return false;
        case VertexKind::surface: return bsdf && !bsdf->is_delta();
    }
    return false;
}

Vec3 direction_to(const PathVertex& from, const PathVertex& to) {
    if (to.kind == VertexKind::escaped) return to.w;
    if (to.at_infinity()) return -to.w;
    if (from.at_infinity()) return from.kind == VertexKind::escaped ? -from.w : from.w;
    const Vec3 d = to.p - from.p;
    const double n = d.norm();
    return n > 0 ? d / n : Vec3();
}

double convert_density(double pdf_omega, const PathVertex& from, const PathVertex& to) {
    if (to.at_infinity()) return pdf_omega;
    const Vec3 d = to.p - from.p;
    const double d2 = d.norm2();
    if (!(d2 > 0)) return 0;
    double pdf = pdf_omega / d2;
    if (to.on_surface()) pdf *= std::fabs(dot(to.ng, d)) / std::sqrt(d2);
    return std::isfinite(pdf) ? pdf : 0.0;
}

Color vertex_f(const PathVertex& v, const Vec3& wi, Transport mode) {
    if (v.kind != VertexKind::surface || !v.bsdf) return Color(0);
    const BSDF& bsdf = *v.bsdf;
    const Vec3 wo = v.isect->wo;
    const Vec3 wo_l = bsdf.to_local(wo), wi_l = bsdf.to_local(wi);
    Color f = bsdf.f(wo_l, wi_l);
    if (mode == Transport::importance && !f.is_black()) {
        // The adjoint BSDF: a refraction through a rough dielectric loses
        // the radiance factor (n_o / n_i)^2 that f carries (Veach 1997 5.2).
        const Material& m = bsdf.material();
        if (m.type == MaterialType::rough_dielectric && wo_l.z * wi_l.z < 0) {
            const double n_o = wo_l.z > 0 ? 1.0 : m.ior, n_i = wi_l.z > 0 ? 1.0 : m.ior;
            f *= (n_i / n_o) * (n_i / n_o);
        }
        // Shading normals (Veach 1997 5.3): f* = f |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|).
        const Vec3 ns = bsdf.frame().to_world(Vec3(0, 0, 1)), ng = v.isect->ng;
        const double denom = std::fabs(dot(wo, ng)) * std::fabs(dot(wi, ns));
        if (!(denom > 0)) return Color(0);
        f *= std::fabs(dot(wo, ns)) * std::fabs(dot(wi, ng)) / denom;
    }
    return f;
}

double pdf_light(const RenderContext& context, const PathVertex& v, const PathVertex& next) {
    const Light* light = v.light;
    if (v.kind == VertexKind::escaped) light = context.lights.environment();
    if (!light) return 0;
    if (v.at_infinity()) {
        // Rays of a far light start uniformly on a disk facing their
        // direction: per unit area at next, p_disk |cos theta_next|.
        const Vec3 w = v.kind == VertexKind::escaped ? -v.w : v.w;
        double pdf = light->pdf_Le(Vec3(), Vec3(), w).pos;
        if (next.on_surface()) pdf *= std::fabs(dot(next.ng, w));
        return pdf;
    }
    const Vec3 w = direction_to(v, next);
    if (!(w.norm2() > 0)) return 0;
    return convert_density(light->pdf_Le(v.p, v.ng, w).dir, v, next);
}

double pdf_light_origin(const RenderContext& context, const PathVertex& v) {
    const Light* light = v.light;
    if (v.kind == VertexKind::escaped) light = context.lights.environment();
    if (!light) return 0;
    const double pick = context.lights.power_probability(light);
    if (v.at_infinity()) {
        const Vec3 w = v.kind == VertexKind::escaped ? -v.w : v.w;
        return pick * light->pdf_Le(Vec3(), Vec3(), w).dir;
    }
    if (light->kind() == LightKind::point) return pick;  // a delta in position: density 1
    return pick * light->pdf_Le(v.p, v.ng, v.ng).pos;
}

Color vertex_Le(const RenderContext& context, const PathVertex& v, const PathVertex& towards) {
    if (v.kind == VertexKind::escaped) return context.lights.environment_radiance(v.w);
    if (v.kind != VertexKind::surface || !v.isect->material) return Color(0);
    // Area lights are one-sided: they emit on the side of their geometric normal.
    return dot(v.isect->ng, direction_to(v, towards)) > 0 ? v.isect->material->emission : Color(0);
}

double vertex_pdf(const RenderContext& context, const PathVertex& v, const PathVertex* prev,
                  const PathVertex& next) {
    if (v.kind == VertexKind::light || (v.kind == VertexKind::escaped)) return pdf_light(context, v, next);
    if (v.kind == VertexKind::camera) {
            const Vec3 w = direction_to(v, next);
        if (!(w.norm2() > 0)) return 0;
        return convert_density(camera_pdf_We(context.scene.camera, v.p, w).dir, v, next);
    }
    if (!prev || !v.bsdf) return 0;
    const Vec3 wn = direction_to(v, next), wp = direction_to(v, *prev);
    if (!(wn.norm2() > 0) || !(wp.norm2() > 0)) return 0;
    const double pdf_omega = v.bsdf->pdf(v.bsdf->to_local(wp), v.bsdf->to_local(wn));
    return convert_density(pdf_omega, v, next);
}

PathVertex make_surface_vertex(const RenderContext& context, const SurfaceInteraction& isect,
                               const Color& beta) {
    PathVertex v;
    v.kind = VertexKind::surface;
    v.p = isect.p;
    v.ng = isect.ng;
    v.isect = isect;
    v.bsdf.emplace(context.bsdf_at(isect));
    v.ns = v.bsdf->frame().to_world(Vec3(0, 0, 1));
    v.beta = beta;
    v.light = isect.material && !isect.material->emission.is_black()
                  ? context.lights.light_of_primitive(isect.primitive)
                  : nullptr;
    return v;
}

}  // namespace pt
