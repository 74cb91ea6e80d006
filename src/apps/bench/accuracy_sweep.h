// What accuracy costs in time, for one technique: renders at 1, 2, 4, ...
// samples per pixel until its time budget is spent, or for one given time
// (--equal-time), each measured against the converged reference.
//
// Efficiency is 1 / (relMSE x seconds) (Veach's thesis, section 2.4, with
// relMSE for the variance): for an unbiased technique relMSE falls as 1/spp
// while the time grows as spp, so the efficiency is the same at every spp,
// and the ratio of two techniques' efficiencies is how many times longer
// the worse one must run to reach the same error. Two ratios are reported:
//   at matched time  relMSE of the baseline / relMSE of the technique, both
//                    interpolated (straight lines in log-log) on the sweep's
//                    rows at the longest time that both reached;
//   at equal time    efficiency of the technique's --equal-time render
//                    divided by the baseline's (both took about the same
//                    time, so this is nearly the inverse ratio of relMSEs).
// Rows at 1 spp are left out of the ratios: one camera ray per pixel goes
// through the pixel centre (stages/camera.h), a different estimator whose
// aliasing the reference does not share.
#pragma once

#include <memory>
#include <ostream>
#include <vector>

#include "apps/bench/accuracy_techniques.h"
#include "core/counters.h"
#include "image/image.h"
#include "render/integrators.h"
#include "stages/accelerator.h"

namespace pt {
struct Scene;
}

namespace pt::bench {

/// What a render's seconds are (`--clock`).
enum class BenchClock {
    wall,  ///< wall-clock time: what a user waits, noisy on a shared machine
    cpu,   ///< CPU seconds of the process / threads: wall time on idle cores, robust to load
};

/// One render of a technique.
struct TechniqueRender {
    Image image;
    double seconds = 0;    ///< render time by the chosen clock (without building the BVH)
    RayCounters counters;  ///< rays, tests
    double mean_spp = 0;   ///< camera rays per pixel (below the -s value for adaptive sampling)
    bool complete = true;  ///< false: cut off by the time limit
    std::vector<uint32_t> sample_counts;  ///< camera rays per pixel, row-major
};

/// A technique ready to render: its settings, accelerator and integrator,
/// built once.
class TechniqueRenderer {
  public:
    TechniqueRenderer(const Scene& scene, const RenderSettings& baseline, Technique technique,
                      int threads, BenchClock clock = BenchClock::wall);
    /// Renders at `spp` samples per pixel (the maximum for adaptive sampling)
    /// with `seed`; stops after `time_limit` seconds when > 0.
    TechniqueRender render(int spp, uint64_t seed, double time_limit) const;

    const Technique& technique() const { return technique_; }
    IntegratorKind integrator() const { return integrator_->kind(); }
    bool adaptive() const { return config_.settings.adaptive; }
    double build_seconds() const { return build_seconds_; }

  private:
    const Scene& scene_;
    Technique technique_;
    TechniqueConfig config_;
    std::unique_ptr<Accelerator> accelerator_;
    std::unique_ptr<Integrator> integrator_;
    int threads_;
    BenchClock clock_;
    double build_seconds_ = 0;
};

/// One line of the table.
struct AccuracyRow {
    int spp = 0;            ///< the -s value
    double mean_spp = 0;    ///< camera rays per pixel
    double seconds = 0;     ///< render time
    uint64_t rays = 0;      ///< closest-hit and shadow rays
    double rmse = 0;        ///< against the reference
    double relmse = 0;      ///< against the reference
    double efficiency = 0;  ///< 1 / (relMSE x seconds)
};

AccuracyRow measure(const TechniqueRender& render, int spp, const Image& reference);

struct SweepOptions {
    double budget = 10;  ///< seconds of renders per technique
    int max_spp = 4096;  ///< the sweep stops here at the latest
    uint64_t seed = 1;   ///< of every render
};

struct SweepResult {
    Technique technique;
    std::vector<AccuracyRow> rows;  ///< by increasing spp
    bool finished = true;           ///< false: even 1 spp did not finish within the budget
    double cut_at = 0;              ///< when !finished: the seconds after which it was stopped
};

/// Renders at 1, 2, 4, ... spp while the technique's total render time
/// stays within the budget, predicting each render to take twice the one
/// before. The first render is cut off at the budget. One progress line per
/// render on `log`.
SweepResult sweep(const TechniqueRenderer& renderer, const Image& reference,
                  const SweepOptions& options, std::ostream& log);

struct EqualTimeResult {
    Technique technique;
    AccuracyRow row;
    Image image;
    std::vector<uint32_t> sample_counts;  ///< camera rays per pixel, row-major
    bool adaptive = false;                ///< the technique samples adaptively (-a)
    bool finished = true;                 ///< false: 2 spp did not finish in twice the time
};

/// One render that takes about `seconds`: the spp is predicted from the
/// sweep's rows when there are some, else from renders at 2, 4, ... spp,
/// and corrected up to twice while the time is off by more than 25%.
EqualTimeResult render_equal_time(const TechniqueRenderer& renderer, const Image& reference,
                                  double seconds, const SweepResult* sweep, uint64_t seed,
                                  std::ostream& log);

/// Efficiency of a technique against its baseline (file comment); NaN
/// where it cannot be computed (no sweep or no equal-time renders, a
/// technique without rows at 2 spp or more, times that do not overlap, a
/// render that did not finish).
struct Comparison {
    std::string technique, baseline;
    double matched_seconds = 0;   ///< where the matched-time ratio was taken
    double matched_ratio = 0;     ///< efficiency ratio at matched time (sweep)
    double equal_time_ratio = 0;  ///< efficiency ratio of the equal-time renders
};
/// One comparison per technique whose baseline was run too, in the order of `sweeps`
/// (or of `equal_time` when there was no sweep).
std::vector<Comparison> compare_with_baselines(const std::vector<SweepResult>& sweeps,
                                               const std::vector<EqualTimeResult>& equal_time);

/// The least-squares slope of log relMSE against log spp over the rows of
/// 2 spp or more (-1 for independent samples; steeper for stratified and
/// quasi-Monte Carlo samplers, stages/sampler.h); NaN with fewer than 3 rows.
double fitted_slope(const std::vector<AccuracyRow>& rows);

/// relMSE at `seconds`, on the straight lines in log-log between the rows
/// of 2 spp or more; NaN outside their times.
double relmse_at(const std::vector<AccuracyRow>& rows, double seconds);

}  // namespace pt::bench
