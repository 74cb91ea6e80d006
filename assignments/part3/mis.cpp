// Part 3, tasks 7 and 8: multiple importance sampling (MIS) of direct light.
// Read assignments/part3/README.md, section "Multiple importance sampling",
// first; the contract of each function is in src/stages/direct.h.
//
// What you have, beyond tasks 3.3 to 3.6:
//   bsdf.sample_f(wo, rng.next_2d())   a BSDFSample: bs.wi (local), bs.f, bs.pdf (solid angle)
//   bsdf.pdf(wo, wi)                   the density with which sample_f draws wi (local)
//   bsdf.is_transmissive()             light may arrive from below (glass): use |cos|
//   light_sample_context(isect, bsdf)  where lights are sampled from (stages/mis.h)
//   light->pdf_Li(ref, wi, p, ng)      the density with which sample_Li would draw the
//                                      world direction wi that hit the light at p (normal ng)
//   context.lights.light_of_primitive(hit->primitive)   the light a BSDF ray hit, or nullptr
//   context.lights.environment()       the environment light (a ray that escapes), or nullptr;
//                                      its pdf_Li(ref, wi, {}, {})
//   mis_weight(context, nf, pf, ng, pg)   the weight of a sample of strategy f against g by
//                                      the heuristic --mis-heuristic names: it calls your
//                                      power_heuristic or balance_heuristic (stages/mis.h)
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/sampling.h"
#include "stages/direct.h"
#include "stages/mis.h"
#include "stages/render_context.h"

namespace pt::student {

double power_heuristic(double nf, double f_pdf, double ng, double g_pdf) {
    // TODO(part3.7): power_heuristic, as src/stages/direct.h states its contract.
    // [guided]
    // Veach's power heuristic with exponent 2, as the
    // contract in src/stages/direct.h states it, limits included: 0 when
    // nf f_pdf is 0, 1 when it is infinite, and no NaN or overflow for
    // densities as large as 1e300 (divide before you square).
    // [/guided]
    (void)nf, (void)f_pdf, (void)ng, (void)g_pdf;
    throw NotImplemented(3, "7", "power_heuristic");
}

double balance_heuristic(double nf, double f_pdf, double ng, double g_pdf) {
    // TODO(part3.7): balance_heuristic, as src/stages/direct.h states its contract.
    // [guided]
    // Veach's balance heuristic, with the same limits as
    // power_heuristic.
    // [/guided]
    (void)nf, (void)f_pdf, (void)ng, (void)g_pdf;
    throw NotImplemented(3, "7", "balance_heuristic");
}

Color estimate_direct_lighting_mis(const RenderContext& context, const Ray& ray,
                                   const SurfaceInteraction& isect, Rng& rng) {
    // TODO(part3.8): estimate_direct_lighting_mis, as src/stages/direct.h states its contract.
    // [guided]
    // direct light by light samples and BSDF samples, each
    // weighted by w = mis_weight(context, ...) (your task 3.7, through the
    // stage table). Black for a delta BSDF. With nb = max(1, -l) BSDF samples:
    //  1. Light samples, as in task 3.5: for every light, its n samples; an
    //     unblocked sample above the surface adds f Le cos / s.pdf times its
    //     weight w(n, s.pdf, nb, bsdf.pdf(wo, wi)) (1 for s.is_delta: no
    //     BSDF sample can find a point light). Average per light, sum.
    //  2. BSDF samples: nb times bsdf.sample_f; trace the ray; what it finds
    //     (zero_bounce_radiance of the hit, or the environment on a miss)
    //     adds Le f |cos| / bs.pdf times w(nb, bs.pdf, n_light, pdf_Li),
    //     where n_light and pdf_Li are those of the light it found (weight
    //     1 if it found no light). Average over nb.
    // The result has the same mean as task 3.5's, with less noise where the
    // BSDF is glossy and the light large.
    // [/guided]
    (void)context, (void)ray, (void)isect, (void)rng;
    throw NotImplemented(3, "8", "estimate_direct_lighting_mis");
}

}  // namespace pt::student
