// Accelerator: answers the two ray queries every integrator needs, closest
// hit and any hit, over all primitives of a scene. The linear scan here
// (`--accel none`) tests every primitive; the BVH (stage `bvh`, Part 2)
// answers the same queries in logarithmic time.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/ray.h"
#include "stages/intersect.h"

namespace pt {

struct Scene;

/// Most rays Accelerator::intersect_packet takes at once (one bit each in a mask).
constexpr int kPacketSize = 8;

/// Figures an accelerator reports for tables and --stats.
struct AcceleratorInfo {
    std::string name;        ///< "linear", "bvh-sah", ...
    uint64_t nodes = 0;      ///< BVH nodes; 0 for the linear scan
    int depth = 0;           ///< deepest leaf; 0 for the linear scan
    uint64_t bytes = 0;      ///< all memory the accelerator holds (with per-primitive triangle copies)
    uint64_t tree_bytes = 0;  ///< nodes (cells) and primitive references only
};

class Accelerator {
public:
    virtual ~Accelerator() = default;
    /// The closest hit of `ray` within [t_min, t_max] over all primitives,
    /// with Hit::primitive set; nothing on a miss.
    virtual std::optional<Hit> intersect(const Ray& ray) const = 0;
    /// Whether any primitive is hit within [t_min, t_max] (shadow rays); may
    /// stop at the first hit found.
    virtual bool occluded(const Ray& ray) const = 0;
    /// Closest hits of `count` (<= kPacketSize) rays traced together, e.g.
    /// camera rays of neighbouring pixels: hits[i] is exactly intersect(rays[i]).
    /// Here one ray at a time; the wide BVH shares one traversal among them
    /// (a ray packet: Wald et al., "Interactive Rendering with Coherent Ray
    /// Tracing", Eurographics 2001), which pays when the rays are coherent.
    virtual void intersect_packet(const Ray* rays, int count, std::optional<Hit>* hits) const {
        for (int i = 0; i < count; ++i)
            hits[i] = intersect(rays[i]);
    }
    /// Whether intersect_packet shares one traversal among its rays (else
    /// it traces them one by one, and packets only cost).
    virtual bool shares_packet_traversal() const { return false; }
    virtual AcceleratorInfo info() const = 0;
};

/// One primitive (triangle or sphere) against a ray, through the intersect
/// stage's functions; sets Hit::primitive.
std::optional<Hit> intersect_primitive(const Scene& scene, const IntersectStage& stage, uint32_t prim,
                                       const Ray& ray);

/// Tests every primitive: correct, simple, and O(n) per ray.
std::unique_ptr<Accelerator> make_linear_scan(const Scene& scene, const IntersectStage& stage);

}  // namespace pt
