// The two rough BSDFs built on a microfacet distribution
// (microfacet_distribution.h), in the local shading frame (normal +z):
//
//   rough conductor (material "microfacet"): reflection only,
//       f(wo, wi) = F(wo . m) D(m) G2(wo, wi) / (4 cos(theta_o) cos(theta_i)),
//       m = (wo + wi) / |wo + wi|, F the conductor Fresnel term; wi is drawn by
//       reflecting wo about a sampled facet normal, with density
//       pdf(wi) = pdf_m(m) / (4 |wo . m|).
//   rough dielectric (material "rough_dielectric"): Walter, Marschner, Li and
//       Torrance, "Microfacet Models for Refraction through Rough Surfaces"
//       (EGSR 2007). With eta = n(wi side) / n(wo side) (1 for reflection) and
//       the generalised half vector m = -(eta wi + wo) / |eta wi + wo|, turned to +z:
//         reflection    F D G2 / (4 |cos_o cos_i|)                            (eq. 20)
//         transmission  (1 - F) D G2 |wi . m| |wo . m| /
//                       (|cos_o cos_i| (wi . m + wo . m / eta)^2) / eta^2      (eq. 21)
//       where the last 1 / eta^2 carries radiance across the interface (it is
//       compressed into the denser medium: the (n_o / n_i)^2 that glass has).
//       Sampling: a facet normal m from the distribution, then reflection with
//       probability F(wo . m), refraction through m by Snell's law otherwise, so
//         pdf(wi) = pdf_m(m) F / (4 |wo . m|)                                  (reflection)
//         pdf(wi) = pdf_m(m) (1 - F) |wi . m| / (wi . m + wo . m / eta)^2      (transmission, eq. 17)
//       The frame keeps the stored normal (as glass does): wo.z > 0 is
//       outside, in the medium of index 1; inside the index is `ior`.
//
// Every sample_f returns f and pdf as f() and pdf() give them for its
// direction, so a sample and an evaluation never disagree (bidirectional
// methods and MIS evaluate pdf(wo, wi) and pdf(wi, wo) for given pairs).
//
// Single scattering: light that would scatter more than once between facets
// is lost; the loss grows with roughness (docs/materials.md measures it with
// `bench furnace`).
//
// Tests: tests/statistical/test_glossy_sampling.cpp (chi-square of each
// sample_f against pdf, over the whole sphere for the dielectric),
// tests/unit/test_microfacet_models.cpp (white furnace energy, reciprocity
// f(wo, wi) / eta_o^2 ... for transmission, Helmholtz for reflection).
#pragma once

#include <cstdint>

#include "core/color.h"
#include "core/vec3.h"
#include "scene/bsdf.h"
#include "scene/microfacet_distribution.h"

namespace pt {

struct Material;

/// The microfacet distribution a rough material describes.
MicrofacetDistribution distribution_of(const Material& material);

Color rough_conductor_f(const Material& material, const Vec3& wo, const Vec3& wi);
BSDFSample rough_conductor_sample_f(const Material& material, const Vec3& wo, Vec2 u);
double rough_conductor_pdf(const Material& material, const Vec3& wo, const Vec3& wi);

Color rough_dielectric_f(const Material& material, const Vec3& wo, const Vec3& wi);
/// u picks the facet normal, uc in [0, 1) reflection (uc < F) or refraction.
BSDFSample rough_dielectric_sample_f(const Material& material, const Vec3& wo, Vec2 u, double uc);
double rough_dielectric_pdf(const Material& material, const Vec3& wo, const Vec3& wi);

/// The white furnace of a rough material alone: its directional albedo
/// E[f |cos theta_i| / pdf] from wo by its own sampling (n samples, PCG32
/// stream `seed`), refracted samples counted eta^2 times (their radiance
/// carries 1 / eta^2, their energy does not); 1 - mean is the energy that
/// single scattering loses. With the standard error of the mean.
struct AlbedoEstimate {
    double mean = 0;
    double standard_error = 0;
};
AlbedoEstimate rough_albedo(const Material& material, const Vec3& wo, int n, uint64_t seed);

}  // namespace pt
