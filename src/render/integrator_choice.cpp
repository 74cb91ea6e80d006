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
    // The lighting integrators arrive with Parts 3 and 4.
    if (reason) *reason = "lighting stages are not built yet";
    return IntegratorKind::normals;
}

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind) {
    switch (kind) {
        case IntegratorKind::normals: return make_normals_integrator();
        case IntegratorKind::depth: return make_depth_integrator();
        default: break;
    }
    throw std::logic_error(std::string("integrator '") + to_string(kind) + "' is not available");
}

}  // namespace pt
