// The accelerator of a CSG shape (scene/csg.h): for a ray, the span list of
// every leaf (a sphere's two roots; a closed mesh's crossings, found by a
// small BVH of its own that reports every triangle the ray crosses, not the
// closest), combined up the tree, and the first span end within [t_min,
// t_max] is the hit. CSG shapes sit under the instance level
// (stages/instance_accelerator.h), which maps rays into their space.
//
// Triangles are crossed by the watertight test (Woop, Benthin and Wald,
// JCGT 2013), so a ray through a shared edge crosses the mesh at least
// once; csg_spans_of_crossings merges the duplicates. The CSG code uses the
// reference routines only: it is not a student stage.
//
// Cost: every leaf whose box the ray meets is intersected in full, so a
// ray costs the sum over the leaves, not the closest one (Roth 1982).
#pragma once

#include <memory>

#include "scene/csg.h"
#include "stages/accelerator.h"

namespace pt {

/// `shape` holds the tree's primitives; both must outlive the accelerator.
std::unique_ptr<Accelerator> make_csg_accelerator(const Scene& shape, const CsgTree& tree);

}  // namespace pt
