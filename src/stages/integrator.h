// Integrator: the interface that turns a camera ray into a radiance
// estimate. The render context (stages/render_context.h) calls it for every
// camera sample; the integrators themselves (normals, whitted, direct,
// path) live one floor up, in src/render/ (render/integrators.h). One
// instance is shared by all threads, so Li must be const and keep its
// state in the Rng.
#pragma once

#include "core/color.h"
#include "core/ray.h"
#include "core/rng.h"
#include "stages/settings.h"

namespace pt {

struct RenderContext;

class Integrator {
public:
    virtual ~Integrator() = default;
    /// Incident radiance at the ray origin from direction -ray.d.
    virtual Color Li(const RenderContext& context, const Ray& ray, Rng& rng) const = 0;
    virtual IntegratorKind kind() const = 0;
    /// Work before the first camera ray (photon mapping traces its photons
    /// here), called once per render by render_image with its thread count.
    /// Integrators that keep what they prepare hold it in mutable members:
    /// Li stays const and thread-safe once prepare has returned.
    virtual void prepare(const RenderContext& context, int threads) const {
        (void)context;
        (void)threads;
    }
    /// Images of splats the integrator adds to pixels other than the camera
    /// ray's (render/splat_film.h): 0 for none; layer 0 is added to the
    /// image, further layers come back in RenderResult::layers.
    virtual int splat_layers(const RenderContext& context) const {
        (void)context;
        return 0;
    }
};

}  // namespace pt
