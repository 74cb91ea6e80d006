#include "scene/light_set.h"

#include "scene/lights.h"
#include "scene/scene.h"

namespace pt {
namespace {

/// Whether triangles a and b share a corner (by vertex index).
bool share_vertex(const TriangleRecord& a, const TriangleRecord& b) {
    for (uint32_t i : a.v)
        for (uint32_t j : b.v)
            if (i == j) return true;
    return false;
}

}  // namespace

LightSet::LightSet(const Scene& scene) {
    light_of_primitive_.assign(scene.primitive_count(), -1);
    auto add = [&](std::unique_ptr<Light> light) {
        if (!light->is_delta()) ++non_delta_count_;
        lights_.push_back(std::move(light));
        return int32_t(lights_.size() - 1);
    };

    // Area lights. Scene::emitters is in increasing id order, so a run of
    // consecutive ids is a run of consecutive triangles of one object.
    const std::vector<uint32_t>& emitters = scene.emitters;
    for (size_t i = 0; i < emitters.size();) {
        uint32_t first = emitters[i];
        const Material& material = scene.material_of(first);
        if (scene.is_sphere(first)) {
            int32_t index =
                add(make_sphere_light(scene.sphere_record(first).sphere, material.emission));
            light_of_primitive_[first] = index;
            ++i;
            continue;
        }
        size_t end = i + 1;
        while (end < emitters.size()) {
            uint32_t prev = emitters[end - 1], next = emitters[end];
            if (next != prev + 1 || scene.is_sphere(next) ||
                scene.triangles[next].material != scene.triangles[prev].material ||
                !share_vertex(scene.triangles[prev], scene.triangles[next]))
                break;
            ++end;
        }
        std::vector<Triangle> triangles;
        for (size_t k = i; k < end; ++k)
            triangles.push_back(scene.triangle(emitters[k]));
        int32_t index = add(make_triangle_light(triangles, material.emission));
        for (size_t k = i; k < end; ++k)
            light_of_primitive_[emitters[k]] = index;
        i = end;
    }

    for (const PointLight& light : scene.point_lights)
        add(make_point_light(light));
    for (const DirectionalLight& light : scene.directional_lights)
        add(make_directional_light(light, scene.bounds));
    if (scene.environment) {
        int32_t index = add(make_environment_light(*scene.environment, scene.bounds));
        environment_ = lights_[size_t(index)].get();
    }
}

const Light* LightSet::light_of_primitive(uint32_t prim) const {
    if (prim >= light_of_primitive_.size() || light_of_primitive_[prim] < 0) return nullptr;
    return lights_[size_t(light_of_primitive_[prim])].get();
}

Color LightSet::environment_radiance(const Vec3& direction) const {
    return environment_ ? environment_->Le(direction) : Color(0);
}

}  // namespace pt
