// The techniques that `bench accuracy` compares: each is a name and a
// function that changes the render settings, the accelerator or a stage
// function, starting from the baseline (light sampling, uniform samples,
// the BVH, the scene's integrator and -m, -l of the command line).
//
// Adding a technique is one entry in the table in accuracy_techniques.cpp.
// Its `baseline` names the technique its efficiency is compared with in
// the ratios (accuracy_sweep.h).
#pragma once

#include <string>
#include <vector>

#include "stages/settings.h"
#include "stages/stages.h"

namespace pt::bench {

/// What a technique may change before its renders. The sweep then sets
/// settings.spp and settings.seed.
struct TechniqueConfig {
    RenderSettings settings;                        ///< starts as the baseline's
    AcceleratorSettings accelerator;                ///< starts as the reference BVH
    Stages stages = make_stages(StageSet::none());  ///< starts all reference
};

struct Technique {
    std::string name;      ///< the name in --techniques, the table and the legend
    std::string what;      ///< one line for the table: what it changes
    std::string baseline;  ///< the technique its efficiency is compared with; "" for none
    void (*apply)(TechniqueConfig& config);
    bool path_only = false;  ///< meaningful only when the baseline is the path tracer (-m >= 2)
    /// Samplers: the theoretical log-log slope of MSE against spp for a
    /// smooth integrand and across an edge (stages/sampler.h); 0: none.
    double theory_smooth = 0, theory_edge = 0;
};

/// The techniques that the group name `samplers` stands for in --techniques.
std::vector<std::string> sampler_technique_names();

/// Every technique, in the order of the table.
const std::vector<Technique>& all_techniques();

/// The techniques named in `list` ("all", or names separated by commas), in
/// the table's order. Throws InputError naming an unknown name.
std::vector<Technique> select_techniques(const std::string& list);

/// CS184's convergence rule without the reference's rare-event guard:
/// 1.96 sigma / sqrt(n) <= tol * mu, so a pixel whose samples are all
/// equal stops at its first test (stages/adaptive.h).
bool textbook_has_converged(const PixelStatistics& stats, double max_tolerance);

}  // namespace pt::bench
