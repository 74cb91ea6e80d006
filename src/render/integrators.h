// The integrators (DESIGN.md "Effects"): normals, depth, Whitted, direct
// and path tracing, each an Integrator (stages/integrator.h), and the rule
// by which `--integrator auto` picks one for a scene.
#pragma once

#include <memory>
#include <string>

#include "stages/integrator.h"
#include "stages/stage_set.h"

namespace pt {

/// n * 0.5 + 0.5 of the first hit's shading normal; black on a miss (CS184 Part 1).
std::unique_ptr<Integrator> make_normals_integrator();
/// Grey level falling linearly from 1 at the nearest point of the scene's
/// bounding sphere to 0 at its farthest; black on a miss.
std::unique_ptr<Integrator> make_depth_integrator();
/// Emission plus direct light at the first hit, through the direct stage
/// (stages/direct.h; render/direct_integrator.cpp): -m 0 emission only, -m 1 direct light.
std::unique_ptr<Integrator> make_direct_integrator();
/// Whitted ray tracing: direct light at non-specular surfaces, mirror and
/// glass followed recursively and deterministically (render/whitted_integrator.cpp).
std::unique_ptr<Integrator> make_whitted_integrator();
/// Path tracing through the global stage (stages/global.h): -m, -o, Russian roulette.
std::unique_ptr<Integrator> make_path_integrator();
/// Volume path tracing: the path tracer with participating media, free
/// flights, phase functions and transmittance (render/volpath_integrator.cpp, Part 9).
std::unique_ptr<Integrator> make_volpath_integrator();
/// Photon mapping with a caustic and a global map and final gathering
/// (render/pm_integrator.cpp); its maps are traced in prepare().
std::unique_ptr<Integrator> make_pm_integrator();
/// Stochastic progressive photon mapping: render_image hands the whole
/// render to render_sppm (render/sppm.h); Li alone is not defined.
std::unique_ptr<Integrator> make_sppm_integrator();
/// Bidirectional path tracing (render/bdpt_integrator.cpp, stages/bdpt.h):
/// every strategy (s, t) weighted by MIS; light tracing splats (Integrator::splat_layers).
std::unique_ptr<Integrator> make_bdpt_integrator();

}  // namespace pt

namespace pt {

struct Scene;
struct Effects;

/// The integrator `--integrator auto` picks for a scene (DESIGN.md "Effects";
/// rules in render/integrator_choice.cpp), with the reason in one phrase for
/// the start-up line. `student`: with `global` among them, the path tracer.
IntegratorKind choose_integrator(const Scene& scene, const Effects& effects, const RenderSettings& settings,
                                 std::string* reason, StageSet student = StageSet::none());
/// A caveat worth printing about `kind` on this scene ("" if none): Whitted
/// forced on area lights, or with -m >= 2.
std::string integrator_note(IntegratorKind kind, const Scene& scene, const RenderSettings& settings);
/// An integrator of the given kind (not `automatic`).
std::unique_ptr<Integrator> make_integrator(IntegratorKind kind);

}  // namespace pt
