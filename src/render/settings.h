// RenderSettings: the rendering parameters chosen on the command line
// (DESIGN.md "Command line"), independent of where the output goes.
#pragma once

#include <cstdint>
#include <string>

namespace pt {

/// How direct light is estimated at a shading point (`--direct`, `-H`).
enum class DirectStrategy {
    light,       ///< sample the lights (importance sampling, the default)
    hemisphere,  ///< sample the hemisphere uniformly (-H)
    mis,         ///< light and BSDF samples combined by the power heuristic
};

/// Which integrator turns a camera ray into radiance (`--integrator`).
enum class IntegratorKind {
    automatic,  ///< chosen from the scene's effects (DESIGN.md "Effects")
    normals,    ///< shading normal as colour, n * 0.5 + 0.5
    depth,      ///< distance to the first hit as grey (debug view)
    whitted,    ///< point and directional lights, hard shadows, mirror and glass
    direct,     ///< emission plus direct light (paths of at most one bounce)
    path,       ///< path tracing with -m, -o and Russian roulette
};

const char* to_string(DirectStrategy s);
const char* to_string(IntegratorKind k);

struct RenderSettings {
    int spp = 1;                      ///< -s: camera rays per pixel (the maximum with -a)
    int light_samples = 1;            ///< -l: samples per area light
    int max_depth = 1;                ///< -m: maximum number of bounces
    bool accumulate_bounces = true;   ///< -o: 1 = all bounces up to -m, 0 = only the m-th
    uint64_t seed = 0;                ///< --seed
    bool adaptive = false;            ///< -a given
    int samples_per_batch = 32;       ///< -a N: samples between convergence tests
    double max_tolerance = 0.05;      ///< -a TOL: relative half-width of the 95% interval
    DirectStrategy direct = DirectStrategy::light;  ///< --direct, -H
    IntegratorKind integrator = IntegratorKind::automatic;  ///< --integrator
};

}  // namespace pt
