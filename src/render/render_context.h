// RenderContext: everything a staged function may use while rendering, in
// one read-only bundle: the scene, its accelerator, the stage tables, the
// settings and the integrator. Passed by const reference to every stage
// function (like CS184's PathTracer members), shared by all threads.
#pragma once

#include <optional>

#include "core/color.h"
#include "core/rng.h"
#include "render/settings.h"
#include "scene/interaction.h"
#include "scene/scene.h"
#include "stages/stages.h"

namespace pt {

class Integrator;

struct RenderContext {
    const Scene& scene;
    const Accelerator& accelerator;
    const Stages& stages;
    const RenderSettings& settings;
    const Integrator& integrator;

    /// The closest surface hit by `ray`, or nothing (counted as a closest-hit ray).
    std::optional<SurfaceInteraction> intersect(const Ray& ray) const;
    /// Whether anything blocks `ray` within its interval (counted as a shadow ray).
    bool occluded(const Ray& ray) const;
    /// The integrator's radiance estimate along a camera ray.
    Color radiance(const Ray& ray, Rng& rng) const;
};

/// The interaction record for `hit`, found by `ray`: the hit point (from
/// barycentrics for triangles, re-projected for spheres) with its error
/// bound, the geometric normal, and the material (interaction.h).
SurfaceInteraction make_interaction(const Scene& scene, const Ray& ray, const Hit& hit);

}  // namespace pt
