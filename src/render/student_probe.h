// Student probes: before the first pixel, call every student function of a
// stage that this render will use, once, in task order, so that the first
// one still missing is the one reported ("Part 3, task 1: diffuse_f is not
// implemented yet"), not whichever the renderer happens to reach first.
// The values are discarded; each probe draws from its own generator.
#pragma once

#include <atomic>
#include <mutex>

#include "core/ray.h"

namespace pt {

struct RenderContext;
struct SurfaceInteraction;

/// The direct stage's functions that -m, -o and --direct make a render use.
void probe_student_direct_stage(const RenderContext& context, const Ray& ray,
                                const SurfaceInteraction& isect);
/// The global stage's: at_least_one_bounce_radiance (task 1, when -m >= 1),
/// then est_radiance_global_illumination (task 2).
void probe_student_global_stage(const RenderContext& context, const Ray& ray,
                                const SurfaceInteraction& isect);

/// Runs the probes of the student stages among `direct` and `global` once
/// per integrator (thread-safe; a throwing probe stops the render).
class StudentProbe {
  public:
    void run_once(const RenderContext& context, const Ray& ray, const SurfaceInteraction& isect,
                  bool direct, bool global) const;
    /// Whether the probes have run (then run_once does nothing).
    bool done() const { return done_.load(std::memory_order_acquire); }

  private:
    mutable std::once_flag once_;
    mutable std::atomic<bool> done_{false};
};

}  // namespace pt
