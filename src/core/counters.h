// RayCounters: hardware-independent work counts (rays, primitive tests, BVH
// nodes visited, non-finite samples) for the summary line, --stats and bench.
//
// Each thread counts into its own thread_local instance (no atomics in the
// hot path); the renderer adds the workers' counts together when they finish.
#pragma once

#include <cstdint>

namespace pt {

struct RayCounters {
    uint64_t camera_rays = 0;        ///< primary rays generated
    uint64_t closest_hit_rays = 0;   ///< rays traced for their closest hit (camera + bounce)
    uint64_t shadow_rays = 0;        ///< any-hit visibility rays
    uint64_t primitive_tests = 0;    ///< ray-triangle and ray-sphere tests
    uint64_t nodes_visited = 0;      ///< BVH nodes whose box was tested
    uint64_t nonfinite_samples = 0;  ///< NaN/Inf radiance samples caught before the film
    uint64_t clamped_samples = 0;    ///< samples scaled down by --clamp (biased; 0 without it)
    uint64_t packet_rays = 0;        ///< closest-hit rays answered from a packet (--packets on)

    uint64_t rays() const { return closest_hit_rays + shadow_rays; }
    RayCounters& operator+=(const RayCounters& o) {
        camera_rays += o.camera_rays;
        closest_hit_rays += o.closest_hit_rays;
        shadow_rays += o.shadow_rays;
        primitive_tests += o.primitive_tests;
        nodes_visited += o.nodes_visited;
        nonfinite_samples += o.nonfinite_samples;
        clamped_samples += o.clamped_samples;
        packet_rays += o.packet_rays;
        return *this;
    }
    /// The work done between two readings of the same counters.
    RayCounters operator-(const RayCounters& o) const {
        RayCounters d = *this;
        d.camera_rays -= o.camera_rays;
        d.closest_hit_rays -= o.closest_hit_rays;
        d.shadow_rays -= o.shadow_rays;
        d.primitive_tests -= o.primitive_tests;
        d.nodes_visited -= o.nodes_visited;
        d.nonfinite_samples -= o.nonfinite_samples;
        d.clamped_samples -= o.clamped_samples;
        d.packet_rays -= o.packet_rays;
        return d;
    }
};

/// The calling thread's counters.
inline RayCounters& thread_counters() {
    static thread_local RayCounters counters;
    return counters;
}

}  // namespace pt
