// RenderContext: everything a staged function may use while rendering, in
// one read-only bundle: the scene, its accelerator, the stage tables, the
// settings, the integrator and the scene's lights. Passed by const
// reference to every stage function (like CS184's PathTracer members),
// shared by all threads.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/color.h"
#include "core/rng.h"
#include "stages/settings.h"
#include "scene/bsdf.h"
#include "scene/interaction.h"
#include "scene/light_set.h"
#include "scene/scene.h"
#include "stages/stages.h"

namespace pt {

class Integrator;

struct RenderContext {
private:
    std::shared_ptr<const LightSet> owned_lights_;  ///< first, so `lights` can refer to it
    /// The stage tables, with the camera's own projection in place of
    /// generate_ray when the scene's camera is not perspective (scene/camera.h).
    Stages owned_stages_;
    std::shared_ptr<const Sampler> owned_sampler_;   ///< null for independent sampling

public:
    /// Builds the scene's lights (LightSet) from `scene`, which must not
    /// change while the context is in use.
    RenderContext(const Scene& scene, const Accelerator& accelerator, const Stages& stages,
                  const RenderSettings& settings, const Integrator& integrator);

    const Scene& scene;
    const Accelerator& accelerator;
    const Stages& stages;
    const RenderSettings& settings;
    const Integrator& integrator;
    const LightSet& lights;  ///< every light of the scene (scene/light_set.h)
    /// The code paths this render runs (stages/effects.h): the effects
    /// analysis of scene and settings, plus settings.force.
    const CodePaths code_paths;
    /// settings.sampler with the sampler stage's functions, or null for
    /// independent sampling (core/sampler.h).
    const Sampler* const sampler;

    /// The generator of camera sample `index` of pixel (x, y): its own PCG32
    /// stream (independent sampling), or the sampler's values (core/rng.h).
    Rng sample_generator(int x, int y, int index) const;

    /// The closest surface hit by `ray`, or nothing (counted as a closest-hit ray).
    std::optional<SurfaceInteraction> intersect(const Ray& ray) const;
    /// Whether anything blocks the shadow ray `ray` within its interval
    /// (counted as a shadow ray). False without tracing when the effects
    /// analysis proved that no light sample can be blocked (code_paths.shadow_rays).
    bool occluded(const Ray& ray) const;
    /// The integrator's radiance estimate along a camera ray; with --clamp X
    /// scaled so that its largest component is at most X (counted). Black
    /// for a ray that sees nothing (scene/camera.h: outside a fisheye's circle).
    Color radiance(const Ray& ray, Rng& rng) const;
    /// The BSDF at `isect`: its material in the shading frame of isect.n,
    /// with the direct stage's diffuse routines (student or reference). For
    /// two-sided materials (all but glass) the frame's +z is turned to the
    /// side of the surface that isect.wo leaves from, so wo.z >= 0 on a flat
    /// surface and a wall is lit the same from both sides.
    BSDF bsdf_at(const SurfaceInteraction& isect) const;
};

/// Closest hits of camera rays traced ahead of the integrator, in packets
/// (`--packets on`, render/camera_packets.h). While a thread's list is set,
/// RenderContext::intersect answers a ray from it when the ray is the next
/// one listed (the same origin, direction and interval; the hit is the one
/// intersect would return, bit for bit), so the image is the same with or
/// without packets; any other ray is traced as usual.
struct TracedCameraRays {
    std::vector<Ray> rays;                 ///< rays[i]: camera ray of sample i of the pixel
    std::vector<Rng> generators;           ///< sample i's generator after drawing rays[i]
    std::vector<std::optional<Hit>> hits;  ///< hits[i]: accelerator.intersect(rays[i])
    size_t next = 0;                       ///< the first ray not yet asked for
    /// The hit of `ray` when it is the next listed ray or the one after (a
    /// camera ray whose integrator asked nothing is passed over); else null.
    const std::optional<Hit>* take(const Ray& ray);
    void clear() {
        rays.clear();
        generators.clear();
        hits.clear();
        next = 0;
    }
};

/// Sets this thread's list of traced camera rays; null: none.
void set_traced_camera_rays(TracedCameraRays* list);
/// This thread's list (reference::raytrace_pixel takes its samples' rays
/// and generators from it rather than drawing them again); null: none.
const TracedCameraRays* traced_camera_rays();

/// The interaction record for `hit`, found by `ray`: the hit point (from
/// barycentrics for triangles, re-projected for spheres) with its error
/// bound, the geometric normal, and the material (interaction.h).
SurfaceInteraction make_interaction(const Scene& scene, const Ray& ray, const Hit& hit);

}  // namespace pt
