// RenderSettings: the rendering parameters chosen on the command line
// (DESIGN.md "Command line"), independent of where the output goes.
#pragma once

#include <cstdint>
#include <string>

#include "core/sampler.h"

namespace pt {

/// How direct light is estimated at a shading point (`--direct`, `-H`).
enum class DirectStrategy {
    light,       ///< sample the lights (importance sampling, the default)
    hemisphere,  ///< sample the hemisphere uniformly (-H)
    mis,         ///< light and BSDF samples combined by the power heuristic
};

/// How MIS weighs a sample against the other strategy (`--mis-heuristic`,
/// Veach 1997, section 9.2): the power heuristic (exponent 2) or the balance heuristic.
enum class MisHeuristic {
    power,    ///< w_f = (nf pf)^2 / ((nf pf)^2 + (ng pg)^2): Veach's recommendation, the default
    balance,  ///< w_f = nf pf / (nf pf + ng pg): provably never much worse than any other weights
};

/// Which integrator turns a camera ray into radiance (`--integrator`).
enum class IntegratorKind {
    automatic,  ///< chosen from the scene's effects (DESIGN.md "Effects")
    normals,    ///< shading normal as colour, n * 0.5 + 0.5
    depth,      ///< distance to the first hit as grey (debug view)
    whitted,    ///< point and directional lights, hard shadows, mirror and glass
    direct,     ///< emission plus direct light (paths of at most one bounce)
    path,       ///< path tracing with -m, -o and Russian roulette
    pm,         ///< photon mapping, Jensen's two passes with final gathering (render/pm_integrator.cpp)
    sppm,       ///< stochastic progressive photon mapping (render/sppm.h)
    volpath,    ///< path tracing through participating media (Part 9)
    bdpt,       ///< bidirectional path tracing (Part 7, stages/bdpt.h)
};

/// The kernel of a photon density estimate (stages/photon.h), `--photon-kernel`.
enum class PhotonKernel {
    box,           ///< 1 / (pi r^2) over the disk
    cone,          ///< Jensen's cone filter, 3 (1 - d / r) / (pi r^2)
    epanechnikov,  ///< 2 (1 - d^2 / r^2) / (pi r^2), the kernel of least mean integrated squared error
};

/// What `--photon-view` shows instead of the image: one photon map's radiance estimate.
enum class PhotonView { none, caustic, global };

/// Photon mapping's parameters (`--photons` ... `--alpha`; docs/photon_mapping.md).
struct PhotonSettings {
    uint64_t photons = 200000;          ///< --photons: emitted for the global map (pm)
    uint64_t caustic_photons = 200000;  ///< --caustic-photons: emitted for the caustic map (pm)
    /// --radius: pm's fixed search radius (or, with --knn, the largest one);
    /// sppm's initial radius. Scene units; 0 = a fraction of the scene's size.
    double radius = 0;
    int knn = 50;                       ///< --knn: photons per estimate (pm); 0 = fixed radius
    PhotonKernel kernel = PhotonKernel::epanechnikov;  ///< --photon-kernel
    int passes = 16;                    ///< --passes (sppm); 0: one per camera sample (-s)
    /// --photons-per-pass (sppm); 0: one per pixel rendered (pbrt-v3's
    /// default), so that camera and photon work stay in proportion at any
    /// resolution (docs/photon_mapping.md measures why).
    uint64_t photons_per_pass = 0;
    double alpha = 2.0 / 3.0;           ///< --alpha: fraction of new photons sppm keeps per pass
    PhotonView view = PhotonView::none;  ///< --photon-view
    int max_bounces = 100;              ///< a photon path's hard cap (Russian roulette ends it sooner)
    /// The photons' seed instead of --seed (not a flag): the grader's image
    /// cases trace one photon map for every render, so that the converged
    /// reference and the student's renders differ only by camera noise.
    bool fixed_seed = false;
    uint64_t seed = 0;
};

/// How adaptive sampling decides that a pixel may stop (`--adaptive`).
enum class AdaptiveRule {
    split,  ///< decide from the odd samples, estimate from the even ones: unbiased (Kirk and Arvo 1991)
    cs184,  ///< decide from the samples the estimate averages (Part 5): biased low where runs stop early
};

const char* to_string(DirectStrategy s);
const char* to_string(AdaptiveRule r);
const char* to_string(MisHeuristic h);
const char* to_string(IntegratorKind k);
const char* to_string(PhotonKernel k);
const char* to_string(PhotonView v);

/// Code paths that the effects analysis (stages/effects.h) may switch off
/// because the effect they simulate cannot contribute to the image. Here
/// each field forces its path *on* regardless (RenderSettings::force): the
/// tests use it to prove that skipping a path changes no pixel. Not a flag.
struct CodePaths {
    bool light_sampling = false;  ///< next-event estimation in the path tracer (any light)
    bool shadow_rays = false;     ///< visibility tests of light samples (something can occlude)
    bool emission = false;  ///< emission and MIS weights found by BSDF-sampled rays (emitters, sky)
    bool refraction = false;      ///< the refraction factor eta^2 kept out of Russian roulette (glass)
    bool lens_sampling = false;   ///< a lens sample per camera ray (thin lens)
};

struct RenderSettings {
    int spp = 1;                      ///< -s: camera rays per pixel (the maximum with -a)
    int light_samples = 1;            ///< -l: samples per area light
    int max_depth = 1;                ///< -m: maximum number of bounces
    bool accumulate_bounces = true;   ///< -o: 1 = all bounces up to -m, 0 = only the m-th
    uint64_t seed = 0;                ///< --seed
    bool adaptive = false;            ///< -a given
    int samples_per_batch = 32;       ///< -a N: samples between convergence tests
    double max_tolerance = 0.05;      ///< -a TOL: relative half-width of the 95% interval
    /// --adaptive. The struct keeps Part 5's rule, which grading was
    /// calibrated with; the apps default to the unbiased `split` (options.cpp).
    AdaptiveRule adaptive_rule = AdaptiveRule::cs184;
    /// --sampler. The struct keeps independent sampling, which grading was
    /// calibrated with; the apps default to the best measured (options.cpp).
    SamplerKind sampler = SamplerKind::independent;
    DirectStrategy direct = DirectStrategy::light;  ///< --direct, -H
    MisHeuristic mis_heuristic = MisHeuristic::power;  ///< --mis-heuristic (every MIS weight: --direct mis, path)
    /// --transmittance delta: shadow rays through density grids estimate
    /// their transmittance by delta tracking (0 or a survivor's weight)
    /// instead of ratio tracking (stages/medium_tracking.h); for bench.
    bool delta_tracking_shadows = false;
    IntegratorKind integrator = IntegratorKind::automatic;  ///< --integrator
    bool russian_roulette = true;     ///< --rr-depth off turns it off
    int rr_depth = 3;                 ///< --rr-depth N: paths of up to N bounces never meet roulette
    double clamp = 0;                 ///< --clamp X: each sample's max component <= X (biased); 0 = off
    int whitted_max_specular = 8;     ///< specular bounces the Whitted integrator follows
    PhotonSettings photon;            ///< --photons ... (pm, sppm)
    /// --bdpt-strategies: BDPT's per-strategy images up to this many bounces
    /// (render/bdpt_strategies.h); -1: none.
    int bdpt_strategy_depth = -1;
    CodePaths force;                  ///< debug: code paths run even when the analysis skips them
};

}  // namespace pt
