// Material: what a surface is made of, as the scene file describes it.
// The BSDFs that turn these parameters into scattering live with the
// lighting stages (Parts 3 and 4, scene/bsdf.h); this is only the data.
// The scene format and the MTL mapping of each type are documented in
// docs/global.md ("Materials").
#pragma once

#include <memory>
#include <string>

#include "core/color.h"
#include "scene/microfacet_distribution.h"
#include "scene/texture.h"

namespace pt {

enum class MaterialType {
    diffuse,  ///< Lambertian: albedo
    mirror,   ///< perfect specular reflection: reflectance
    glass,    ///< smooth dielectric: ior, reflectance, transmittance
    microfacet,  ///< rough conductor (GGX, Beckmann or Blinn-Phong; Smith): roughness, eta, k
    rough_dielectric,  ///< rough glass (Walter et al. 2007): ior, roughness, reflectance, transmittance
    null,  ///< no surface: light passes straight through (the invisible boundary of a medium)
};

struct Material {
    std::string name;                       ///< the key in the scene's "materials", or "mesh.obj:mtlname"
    MaterialType type = MaterialType::diffuse;
    Color albedo{0.8, 0.8, 0.8};            ///< diffuse reflectance in [0, 1]
    std::shared_ptr<const Texture> albedo_texture;  ///< diffuse reflectance varying with (u, v); null = `albedo`
    Color emission;                         ///< emitted radiance, W/(m^2 sr) in scene units; 0 = none
    Color reflectance{1, 1, 1};             ///< mirror and glass: tint of reflected light, [0, 1]
    Color transmittance{1, 1, 1};           ///< glass: tint of refracted light, [0, 1]
    double ior = 1.5;                       ///< glass, rough_dielectric: index of refraction inside / outside
    double roughness = 0.3;                 ///< microfacet, rough_dielectric: alpha (along x when anisotropic), in [0.001, 1]
    double roughness_y = -1;                ///< alpha along the second tangent (y); < 0: the same as `roughness`
    MicrofacetModel distribution = MicrofacetModel::ggx;  ///< microfacet, rough_dielectric: the facet statistics
    double exponent = 100;                  ///< Blinn-Phong exponent e >= 0 (distribution blinn_phong)
    Color eta{1.66, 0.88, 0.52};            ///< microfacet: real part of the conductor's IOR per channel
    Color k{9.22, 6.27, 4.84};              ///< microfacet: imaginary part (absorption) per channel
    /// Index into Scene::media of the medium filling the closed shapes made of
    /// this material ("interior"), or -1: none (scene/medium.h).
    int interior = -1;

    bool is_emissive() const { return !emission.is_black(); }
    /// The diffuse reflectance at surface coordinates uv (scene/texture.h).
    Color albedo_at(Vec2 uv) const { return albedo_texture ? albedo_texture->evaluate(uv) : albedo; }
};

const char* to_string(MaterialType type);

}  // namespace pt
