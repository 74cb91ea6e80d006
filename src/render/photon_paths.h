// Camera-side helpers shared by the photon mapping integrators (pm, sppm):
// following a ray through mirrors and glass to the first surface that a
// photon map can describe, and the radii they default to.
#pragma once

#include <optional>

#include "core/color.h"
#include "core/ray.h"
#include "core/rng.h"
#include "scene/bsdf.h"
#include "scene/interaction.h"

namespace pt {

struct RenderContext;

/// Specular bounces a camera or gather ray follows before it gives up.
constexpr int kMaxSpecularBounces = 32;

/// Where a ray followed through specular surfaces ends.
struct DiffuseVertex {
    SurfaceInteraction isect;  ///< the first non-specular hit
    Color beta;                ///< product of the specular bounces' weights f |cos| / pdf
};

/// Follows `ray` through delta BSDFs (one lobe drawn by sample_f each time)
/// to its first non-specular hit. With `emitted`, adds beta times the
/// emission of every surface hit and the environment on a miss (light that
/// reaches the ray's origin through specular bounces only). Nothing on a
/// miss, after kMaxSpecularBounces bounces, or when a lobe has no weight.
std::optional<DiffuseVertex> trace_to_diffuse(const RenderContext& context, Ray ray, Color beta, Rng& rng,
                                              Color* emitted);

/// The default search radius of photon mapping as a fraction of the
/// scene's bounding-sphere radius: `--radius` when given, else `fraction`.
double photon_radius(const RenderContext& context, double fraction);

}  // namespace pt
