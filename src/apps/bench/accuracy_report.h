// The outputs of `bench accuracy`: the Markdown table, the JSON file, the
// log-log plot of error against time, and the side-by-side image of the
// equal-time renders with their error heat maps.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/bench/accuracy_reference.h"
#include "apps/bench/accuracy_sweep.h"
#include "image/image.h"

namespace pt::bench {

/// Everything one run measured.
struct AccuracyReport {
    std::string command;     ///< the command line that produced it
    std::string scene_name;  ///< for file names and titles
    std::string scene_path;
    int width = 0, height = 0;  ///< pixels
    int threads = 1;
    uint64_t seed = 1;
    BenchClock clock = BenchClock::wall;  ///< what the seconds are
    std::string integrator;               ///< the baseline's integrator
    std::string load_before, load_after;  ///< 1-minute load averages, "unknown" if unreadable
    const Reference* reference = nullptr;
    double budget = 0;  ///< seconds per technique; 0: no sweep
    std::vector<SweepResult> sweeps;
    std::vector<Comparison> comparisons;
    double equal_time = 0;  ///< seconds; 0: no equal-time renders
    std::vector<EqualTimeResult> equal_time_results;
};

/// The report as Markdown: settings, the table, the ratios, the equal-time table.
std::string accuracy_markdown(const AccuracyReport& report);

/// The report as JSON (NaN figures as null).
nlohmann::json accuracy_json(const AccuracyReport& report);

/// sqrt(relMSE) against seconds on log-log axes, one line per technique,
/// and the 1/sqrt(time) slope dashed through the baseline's longest render.
Image accuracy_plot(const AccuracyReport& report);

/// The reference and each equal-time render side by side, each with its
/// relMSE heat map below it (image/colormap.h, 1e-4 to 1) and its name,
/// spp, seconds and relMSE written under it.
Image equal_time_composite(const AccuracyReport& report);

/// The 1-minute load average from /proc/loadavg, or "unknown".
std::string load_average();

}  // namespace pt::bench
