// `--accel embree`: Intel Embree 3 (Debian's libembree-dev) as the
// acceleration structure, for users who want production speed. Optional:
// compiled in only with -DPT_WITH_EMBREE=ON; otherwise asking for it is an
// input error naming the flag. Never needed by the default build or tests.
//
// Embree works in single precision, so it is not bit-exact like the other
// accelerators: it finds the nearest triangle in float (rtcIntersect1,
// rtcOccluded1) and the hit is then recomputed with the intersect stage's
// routine in double, so t, the barycentrics and the normal are the
// reference's whenever Embree picks the same triangle (it does not always
// at shared edges and near-ties; `bench accel` reports how often it does).
// Spheres are not given to Embree: they are tested one by one after it
// (scenes have a handful).
#pragma once

#include <memory>

#include "stages/accelerator.h"

namespace pt {

/// Whether this build has Embree (-DPT_WITH_EMBREE=ON).
bool embree_available();

/// Throws InputError ("--accel embree: ...") when Embree is not built in.
std::unique_ptr<Accelerator> make_embree_accelerator(const Scene& scene, const IntersectStage& stage);

}  // namespace pt
