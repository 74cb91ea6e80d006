// Lights that are not geometry. Area lights are not listed here: every
// primitive whose material emits is one (Scene::emitters), one-sided on the
// side of its geometric normal (a sphere emits outward).
#pragma once

#include <string>

#include "core/color.h"
#include "core/vec3.h"

namespace pt {

/// An isotropic point light. Irradiance at distance r, normal incidence:
/// E = intensity / r^2.
struct PointLight {
    Vec3 position;
    Color intensity;  ///< radiant intensity, W/sr
};

/// A light infinitely far away (the sun). Irradiance on a surface facing it:
/// E = irradiance.
struct DirectionalLight {
    Vec3 direction;    ///< unit direction the light travels in (from the light to the scene)
    Color irradiance;  ///< irradiance on a surface perpendicular to `direction`, W/m^2
};

/// Light arriving from infinitely far in every direction: constant radiance,
/// or a lat-long map (loaded and sampled by Part 4).
struct EnvironmentLight {
    Color radiance{1, 1, 1};  ///< constant radiance, or a multiplier on the map, W/(m^2 sr)
    std::string file;         ///< lat-long .hdr or .pfm; empty for a constant environment
    double scale = 1.0;       ///< multiplier on the map's values
};

}  // namespace pt
