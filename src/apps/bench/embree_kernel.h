// EmbreeKernel: Intel Embree 3 (Debian's libembree-dev) traversing the same
// triangles and the same rays as the reference BVH, so that `bench bvh`
// can show how far the reference is from the best kernel library.
//
// Optional: compiled in only with -DPT_WITH_EMBREE=ON; otherwise
// available() is false and the bench leaves the Embree columns out.
// Embree works in single precision (rays and vertices are rounded to
// float), builds with one thread (device config "threads=1") and its
// default quality, and answers with rtcIntersect1 / rtcOccluded1, one ray
// at a time, as the renderer asks.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "apps/bench/bench_util.h"

namespace pt {
struct Scene;
}

namespace pt::bench {

class EmbreeKernel {
  public:
    /// Whether the bench was built with Embree.
    static bool available();
    /// "Embree 3.13.5", or "" when not available.
    static std::string version();

    /// Builds Embree's BVH over the scene's triangles (spheres are left
    /// out) and times the build. Throws std::runtime_error when unavailable.
    explicit EmbreeKernel(const Scene& scene);
    ~EmbreeKernel();
    EmbreeKernel(const EmbreeKernel&) = delete;
    EmbreeKernel& operator=(const EmbreeKernel&) = delete;

    /// Seconds from handing over the vertices to the committed scene.
    double build_seconds() const;
    /// Bytes that Embree holds after the build beyond its vertex and index
    /// buffers (its BVH and its own triangle copies), from the device's
    /// memory monitor: the figure to set beside the reference BVH's.
    uint64_t structure_bytes() const;
    /// Traces every ray once (rtcIntersect1, or rtcOccluded1 when any_hit);
    /// only seconds and hits are filled in.
    KernelPass trace(const std::vector<Ray>& rays, bool any_hit) const;
    /// The triangle each ray hits first, or UINT32_MAX on a miss.
    std::vector<uint32_t> closest_triangles(const std::vector<Ray>& rays) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace pt::bench
