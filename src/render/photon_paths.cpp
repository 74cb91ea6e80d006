#include "render/photon_paths.h"

#include <cmath>

#include "stages/photon.h"
#include "stages/render_context.h"

namespace pt {

std::optional<DiffuseVertex> trace_to_diffuse(const RenderContext& context, Ray ray, Color beta, Rng& rng,
                                              Color* emitted) {
    for (int bounce = 0; bounce <= kMaxSpecularBounces; ++bounce) {
        std::optional<SurfaceInteraction> hit = context.intersect(ray);
        if (!hit) {
            if (emitted) *emitted += beta * context.lights.environment_radiance(ray.d);
            return std::nullopt;
        }
        if (emitted) *emitted += beta * context.stages.direct.zero_bounce_radiance(context, ray, *hit);
        BSDF bsdf = context.bsdf_at(*hit);
        if (!bsdf.is_delta()) return DiffuseVertex{*hit, beta};
        BSDFSample bs = bsdf.sample_f(bsdf.to_local(hit->wo), rng.next_2d());
        if (!bs.valid() || bs.f.is_black()) return std::nullopt;
        beta *= bs.f * (std::fabs(bs.wi.z) / bs.pdf);
        ray = hit->spawn_ray(bsdf.to_world(bs.wi));
    }
    return std::nullopt;
}

double photon_radius(const RenderContext& context, double fraction) {
    const double r = context.settings.photon.radius;
    return r > 0 ? r : fraction * scene_radius(context);
}

}  // namespace pt
