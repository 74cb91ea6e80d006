// Comparing a student's Hit with the reference's, for the intersection
// checks: hit-or-miss agreement, then t, barycentrics and the normal
// within tolerances (function_checks.h states them).
#pragma once

#include <optional>
#include <string>

#include "stages/intersect.h"

namespace pt {

struct HitTolerance {
    double rel_tol = 1e-6;     ///< relative tolerance on t; absolute on barycentrics and normals
    double t_abs = 0;          ///< extra absolute tolerance on t (ill-conditioned cases)
    double normal_abs = 0;     ///< extra absolute tolerance on normal components
    bool barycentrics = true;  ///< compare b1 and b2 (triangles)
};

/// Whether a traversal's closest hit at `got` is the closest hit at `want`:
/// t within `rel_tol` relative (absolute below 1). Both come from the same
/// intersection routines, so only the order of the search can differ; an
/// equal t on two primitives (a shared edge) is a tie, not a mistake. The
/// one comparison of part2.3 (bvh_intersect) and part2.5 (bvh_performance),
/// so that the two tasks cannot disagree on what "the closest hit" is.
bool same_closest_t(double got, double want, double rel_tol);

/// "" when the student's answer agrees with the reference's, else what
/// differs ("hit at t = 2 where the reference misses", "normal (..)
/// instead of (..)", ...).
std::string compare_hits(const std::optional<Hit>& student, const std::optional<Hit>& reference,
                         const HitTolerance& tol);

}  // namespace pt
