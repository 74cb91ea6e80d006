// Mixing stage tables: the reference everywhere except the student
// functions a task grades, so that a bug is charged to one task only (a
// wrong generate_ray fails the generate_ray task, not also every image
// task that happens to shoot camera rays).
#pragma once

#include <string>
#include <vector>

#include "stages/stages.h"

namespace pt {

/// `reference` with the named slots taken from `student`. A slot is a
/// whole stage ("camera", "intersect", "bvh", "direct", "adaptive") or one
/// function ("camera.generate_ray", "direct.zero_bounce_radiance",
/// "adaptive.has_converged", ...: known_slots()). The result's `student`
/// set lists every stage with a student slot. Throws InputError naming
/// `where` for an unknown slot.
///
/// A direct-lighting estimator slot ("direct.estimate_direct_lighting_*")
/// without "direct.one_bounce_radiance" also replaces one_bounce_radiance
/// by one that dispatches through the table (the reference's calls the
/// reference estimators directly), so that the student's estimator is what
/// the renderer runs.
Stages mix_stages(const Stages& reference, const Stages& student,
                  const std::vector<std::string>& slots, const std::string& where);

/// The reference's one_bounce_radiance, calling the estimators of the
/// context's stage table (the reference's own calls its estimators directly).
Color one_bounce_through_table(const RenderContext& context, const Ray& ray,
                               const SurfaceInteraction& isect, Rng& rng);

/// The slot names mix_stages accepts, for error messages and docs.
std::vector<std::string> known_slots();

}  // namespace pt
