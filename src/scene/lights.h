// The light types behind the Light interface (light_set.h). Each factory
// returns a self-contained light: it copies the geometry it needs, so it
// never refers back into the Scene.
#pragma once

#include <memory>
#include <vector>

#include "core/bbox.h"
#include "scene/geometry.h"
#include "scene/light.h"
#include "scene/light_set.h"

namespace pt {

/// An area light made of emissive triangles (one-sided: emitting on the side
/// of each triangle's geometric normal (p1 - p0) x (p2 - p0)), all emitting
/// radiance `Le`. Sampled uniformly by area over all of them.
std::unique_ptr<Light> make_triangle_light(const std::vector<Triangle>& triangles, const Color& Le);
/// A spherical area light emitting `Le` outwards; sampled by the cone of
/// directions it subtends (its visible cap).
std::unique_ptr<Light> make_sphere_light(const Sphere& sphere, const Color& Le);
/// An isotropic point light (intensity in W/sr).
std::unique_ptr<Light> make_point_light(const PointLight& light);
/// A directional light; `scene_bounds` places its shadow-ray targets outside the scene.
std::unique_ptr<Light> make_directional_light(const DirectionalLight& light,
                                              const BBox& scene_bounds);
/// The environment light: constant radiance (cosine-weighted sampling about
/// the shading normal), or a lat-long map read from light.file (InputError
/// naming the file if it cannot be read), importance-sampled by luminance.
std::unique_ptr<Light> make_environment_light(const EnvironmentLight& light,
                                              const BBox& scene_bounds);

}  // namespace pt
