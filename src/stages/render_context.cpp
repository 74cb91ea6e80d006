#include "stages/render_context.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/counters.h"
#include "core/math.h"
#include "stages/integrator.h"
#include "stages/effects.h"

namespace pt {

namespace {

/// The interaction on an instance: made in the shape's object space (the
/// ray mapped by the inverse transform, so t is the same), then mapped
/// back; normals by the inverse transpose (Transform::normal), the point's
/// error bound carried through the map (Transform::point_error).
SurfaceInteraction make_instance_interaction(const Scene& scene, const Ray& ray, const Hit& hit) {
    const Transform& m = scene.instance(hit.primitive).to_world;
    Ray local = ray;
    local.o = m.inverse_point(ray.o);
    local.d = m.inverse_vector(ray.d);
    Hit part = hit;
    part.primitive = hit.part;
    part.part = kNoIndex;
    SurfaceInteraction si = make_interaction(scene.shape_of(hit.primitive), local, part);
    si.p_error = m.point_error(si.p, si.p_error);
    si.p = m.point(si.p);
    si.ng = m.normal(si.ng);
    si.n = hit.n;  // the accelerator mapped it already
    double len = si.n.norm();
    si.n = (len > 0 && std::isfinite(len)) ? si.n / len : si.ng;
    si.wo = (-ray.d).unit();
    si.primitive = hit.primitive;
    si.part = hit.part;
    si.material = &scene.material_of(hit.primitive);
    return si;
}

}  // namespace

SurfaceInteraction make_interaction(const Scene& scene, const Ray& ray, const Hit& hit) {
    if (scene.is_instance(hit.primitive)) return make_instance_interaction(scene, ray, hit);
    SurfaceInteraction si;
    si.t = hit.t;
    si.b1 = hit.b1;
    si.b2 = hit.b2;
    si.primitive = hit.primitive;
    si.material = &scene.material_of(hit.primitive);
    si.wo = (-ray.d).unit();
    si.depth = ray.depth;
    if (scene.is_sphere(hit.primitive)) {
        // Re-project onto the sphere: |p - c| = r up to a few ulp, whatever t's
        // error (pbrt-v3 section 3.9.4); the bound covers the re-projection
        // and the addition of the centre.
        const Sphere& s = scene.sphere_record(hit.primitive).sphere;
        Vec3 local = ray.o + hit.t * ray.d - s.center;
        local *= s.radius / local.norm();
        si.p = s.center + local;
        si.p_error = gamma(6) * (abs(local) + abs(s.center));
        si.ng = local / s.radius;
        if (scene.sphere_record(hit.primitive).inward) si.ng = -si.ng;  // subtracted by CSG
    } else {
        // Barycentric interpolation has error at most gamma(7) sum |b_i p_i|
        // (pbrt-v3 section 3.9.3), independent of how inaccurate t is.
        Triangle tri = scene.triangle(hit.primitive);
        double b0 = 1.0 - hit.b1 - hit.b2;
        si.p = b0 * tri.p0 + hit.b1 * tri.p1 + hit.b2 * tri.p2;
        si.p_error = gamma(7) * (abs(b0 * tri.p0) + abs(hit.b1 * tri.p1) + abs(hit.b2 * tri.p2));
        si.ng = cross(tri.p1 - tri.p0, tri.p2 - tri.p0).unit();
    }
    si.n = hit.n;
    // A student routine may hand back an unnormalised or zero normal; the
    // film must still never see NaN, so fall back to the geometric normal.
    double len = si.n.norm();
    si.n = (len > 0 && std::isfinite(len)) ? si.n / len : si.ng;
    return si;
}

namespace {

std::shared_ptr<const Sampler> make_sampler(const Scene& scene, const LightSet& lights, const Stages& stages,
                                            const RenderSettings& settings, IntegratorKind integrator) {
    if (settings.sampler == SamplerKind::independent) return nullptr;
    SamplerSettings s;
    s.kind = settings.sampler;
    s.seed = settings.seed;
    // The split adaptive rule averages only every other sample: stratify those.
    s.spp = settings.adaptive && settings.adaptive_rule == AdaptiveRule::split ? (settings.spp + 1) / 2 : settings.spp;
    // sppm draws camera sample `pass` of every pixel: one per --passes, not
    // per -s. Sized by -s (1 by default), zsobol's sample index spilled into
    // the pixel's Morton code, so passes repeated other pixels' samples
    // (relMSE 3.6 times too high on caustic_glass, docs/photon_mapping.md).
    if (integrator == IntegratorKind::sppm && settings.photon.passes > 0) s.spp = std::max(s.spp, settings.photon.passes);
    s.width = scene.film_width;
    s.height = scene.film_height;
    // Light 2D draws per shading point: the size of a bounce's light slot.
    s.light_samples_per_vertex = 0;
    for (const std::unique_ptr<Light>& light : lights.all())
        s.light_samples_per_vertex += light->sample_count(settings.light_samples);
    return std::make_shared<const Sampler>(s, stages.sampler.functions());
}

/// `stages` with generate_ray replaced by the projection of a camera that
/// is not perspective (Part 1's generate_ray is the perspective one).
Stages with_camera_projection(Stages stages, const Camera& camera) {
    if (camera.type == CameraType::orthographic) stages.camera.generate_ray = orthographic_ray;
    if (camera.type == CameraType::fisheye) stages.camera.generate_ray = fisheye_ray;
    return stages;
}

}  // namespace

RenderContext::RenderContext(const Scene& scene_, const Accelerator& accelerator_,
                             const Stages& stages_, const RenderSettings& settings_,
                             const Integrator& integrator_)
    : owned_lights_(std::make_shared<const LightSet>(scene_)),
      owned_stages_(with_camera_projection(stages_, scene_.camera)),
      owned_sampler_(make_sampler(scene_, *owned_lights_, stages_, settings_, integrator_.kind())),
      scene(scene_),
      accelerator(accelerator_),
      stages(owned_stages_),
      settings(settings_),
      integrator(integrator_),
      lights(*owned_lights_),
      code_paths(plan_code_paths(scene_, analyze_effects(scene_, settings_), settings_)),
      sampler(owned_sampler_.get()) {}

Rng RenderContext::sample_generator(int x, int y, int index) const {
    const uint64_t pixel = uint64_t(y) * uint64_t(scene.film_width) + uint64_t(x);
    if (!sampler) return Rng(settings.seed, pixel, uint64_t(index));
    return Rng(*sampler, uint32_t(x), uint32_t(y), pixel, uint64_t(index));
}

namespace {
thread_local TracedCameraRays* t_traced_camera_rays = nullptr;

/// The same bits (so -0.0 is not 0.0: the slab test tells them apart).
bool same_ray(const Ray& a, const Ray& b) {
    const double x[8] = {a.o.x, a.o.y, a.o.z, a.d.x, a.d.y, a.d.z, a.t_min, a.t_max};
    const double y[8] = {b.o.x, b.o.y, b.o.z, b.d.x, b.d.y, b.d.z, b.t_min, b.t_max};
    return std::memcmp(x, y, sizeof x) == 0;
}
}  // namespace

const std::optional<Hit>* TracedCameraRays::take(const Ray& ray) {
    for (size_t i = next; i < rays.size() && i < next + 2; ++i) {
        if (same_ray(rays[i], ray)) {
            next = i + 1;
            return &hits[i];
        }
    }
    return nullptr;
}

void set_traced_camera_rays(TracedCameraRays* list) {
    t_traced_camera_rays = list;
}

const TracedCameraRays* traced_camera_rays() {
    return t_traced_camera_rays;
}

std::optional<SurfaceInteraction> RenderContext::intersect(const Ray& ray) const {
    ++thread_counters().closest_hit_rays;
    if (TracedCameraRays* traced = t_traced_camera_rays) {
        if (const std::optional<Hit>* hit = traced->take(ray)) {
            ++thread_counters().packet_rays;
            if (!*hit) return std::nullopt;
            return make_interaction(scene, ray, **hit);
        }
    }
    std::optional<Hit> hit = accelerator.intersect(ray);
    if (!hit) return std::nullopt;
    return make_interaction(scene, ray, *hit);
}

bool RenderContext::occluded(const Ray& ray) const {
    if (!code_paths.shadow_rays) return false;  // nothing in the scene can block a light sample
    ++thread_counters().shadow_rays;
    return accelerator.occluded(ray);
}

Color RenderContext::radiance(const Ray& ray, Rng& rng) const {
    if (sees_nothing(ray)) return Color(0);
    Color L = integrator.Li(*this, ray, rng);
    // Clamping trades bias for less variance; only on request, and counted.
    if (settings.clamp > 0 && L.max_component() > settings.clamp) {
        ++thread_counters().clamped_samples;
        L *= settings.clamp / L.max_component();
    }
    return L;
}

BSDF RenderContext::bsdf_at(const SurfaceInteraction& isect) const {
    const Material& material = *isect.material;
    Vec3 n = isect.n;
    const bool keeps_normal = material.type == MaterialType::glass || material.type == MaterialType::rough_dielectric;
    if (!keeps_normal) {
        // The side is the geometric normal's (the true surface); the shading
        // normal, which may disagree near silhouettes of smooth meshes or
        // when a mesh's vertex normals oppose its winding, is turned into
        // that hemisphere. Glass keeps its normal: it must know in from out.
        Vec3 ng = dot(isect.ng, isect.wo) < 0 ? -isect.ng : isect.ng;
        if (dot(n, ng) < 0) n = -n;
    }
    // A textured albedo is looked up at the hit's (u, v) (scene/texture.h).
    Color albedo = material.albedo_texture
                       ? material.albedo_texture->evaluate(scene.uv_at(isect.primitive, isect.b1, isect.b2, isect.p, isect.part))
                       : material.albedo;
    // Anisotropic roughness needs the frame's x axis along the surface's u direction.
    const bool anisotropic = material.roughness_y >= 0 && material.roughness_y != material.roughness &&
                             (material.type == MaterialType::microfacet || keeps_normal);
    Frame frame = anisotropic ? Frame::with_tangent(n, scene.dpdu(isect.primitive, isect.p, isect.part)) : Frame(n);
    return BSDF(material, frame, {stages.direct.diffuse_f, stages.direct.diffuse_sample_f}, albedo);
}

}  // namespace pt
