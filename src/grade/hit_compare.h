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

/// "" when the student's answer agrees with the reference's, else what
/// differs ("hit at t = 2 where the reference misses", "normal (..)
/// instead of (..)", ...).
std::string compare_hits(const std::optional<Hit>& student, const std::optional<Hit>& reference,
                         const HitTolerance& tol);

}  // namespace pt
