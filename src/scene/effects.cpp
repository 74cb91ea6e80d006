#include "scene/effects.h"

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
    add(refraction, "refraction");
    add(diffuse_interreflection, "diffuse_interreflection");
    add(caustics, "caustics");
    add(depth_of_field, "depth_of_field");
    return out;
}

std::string Effects::to_string() const {
    std::string s;
    for (const std::string& n : names()) s += (s.empty() ? "" : ", ") + n;
    return s.empty() ? "none" : s;
}

Effects analyze_effects(const Scene& scene, const RenderSettings& settings) {
    Effects e;
    bool has_geometry = scene.primitive_count() > 0;
    bool any_diffuse = false;
    for (uint32_t i = 0; i < scene.primitive_count(); ++i) {
        switch (scene.material_of(i).type) {
            case MaterialType::diffuse: any_diffuse = true; break;
            case MaterialType::mirror: e.mirror = true; break;
            case MaterialType::glass: e.refraction = true; break;
        }
    }
    e.area_lights = !scene.emitters.empty();
    e.point_lights = !scene.point_lights.empty();
    e.directional_lights = !scene.directional_lights.empty();
    e.environment = scene.environment.has_value();
    e.emission_visible = e.area_lights || e.environment;
    bool lit = e.area_lights || e.point_lights || e.directional_lights || e.environment;
    e.hard_shadows = has_geometry && (e.point_lights || e.directional_lights);
    e.soft_shadows = has_geometry && (e.area_lights || e.environment);
    e.diffuse_interreflection = lit && any_diffuse && settings.max_depth >= 2;
    e.caustics = lit && any_diffuse && (e.mirror || e.refraction) && settings.max_depth >= 2;
    e.depth_of_field = scene.camera.lens_radius > 0;
    return e;
}

}  // namespace pt
