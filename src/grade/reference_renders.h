// The reference side of an image check: the converged reference (many
// samples per pixel, rendered once and cached on disk) with the per-sample
// variance of every pixel, and K reference renders at the student's sample
// count (cheap, rendered per process and kept in memory).
//
// The converged image is rendered in B = min(64, N) batches of N / B spp
// with different seeds: their mean is the converged image, and the spread
// of the batch means gives the per-sample variance s2 = B_spp * var(batch
// means), with B - 1 degrees of freedom per pixel, for the z-test.
//
// The disk cache validates itself: beside each converged image it keeps a
// small "witness" render (2 spp, fixed seed) made by the same reference
// code. Before a cached image is used, the witness is rendered again; if
// it differs in any bit (renders are deterministic), the reference code or
// the scene changed, and the converged image is rendered anew. Cache files
// are named <scene>-<fingerprint>-c<converged spp>.pfm (and -variance.pfm,
// -witness.pfm); the fingerprint
// covers the scene, its meshes and materials, the settings and
// kReferenceCacheVersion.
#pragma once

#include <string>
#include <vector>

#include "grade/grade_environment.h"
#include "grade/image_case.h"
#include "image/image.h"

namespace pt {

/// Bump to invalidate every cached reference at once.
constexpr const char* kReferenceCacheVersion = "pt-grade-reference-1";

struct ReferenceRenders {
    Image converged;        ///< converged_spp samples per pixel
    int converged_spp = 0;  ///< the samples per pixel it really has (a multiple of the batch count)
    Image sample_variance;  ///< per-sample variance of each pixel and channel
    std::vector<Image> runs;  ///< `runs` renders at the case's spp, seeds kReferenceRunSeed + i
    bool from_cache = false;  ///< the converged image came from the disk cache
};

/// Seeds of the reference renders: far from the small seeds graders pass to
/// `grade --seed`, so that a student's render never shares a stream with them.
constexpr uint64_t kConvergedSeed = 0x5EED00000000ull;
constexpr uint64_t kReferenceRunSeed = 0x5EED10000000ull;

ReferenceRenders reference_renders(const Scene& scene, const ImageCase& c, int runs,
                                   const GradeEnvironment& env);

/// Forgets the converged images this process keeps in memory, so that the
/// next reference_renders reads the disk cache again (the cache's tests).
void forget_converged_in_memory();

}  // namespace pt
