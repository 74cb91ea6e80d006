// Which integrator renders a scene: the user's --integrator, or for `auto`
// the cheapest one that simulates every effect the scene and flags call for
// (DESIGN.md "Effects"; the rules are in docs/global.md):
//
//   normals  nothing emits light
//   volpath  the scene has a participating medium or a null surface
//   path     `global` is a student stage (so that part4 runs the student's code)
//   whitted  every light is a point or directional light, -m >= 1, and no
//            diffuse interreflection is asked for (-m 1, or nothing
//            non-specular to bounce between): exact, no Monte Carlo noise
//   direct   -m 0; or -m 1 when no mirror or glass can show an area light or
//            the sky (a reflection of a lamp is a one-bounce path)
//   sppm     light from point or directional lights reaches a non-specular
//            surface through mirrors or glass (-m >= 2): caustics (and S D S
//            paths) that no camera path can find; photon mapping carries them
//   bdpt     (the `pathtracer` executable, -m >= 2) small area lights, whose
//            light (a) forms caustics, L S+ D, or (b) reaches the camera
//            after 3 or more bounces (-m >= 3) in a scene that can shadow:
//            a camera path finds a small light through glass only by
//            chance, and light arriving through a gap (a door ajar) only
//            after it found the gap; light subpaths start at the light and
//            find both (docs/bdpt.md has the measured efficiencies). "Small":
//            the lights' area is under 0.5% of the scene's bounding box's.
//            `part7` (student bdpt) always runs bdpt.
//   path     everything else (-m >= 2 with area or sky light, or diffuse
//            interreflection; -m 1 with lamps seen in mirrors or glass)
#include <stdexcept>

#include "render/integrators.h"
#include "stages/effects.h"
#include "scene/scene.h"

namespace pt {
namespace {

/// The area of every area light over the surface area of the scene's box.
double light_area_fraction(const Scene& scene) {
    double lights = 0;
    for (uint32_t prim : scene.emitters) lights += scene.primitive_area(prim);
    const Vec3 e = scene.bounds.max - scene.bounds.min;
    const double box = 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
    return box > 0 ? lights / box : 1.0;
}

}  // namespace

IntegratorKind choose_integrator(const Scene& scene, const Effects& effects,
                                 const RenderSettings& settings, std::string* reason,
                                 StageSet student) {
    auto because = [&](IntegratorKind kind, const char* why) {
        if (reason) *reason = why;
        return kind;
    };
    if (settings.integrator == IntegratorKind::pm && student.contains(Stage::photon) &&
        !student.contains(Stage::global))
        return because(IntegratorKind::pm, "photon is a student stage: photon mapping runs it");
    if (settings.integrator != IntegratorKind::automatic)
        return because(settings.integrator, "chosen with --integrator");
    if (student.contains(Stage::bdpt) && !student.contains(Stage::global) && scene.has_lights() &&
        !scene.has_media())
        return because(IntegratorKind::bdpt, "bdpt is a student stage: bidirectional path tracing runs it");
    if (!scene.has_lights())
        return because(IntegratorKind::normals,
                       "nothing in the scene emits light, so normals are shown");
    if (scene.has_media())
        return because(IntegratorKind::volpath,
                       "participating media or null boundaries: volume path tracing");
    if (student.contains(Stage::global))
        return because(IntegratorKind::path, "global is a student stage: the path tracer runs it");
    const int m = settings.max_depth;
    const bool only_delta_lights = scene.emitters.empty() && !scene.environment;
    if (only_delta_lights && m >= 1 && !effects.diffuse_interreflection)
        return because(IntegratorKind::whitted,
                       m == 1 ? "only point and directional lights, and -m 1 asks for no diffuse "
                                "interreflection: exact, no noise but anti-aliasing"
                              : "only point and directional lights, and no surface that light "
                                "could bounce between: exact, no noise but anti-aliasing");
    if (m == 0) return because(IntegratorKind::direct, "-m 0: emission only");
    if (effects.point_light_caustics)
        return because(IntegratorKind::sppm,
                       "point or directional light reaches diffuse surfaces through mirrors or glass: "
                       "caustics that no path from the camera can find, so photon mapping (sppm) carries them");
    // BDPT where the light's side finds what camera paths find by chance
    // (see the file comment); only without student stages, so that the
    // course executables keep the integrators their grading expects.
    const bool small_lights = !scene.emitters.empty() && light_area_fraction(scene) < 0.005;
    if (student.empty() && small_lights && effects.caustics)
        return because(IntegratorKind::bdpt,
                       "small area lights focused by mirrors or glass onto diffuse surfaces (caustics): "
                       "bidirectional path tracing finds them from the light's side");
    if (student.empty() && small_lights && m >= 3 && effects.diffuse_interreflection && scene_can_occlude(scene))
        return because(IntegratorKind::bdpt,
                       "small area lights, -m >= 3 and occluders: light that reaches the camera only after "
                       "several bounces (through a gap) is found from the light's side by bidirectional path tracing");
    const bool specular = effects.mirror || effects.refraction;
    if (m == 1 && !(specular && !only_delta_lights))
        return because(IntegratorKind::direct, "-m 1: emission and direct light");
    if (m == 1)
        return because(IntegratorKind::path,
                       "-m 1 with mirrors or glass: lights seen in them are one-bounce paths");
    return because(IntegratorKind::path, "-m >= 2: light bounces between surfaces");
}

std::string integrator_note(IntegratorKind kind, const Scene& scene,
                            const RenderSettings& settings) {
    if (scene.has_media() && kind != IntegratorKind::volpath && kind != IntegratorKind::normals &&
        kind != IntegratorKind::depth)
        return std::string(to_string(kind)) + " ignores participating media (null surfaces count as bounces): "
               "use --integrator volpath";
    if ((kind == IntegratorKind::pm || kind == IntegratorKind::sppm) && settings.max_depth != 1)
        return std::string(to_string(kind)) + " follows photon paths until Russian roulette ends them: -m " +
               std::to_string(settings.max_depth) + " is not used";
    if (kind != IntegratorKind::whitted) return "";
    if (!scene.emitters.empty() || scene.environment)
        return "Whitted lights surfaces with area and sky lights by light sampling (-l), which "
               "is noisy; it is exact for point and directional lights only";
    if (settings.max_depth >= 2)
        return "Whitted has no diffuse interreflection: -m " + std::to_string(settings.max_depth) +
               " shows what -m 1 shows (use --integrator path for more bounces)";
    return "";
}

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind) {
    switch (kind) {
        case IntegratorKind::normals:
            return make_normals_integrator();
        case IntegratorKind::depth:
            return make_depth_integrator();
        case IntegratorKind::direct:
            return make_direct_integrator();
        case IntegratorKind::whitted:
            return make_whitted_integrator();
        case IntegratorKind::path:
            return make_path_integrator();
        case IntegratorKind::volpath:
            return make_volpath_integrator();
        case IntegratorKind::bdpt:
            return make_bdpt_integrator();
        case IntegratorKind::pm:
            return make_pm_integrator();
        case IntegratorKind::sppm:
            return make_sppm_integrator();
        default:
            break;
    }
    throw std::logic_error(std::string("integrator '") + to_string(kind) + "' is not available");
}

}  // namespace pt
