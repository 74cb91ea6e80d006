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
};

}  // namespace pt
