// Function checks: a student function against the reference on thousands
// of random inputs plus the hard ones, with stated tolerances. Each check
// draws its inputs from a generator seeded by env.seed, so a report can be
// reproduced with `grade --seed N`.
//
// Tolerances (the manifest's "rel_tol", default 1e-6): a figure a passes
// against the reference r when |a - r| <= rel_tol * max(1, |r|), vectors
// componentwise; unit vectors (directions, normals) must also have length
// 1 within rel_tol. Hit-or-miss verdicts may disagree only inside the edge
// band: where the exact (long double) margin of the verdict (a barycentric
// coordinate, b1 + b2 - 1, t - t_min, t_max - t, or for spheres the
// distance of the ray from the centre minus the radius) is within
// 1e-9 times the problem's condition number of zero, so that a one-ulp
// difference in a correct implementation may flip it. Such cases are
// counted and reported, never failed.
#pragma once

#include "grade/grade_environment.h"
#include "grade/task.h"

namespace pt {

/// Part 1, generate_ray: random pinhole cameras (position, orientation,
/// fov, aspect, clip range) at the corners, the centre, the edge midpoints
/// and random points of the image; with params.thin_lens, also thin-lens
/// cameras, checked by properties (origin on the lens disk, ray through the
/// point in focus) since any area-preserving disk mapping is correct.
TaskResult check_generate_ray(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 1, intersect_triangle: random triangles and rays, hits near edges
/// and vertices, grazing and parallel rays, t_min and t_max boundaries,
/// hits behind the origin, degenerate triangles, vertex normals, and
/// directions that are not unit length (shadow rays).
TaskResult check_intersect_triangle(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 1, intersect_sphere: rays from outside and inside, tangent rays,
/// spheres behind the origin, a unit sphere 10^6 units away, tiny and huge
/// spheres, every placement of [t_min, t_max] around the two roots.
TaskResult check_intersect_sphere(const TaskSpec& spec, const GradeEnvironment& env);

/// Part 2, bvh_intersect: the student's accelerator (bvh stage, with the
/// reference intersection routines) against the linear scan on random
/// rays through a scene: same closest hit (t, primitive) and same
/// occlusion verdict.
TaskResult check_accelerator(const TaskSpec& spec, const GradeEnvironment& env);

}  // namespace pt
