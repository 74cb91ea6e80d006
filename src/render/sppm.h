// Stochastic progressive photon mapping (Hachisuka and Jensen 2009,
// "Stochastic Progressive Photon Mapping"; pbrt-v3 section 16.2).
//
// Photon mapping with a fixed radius r stays biased however many photons
// it traces. Progressive photon mapping shrinks the radius at every pixel
// as photons arrive, slowly enough that the number of photons inside it
// still grows, so both the bias and the variance go to 0. Each pass:
//
//   1. camera pass: one camera ray per pixel, followed through mirrors and
//      glass to its first non-specular point x (the pass's visible point);
//      the emission it sees and the direct light at x (light sampling) are
//      averaged over the passes like a path tracer's samples;
//   2. photon pass: --photons-per-pass photons (default one per pixel;
//      stages/photon.h), storing their non-specular hits after the first
//      (direct light is step 1's), in a kd-tree that lives for this pass
//      only;
//   3. update, per pixel, with the M photons found within R_i of x:
//
//        N_{i+1}   = N_i + alpha M
//        R_{i+1}^2 = R_i^2 (N_i + alpha M) / (N_i + M)
//        tau_{i+1} = (tau_i + beta sum_p f(wo, wi_p) Phi_p) R_{i+1}^2 / R_i^2
//
//      (alpha in (0, 1), --alpha, default 2/3: the fraction of new photons
//      kept; the radius shrinks only when photons arrive). tau is the flux
//      gathered within the current radius, Phi_p normalised per pass.
//
// After P passes: L = (sum of step 1's radiance) / P + tau / (P pi R^2).
// Memory: the per-pixel state (visible point, N, R, tau) and one pass's
// photons, whatever the number of passes: bounded by the pixels and
// --photons-per-pass, not by the total photon count.
//
// Tests: tests/global/test_photon_mapping.cpp (agreement with the path
// tracer on a small Cornell box; error falling with passes).
#pragma once

#include "render/renderer.h"

namespace pt {

/// Renders context's image by SPPM with context.settings.photon (passes,
/// photons_per_pass, radius, alpha). With options.time_limit, stops after
/// the pass during which the limit passed (the image is complete, from
/// fewer passes). sample_counts holds the passes per pixel.
RenderResult render_sppm(const RenderContext& context, const RenderOptions& options);

}  // namespace pt
