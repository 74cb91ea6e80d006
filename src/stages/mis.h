// Multiple importance sampling (MIS) of direct light, beyond the course's
// two estimators: light sampling is excellent for small or distant lights
// and poor for large, close ones (its pdf_omega = pdf_A r^2 / cos blows up
// near the light); BSDF sampling is the reverse. Veach's balance of the two
// (Veach 1997, chapter 9; pbrt-v3 section 14.3.1) draws samples from both
// and weights each by the power (default) or the balance heuristic
// (--mis-heuristic; the stage table's, task 3.7), so each strategy counts
// where it is good:
//
//     Ld ~ 1/nl sum_i w_l(x_i) f Le cos / p_l(x_i) + 1/nb sum_j w_b(y_j) f Le cos / p_b(y_j)
//     w_l = (nl p_l)^2 / ((nl p_l)^2 + (nb p_b)^2),   w_b = 1 - w_l at the same direction.
//
// Here nl = -l light samples per non-delta light (1 per delta light, weight
// 1: no BSDF sample can hit it) and nb = -l BSDF samples shared by all
// lights: a BSDF ray counts for whichever light it hits, weighted against
// that light's density (pdf_Li), or the environment's when it escapes.
//
// Part 4 builds its path tracer on the two halves: at every vertex
// sample_lights_mis(..., bsdf_samples = 1) for next-event estimation, and
// when the continuation ray, drawn by BSDF::sample_f, hits an emitter (or
// escapes into the environment), its emission times
// bsdf_sample_mis_weight(...) (weight 1 after a delta BSDF sample).
//
// Tests: tests/analytic (MIS against closed forms, zero variance in the
// furnace), docs/direct.md (variance saved, measured).
#pragma once

#include <optional>

#include "core/color.h"
#include "core/ray.h"
#include "core/rng.h"
#include "scene/bsdf.h"
#include "scene/interaction.h"
#include "scene/light_set.h"

namespace pt {

struct RenderContext;

/// The MIS weight of a sample of strategy f against strategy g by the
/// heuristic context.settings.mis_heuristic names, computed by the stage
/// table's power_heuristic or balance_heuristic (task 3.7).
double mis_weight(const RenderContext& context, double nf, double f_pdf, double ng, double g_pdf);

/// The light-sampling half: for every light, light.sample_count(-l) samples
/// from sample_Li, each tested with a shadow ray and weighted against BSDF
/// sampling with `bsdf_samples` samples (0: no BSDF sampling, every weight
/// is 1: plain light sampling); averaged per light, summed over lights.
/// `wo` is isect.wo in bsdf's local frame.
Color sample_lights_mis(const RenderContext& context, const SurfaceInteraction& isect,
                        const BSDF& bsdf, const Vec3& wo, int bsdf_samples, Rng& rng);

/// The MIS weight of emission found by a BSDF-sampled ray from ref in world
/// direction wi (density bsdf_pdf, `bsdf_samples` such samples): the power
/// heuristic of mis_weight against the density with which the light it hit (`hit`), or
/// the environment (no hit), would have been sampled. 1 when nothing there
/// is a light.
double bsdf_sample_mis_weight(const RenderContext& context, const LightSampleContext& ref,
                              const Vec3& wi, const std::optional<SurfaceInteraction>& hit,
                              double bsdf_pdf, int bsdf_samples);

/// Where light is sampled from for a shading point: with the shading normal
/// (light from above only), or without one for a transmissive BSDF, whose
/// light may come from either side (LightSampleContext's n = 0).
LightSampleContext light_sample_context(const SurfaceInteraction& isect, const BSDF& bsdf);

}  // namespace pt
