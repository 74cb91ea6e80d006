// Which integrator renders a scene: the user's --integrator, or for `auto`
// the cheapest one that simulates every effect the scene calls for.
#include <stdexcept>

#include "render/integrator.h"
#include "scene/effects.h"
#include "scene/scene.h"

namespace pt {

IntegratorKind choose_integrator(const Scene& scene, const Effects&, const RenderSettings& settings,
                                 std::string* reason) {
    if (settings.integrator != IntegratorKind::automatic) {
        if (reason) *reason = "chosen with --integrator";
        return settings.integrator;
    }
    if (!scene.has_lights()) {
        if (reason) *reason = "nothing in the scene emits light, so normals are shown";
        return IntegratorKind::normals;
    }
    // Part 4 refines this: path tracing for -m >= 2, Whitted for delta lights only.
    if (reason)
        *reason = settings.max_depth >= 2
                      ? "the scene has lights; -m >= 2 needs path tracing (Part 4), so direct light only"
                      : "the scene has lights: emission and direct light";
    return IntegratorKind::direct;
}

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind) {
    switch (kind) {
        case IntegratorKind::normals: return make_normals_integrator();
        case IntegratorKind::depth: return make_depth_integrator();
        case IntegratorKind::direct: return make_direct_integrator();
        default: break;
    }
    throw std::logic_error(std::string("integrator '") + to_string(kind) + "' is not available");
}

}  // namespace pt
