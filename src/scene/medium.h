// Medium: a participating medium (fog, milk, smoke) as the scene file
// describes it: what it absorbs and scatters per unit length, and how it
// scatters (Henyey-Greenstein's g). The transport through it (transmittance,
// free-flight sampling, the phase function) is stage `media`
// (stages/media.h, Part 9); this is only the data.
//
// Where a medium is: inside the closed shapes whose material names it as
// its "interior", or everywhere outside them (the scene-level "medium",
// fog). A heterogeneous medium multiplies its coefficients by a density
// read from a grid file (scene/density_grid.h): sigma(x) = density(x) sigma.
// Units: sigma_a, sigma_s are per scene unit (a mean free path of 1 /
// sigma_t scene units).
#pragma once

#include <memory>
#include <string>

#include "core/color.h"
#include "scene/density_grid.h"

namespace pt {

struct Medium {
    std::string name;   ///< "medium" (the scene's), or the material whose interior it is
    Color sigma_a;      ///< absorption coefficient per scene unit, >= 0 per channel
    Color sigma_s;      ///< scattering coefficient per scene unit, >= 0 per channel
    double g = 0;       ///< Henyey-Greenstein asymmetry in (-1, 1): > 0 forward, < 0 backward
    /// Density multiplying sigma_a and sigma_s at each point; null: homogeneous (density 1).
    std::shared_ptr<const DensityGrid> density;

    /// Extinction sigma_t = sigma_a + sigma_s (at density 1).
    Color sigma_t() const { return sigma_a + sigma_s; }
    bool homogeneous() const { return !density; }
    bool scatters() const { return !sigma_s.is_black(); }
    bool absorbs() const { return !sigma_a.is_black(); }
};

}  // namespace pt
