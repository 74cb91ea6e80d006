#include "stages/effects.h"

#include <algorithm>
#include <cmath>

namespace pt {

std::vector<std::string> Effects::names() const {
    std::vector<std::string> out;
    auto add = [&](bool on, const char* name) {
        if (on) out.push_back(name);
    };
    add(emission_visible, "emission_visible");
    add(point_lights, "point_lights");
    add(directional_lights, "directional_lights");
    add(area_lights, "area_lights");
    add(environment, "environment");
    add(hard_shadows, "hard_shadows");
    add(soft_shadows, "soft_shadows");
    add(mirror, "mirror");
    add(glossy, "glossy");
    add(refraction, "refraction");
    add(diffuse_interreflection, "diffuse_interreflection");
    add(caustics, "caustics");
    add(point_light_caustics, "point_light_caustics");
    add(specular_diffuse_specular, "specular_diffuse_specular");
    add(depth_of_field, "depth_of_field");
    add(medium_absorption, "medium_absorption");
    add(single_scattering, "single_scattering");
    add(multiple_scattering, "multiple_scattering");
    return out;
}

std::string Effects::to_string() const {
    std::string s;
    for (const std::string& n : names())
        s += (s.empty() ? "" : ", ") + n;
    return s.empty() ? "none" : s;
}

namespace {

/// Every point light lies in `inside` and no light is at infinity.
template <class Inside>
bool all_lights_within(const Scene& scene, Inside inside) {
    if (!scene.directional_lights.empty() || scene.environment) return false;
    for (const PointLight& light : scene.point_lights)
        if (!inside(light.position)) return false;
    return true;
}

}  // namespace

bool scene_can_occlude(const Scene& scene) {
    const uint32_t count = scene.primitive_count();
    if (!scene.instances.empty()) return true;  // instanced shapes: assume so
    if (count == 0) return false;
    if (!scene.spheres.empty()) {
        if (count > 1) return true;  // a sphere and anything else: assume so
        // One sphere. Seen from outside, a path meets it once, on the side
        // facing out, and every light that side faces is outside its
        // tangent plane. Seen from inside, only lights inside are unblocked
        // (its own emission faces outwards and cannot be sampled from inside).
        const Sphere& s = scene.spheres[0].sphere;
        double camera_distance = (scene.camera.position - s.center).norm();
        if (camera_distance >= s.radius + scene.camera.lens_radius) return false;
        return !all_lights_within(scene,
                                  [&](const Vec3& p) { return (p - s.center).norm() < s.radius; });
    }
    // Triangles only. Each one's plane with the side the other vertices lie
    // on; a scene is convex when no plane has vertices on both sides.
    // Quadratic, so only for small scenes; a non-convex scene usually fails
    // at the first triangle.
    if (scene.triangles.size() > 4096) return true;
    // OBJ coordinates arrive as floats: planar quads are planar to ~1e-7.
    const double tolerance = 1e-6 * std::max(scene.bounds.extent().norm(), 1e-300);
    struct Plane {
        Vec3 n;   ///< unit normal pointing away from the vertices
        Vec3 p0;  ///< a point of the plane
    };
    std::vector<Plane> planes;
    bool flat = true;
    for (uint32_t i = 0; i < count; ++i) {
        Triangle t = scene.triangle(i);
        Vec3 n = cross(t.p1 - t.p0, t.p2 - t.p0);
        double len = n.norm();
        if (!(len > 0)) continue;  // degenerate: no area, blocks nothing
        n = n / len;
        bool above = false, below = false;
        for (const TriangleRecord& r : scene.triangles) {
            for (uint32_t v : r.v) {
                double d = dot(scene.positions[v] - t.p0, n);
                above |= d > tolerance;
                below |= d < -tolerance;
            }
            if (above && below) return true;  // not convex
        }
        flat &= !above && !below;
        planes.push_back({above ? -n : n, t.p0});
    }
    // All in one plane: a light sample on the side a path reaches the
    // plane from is never behind it.
    if (flat) return false;
    // A convex body: the segment between a point of its boundary and a point
    // inside every supporting half-space (an area light on the boundary, a
    // point light inside) stays inside and crosses no triangle. Lights
    // outside, or at infinity, may be blocked (a path can enter the body
    // through an opening, or start inside it).
    return !all_lights_within(scene, [&](const Vec3& p) {
        for (const Plane& plane : planes)
            if (dot(p - plane.p0, plane.n) > tolerance) return false;
        return true;
    });
}

Effects analyze_effects(const Scene& scene, const RenderSettings& settings) {
    Effects e;
    const int m = settings.max_depth;
    const bool has_geometry = scene.has_geometry();
    bool any_nonspecular = false, any_specular = false;
    bool mirror = false, glass = false, glossy = false;
    const uint32_t ids = scene.primitive_count() + uint32_t(scene.instances.size());  // instances last
    for (uint32_t i = 0; i < ids; ++i) {
        switch (scene.material_of(i).type) {
            case MaterialType::diffuse:
                any_nonspecular = true;
                break;
            case MaterialType::microfacet:
                any_nonspecular = glossy = true;
                break;
            case MaterialType::mirror:
                any_specular = mirror = true;
                break;
            case MaterialType::glass:
                any_specular = glass = true;
                break;
            case MaterialType::rough_dielectric:
                any_nonspecular = glossy = glass = true;
                break;
            case MaterialType::null:
                break;  // nothing there: light goes straight on
        }
    }
    const bool area = !scene.emitters.empty(), environment = scene.environment.has_value();
    const bool point = !scene.point_lights.empty(), directional = !scene.directional_lights.empty();
    const bool lit = area || environment || point || directional;
    // Emission seen directly is bounce 0: shown when -o 1, or when -m 0.
    e.emission_visible = (area || environment) && (settings.accumulate_bounces || m == 0);
    // Light reflected at a surface needs at least one bounce.
    const bool bounces = m >= 1 && has_geometry;
    e.area_lights = bounces && area;
    e.environment = (bounces && environment) || (environment && e.emission_visible);
    e.point_lights = bounces && point;
    e.directional_lights = bounces && directional;
    const bool occluders = scene_can_occlude(scene);
    e.hard_shadows = bounces && occluders && (point || directional);
    e.soft_shadows = bounces && occluders && (area || environment);
    e.mirror = bounces && lit && mirror;
    e.glossy = bounces && lit && glossy;
    e.refraction = bounces && lit && glass;
    e.diffuse_interreflection = lit && any_nonspecular && m >= 2;
    // Delta lights cannot be reached by a path through a specular surface,
    // so caustics need an area light or the sky.
    e.caustics = (area || environment) && any_nonspecular && any_specular && m >= 2;
    e.point_light_caustics = (point || directional) && any_nonspecular && any_specular && m >= 2;
    e.specular_diffuse_specular = lit && any_nonspecular && any_specular && m >= 3;
    e.depth_of_field = scene.camera.lens_radius > 0;
    // Media: any medium dims what is seen through it; one that scatters
    // lights itself (a bounce) and, from -m 2, lights itself again.
    bool scattering_medium = false;
    for (const Medium& medium : scene.media) {
        e.medium_absorption |= !medium.sigma_t().is_black();
        scattering_medium |= medium.scatters();
    }
    e.single_scattering = scattering_medium && lit && m >= 1;
    e.multiple_scattering = scattering_medium && lit && m >= 2;
    return e;
}

CodePaths plan_code_paths(const Scene& scene, const Effects& e, const RenderSettings& settings) {
    const CodePaths& f = settings.force;
    CodePaths p;
    const bool lit = !scene.emitters.empty() || scene.environment || !scene.point_lights.empty() ||
                     !scene.directional_lights.empty();
    p.light_sampling = f.light_sampling || (lit && settings.max_depth >= 1);
    p.shadow_rays = f.shadow_rays || e.hard_shadows || e.soft_shadows;
    p.emission = f.emission || !scene.emitters.empty() || scene.environment.has_value();
    p.refraction = f.refraction || e.refraction;
    p.lens_sampling = f.lens_sampling || e.depth_of_field;
    return p;
}

std::string skipped_code_paths(const CodePaths& p) {
    std::string s;
    auto add = [&](bool run, const char* what) {
        if (!run) s += (s.empty() ? "" : ", ") + std::string(what);
    };
    add(p.light_sampling, "light sampling (no light, or -m 0)");
    add(p.shadow_rays, "shadow rays (no light sample can be blocked)");
    add(p.emission, "emission look-ups (nothing emits)");
    add(p.refraction, "refraction bookkeeping (no glass)");
    add(p.lens_sampling, "lens sampling (pinhole)");
    return s.empty() ? "none" : s;
}

}  // namespace pt
