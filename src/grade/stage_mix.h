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
/// whole stage ("camera", "intersect", "bvh") or one function
/// ("camera.generate_ray", "camera.raytrace_pixel",
/// "intersect.intersect_triangle", "intersect.intersect_sphere"). The
/// result's `student` set lists every stage with a student slot. Throws
/// InputError naming `where` for an unknown slot.
Stages mix_stages(const Stages& reference, const Stages& student,
                  const std::vector<std::string>& slots, const std::string& where);

/// The slot names mix_stages accepts, for error messages and docs.
std::vector<std::string> known_slots();

}  // namespace pt
