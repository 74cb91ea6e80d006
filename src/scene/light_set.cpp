#include "scene/light_set.h"

#include <algorithm>
#include <cmath>

#include "scene/interaction.h"
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

    // Light selection by power (for light subpaths and photons).
    double total = 0;
    for (size_t i = 0; i < lights_.size(); ++i) {
        const Light* light = lights_[i].get();
        index_.emplace(light, i);
        double y = light->power().luminance();
        power_probability_.push_back(y > 0 && std::isfinite(y) ? y : 0.0);
        total += power_probability_.back();
    }
    for (double& p : power_probability_)
        p = total > 0 ? p / total : 1.0 / double(lights_.size());
    double sum = 0;
    for (double p : power_probability_)
        power_cdf_.push_back(sum += p);
    if (!power_cdf_.empty()) power_cdf_.back() = 1.0;
}

const Light* LightSet::sample_by_power(double u, double* probability) const {
    if (lights_.empty()) {
        if (probability) *probability = 0;
        return nullptr;
    }
    size_t i = size_t(std::upper_bound(power_cdf_.begin(), power_cdf_.end(), u) - power_cdf_.begin());
    i = std::min(i, lights_.size() - 1);
    while (i > 0 && !(power_probability_[i] > 0)) --i;  // a zero-width step, reached by rounding
    if (probability) *probability = power_probability_[i];
    return lights_[i].get();
}

double LightSet::power_probability(const Light* light) const {
    auto it = index_.find(light);
    return it == index_.end() ? 0.0 : power_probability_[it->second];
}

Ray LightEmission::ray() const {
    return Ray(offset_ray_origin(p, p_error, n.norm2() > 0 ? n : w, w), w, kSpawnTMin, kInfinity);
}

const Light* LightSet::light_of_primitive(uint32_t prim) const {
    if (prim >= light_of_primitive_.size() || light_of_primitive_[prim] < 0) return nullptr;
    return lights_[size_t(light_of_primitive_[prim])].get();
}

Color LightSet::environment_radiance(const Vec3& direction) const {
    return environment_ ? environment_->Le(direction) : Color(0);
}

}  // namespace pt
