// Effects: which light-transport effects can contribute to an image of a
// scene with given settings (DESIGN.md "Effects: simulate only what the
// scene calls for"). The renderer prints the set at start-up, writes it to
// --stats, and runs only the code paths the set needs (plan_code_paths):
//
//   code path        runs when                              skipped, it saves
//   light_sampling   some light exists and -m >= 1          next-event estimation
//   shadow_rays      hard_shadows or soft_shadows           every shadow ray (occluded() is false)
//   emission         an emitter or the environment exists   emission look-ups and MIS weights
//                                                           at BSDF-sampled hits, last bounce rays
//   refraction       glass exists                           the eta^2 book-keeping of roulette
//   lens_sampling    depth_of_field (-b > 0)                a lens sample per camera ray
//
// and `--integrator auto` picks the cheapest integrator that simulates the
// whole set (render/integrator_choice.cpp). Shadows need an occluder
// (scene_can_occlude): no light sample is ever blocked when all surfaces
// lie in one plane; or form one sphere seen from outside (a path meets it
// once, on the side facing out, and every light that side faces is beyond
// the tangent plane); or lie on the boundary of one convex body that holds
// every light (area lights on its boundary, point lights inside; the
// interior furnace box), since a segment between two points of a convex
// body never crosses its boundary.
//
// Tests: tests/global/test_effects.cpp renders scenes without each effect
// with its code path forced on and off (RenderSettings::force) and checks
// the images are byte-identical; `bench effects` measures the savings.
#pragma once

#include <string>
#include <vector>

#include "stages/settings.h"
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
    bool glossy = false;              ///< rough (microfacet) reflection
    bool refraction = false;          ///< glass
    bool diffuse_interreflection =
        false;              ///< light bouncing between non-specular surfaces (-m >= 2)
    bool caustics = false;  ///< light from area or sky lights focused by mirrors or glass (-m >= 2)
    /// Light from point or directional lights through mirrors or glass onto
    /// a non-specular surface (L S+ D, -m >= 2): no path from the camera can
    /// find a delta light through a specular bounce, so only photon mapping carries it.
    bool point_light_caustics = false;
    /// Specular-diffuse-specular paths: a caustic seen in a mirror or through
    /// glass (L S+ D S+ E, -m >= 3); with a point light, photon mapping's alone.
    bool specular_diffuse_specular = false;
    bool depth_of_field = false;  ///< thin lens (-b > 0)
    bool medium_absorption = false;    ///< light dimmed along rays by participating media (extinction)
    bool single_scattering = false;    ///< light scattered once in a medium towards the camera (-m >= 1)
    bool multiple_scattering = false;  ///< light scattered more than once in media (-m >= 2)

    /// Names of the effects present, in a fixed order ("area_lights", ...).
    std::vector<std::string> names() const;
    /// "area_lights, soft_shadows, ..." or "none".
    std::string to_string() const;
};

Effects analyze_effects(const Scene& scene, const RenderSettings& settings);

/// Whether some surface of the scene can block a light sample (see the file
/// comment); true whenever that cannot be proved cheaply (a sphere with
/// other primitives, more than 4096 triangles).
bool scene_can_occlude(const Scene& scene);

/// The code paths a render runs: those the effects need, plus those
/// settings.force turns on.
CodePaths plan_code_paths(const Scene& scene, const Effects& effects,
                          const RenderSettings& settings);

/// "shadow rays (nothing can cast a shadow), lens sampling (pinhole)", or "none".
std::string skipped_code_paths(const CodePaths& paths);

}  // namespace pt
