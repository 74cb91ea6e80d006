// Effects: which light-transport effects can contribute to an image of a
// scene with given settings (DESIGN.md "Effects: simulate only what the
// scene calls for"). The renderer prints the set at start-up, writes it to
// --stats, and runs only the code paths the set needs.
#pragma once

#include <string>
#include <vector>

#include "render/settings.h"
#include "scene/scene.h"

namespace pt {

struct Effects {
    bool emission_visible = false;    ///< an emitter or the environment can be seen directly
    bool point_lights = false;        ///< direct light from point lights
    bool directional_lights = false;  ///< direct light from directional lights
    bool area_lights = false;         ///< direct light from emissive primitives
    bool environment = false;         ///< light from the environment
    bool hard_shadows = false;        ///< shadows of delta (point, directional) lights
    bool soft_shadows = false;        ///< shadows of area or environment lights
    bool mirror = false;              ///< perfect specular reflection
    bool refraction = false;          ///< glass
    bool diffuse_interreflection = false;  ///< light bouncing between diffuse surfaces (-m >= 2)
    bool caustics = false;            ///< light focused by mirrors or glass onto diffuse surfaces
    bool depth_of_field = false;      ///< thin lens (-b > 0)

    /// Names of the effects present, in a fixed order ("area_lights", ...).
    std::vector<std::string> names() const;
    /// "area_lights, soft_shadows, ..." or "none".
    std::string to_string() const;
};

Effects analyze_effects(const Scene& scene, const RenderSettings& settings);

}  // namespace pt
