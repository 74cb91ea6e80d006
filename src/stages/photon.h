// Stage `photon` (Part 8): photons, photon maps and density estimation.
//
// Photon mapping (Jensen 1996; "Realistic Image Synthesis Using Photon
// Mapping", 2001) solves the rendering equation in two passes. The first
// pass follows light forwards: N photons leave the lights, each carrying a
// share of their power, and bounce through the scene; wherever one meets a
// non-specular surface it is stored (position, incoming direction, flux).
// The second pass estimates the radiance a surface reflects from the
// photons stored around the shading point x:
//
//     L_r(x, wo) ~= sum_p f(x, wo, wi_p) Phi_p K(|x - x_p|)               (1)
//
// with K a kernel of radius r over the surface whose integral is 1
// (a density per unit area): the box 1 / (pi r^2), Jensen's cone
// 3 (1 - d/r) / (pi r^2), or Epanechnikov's 2 (1 - d^2/r^2) / (pi r^2).
// Jensen's book (section 7.2) derives (1) from L_r = integral f L_i cos dw
// and dPhi = L_i cos dw dA. The estimate is biased (it blurs the
// illumination over the disk) and consistent: the bias goes to 0 as r
// shrinks, the variance as the photons within r grow.
//
// Emission (photon flux): a light is chosen with probability P(light)
// proportional to its power (LightSet::sample_by_power), a ray leaves it
// by Light::sample_Le with densities pdf_pos (per unit area) and pdf_dir
// (per unit solid angle), and photon i of N carries
//
//     Phi_i = Le |cos theta| / (pdf_pos pdf_dir P(light) N)               (2)
//
// so that the mean of the sum over all N photons is the total power of
// the lights, and every photon of a light whose pdfs follow its emission
// carries the same flux (Jensen section 5.1).
//
// Which photons go where (Jensen section 5.3): the caustic map holds the
// photons that reached a non-specular surface through specular bounces
// only (paths L S+ D, a separate pass of --caustic-photons); the global map
// holds every non-specular hit of --photons photons (L (S|D)* D). At each
// hit a photon survives Russian roulette with the probability of its
// albedo in the sampled direction, q = max component of f |cos| / pdf, and
// its flux is scaled by (f |cos| / pdf) / q: photons keep their power, and
// dim paths end sooner. Through glass the flux is not scaled by eta^2
// (that factor belongs to radiance, not flux: Veach 1997 section 5.2).
//
// Tests: tests/unit/test_kdtree.cpp, tests/unit/test_photon_map.cpp
// (emitted flux sums to the lights' power for every light kind, kernel
// normalisation, the estimate of a uniform photon density),
// tests/global/test_photon_mapping.cpp (renders against closed forms and
// the path tracer).
#pragma once

#include <cstdint>
#include <vector>

#include "core/color.h"
#include "core/ray.h"
#include "core/vec3.h"
#include "stages/kdtree.h"
#include "stages/knn_index.h"
#include "stages/settings.h"

namespace pt {

class Light;
struct RenderContext;
struct SurfaceInteraction;
class BSDF;

/// A photon stored on a non-specular surface.
struct Photon {
    Vec3 p;        ///< where it landed, world space
    Vec3 wi;       ///< unit direction it came from (pointing away from the surface), world space
    Color flux;    ///< W, already divided by the number of photons emitted (equation 2)
    int bounces = 0;  ///< surface hits from the light up to and including this one (1 = direct light)
};

/// A photon map: the photons and a kd-tree over their positions.
struct PhotonMap {
    std::vector<Photon> photons;  ///< in the order they were traced
    KdTree tree;                  ///< tree.ids index `photons`
    /// The reference query's copy of the tree's inner nodes (stages/knn_index.h),
    /// built only when the reference k_nearest answers the map's queries.
    KnnIndex index;
    uint64_t emitted = 0;         ///< photons emitted to fill it (N of equation 2)

    bool empty() const { return photons.empty(); }
    /// Bytes held by the photons, the tree and the index.
    size_t bytes() const { return photons.capacity() * sizeof(Photon) + tree.bytes() + index.bytes(); }
};

/// A photon leaving a light: the ray it travels along and its flux.
struct EmittedPhoton {
    Ray ray;       ///< origin on (or off) the light, unit direction away from it
    Color flux;    ///< W, equation 2
    bool valid = false;  ///< false: the light drew no ray (ignore this photon)
};

/// One photon found around a shading point, ready for equation 1.
struct PhotonContribution {
    double dist2 = 0;    ///< squared distance from the shading point, scene units^2
    Color weighted_flux;  ///< f(x, wo, wi_p) Phi_p, W/sr
};

using EmitPhotonFn = EmittedPhoton (*)(const Light& light, double light_probability, uint64_t count,
                                       Vec2 u_pos, Vec2 u_dir);
using BuildKdTreeFn = KdTree (*)(const std::vector<Vec3>& points);
using KNearestFn = void (*)(const KdTree& tree, const Vec3& p, int k, double max_dist2,
                            std::vector<Neighbor>& out);
using DensityEstimateFn = Color (*)(const std::vector<PhotonContribution>& found, double radius2,
                                    PhotonKernel kernel);

/// The function table of the stage (the student writes all four in Part 8).
struct PhotonStage {
    /// One of `count` photons from `light`, which was chosen with probability
    /// light_probability (> 0): the ray of light.sample_Le(u_pos, u_dir)
    /// and the flux of equation 2; invalid when sample_Le is.
    EmitPhotonFn emit_photon;
    /// The kd-tree over `points` in the layout of stages/kdtree.h.
    BuildKdTreeFn build_kdtree;
    /// The at most k points of `tree` nearest to p with dist2 <= max_dist2,
    /// nearest first, in `out` (cleared first).
    KNearestFn k_nearest;
    /// Equation 1: sum of weighted_flux K(d) over `found`, for the kernel
    /// of radius sqrt(radius2) (radius2 > 0), W/(m^2 sr). Every entry has
    /// dist2 <= radius2. Empty: black.
    DensityEstimateFn density_estimate;
};

namespace reference {
EmittedPhoton emit_photon(const Light& light, double light_probability, uint64_t count, Vec2 u_pos, Vec2 u_dir);
Color density_estimate(const std::vector<PhotonContribution>& found, double radius2, PhotonKernel kernel);
}  // namespace reference

namespace student {
EmittedPhoton emit_photon(const Light& light, double light_probability, uint64_t count, Vec2 u_pos, Vec2 u_dir);
KdTree build_kdtree(const std::vector<Vec3>& points);
void k_nearest(const KdTree& tree, const Vec3& p, int k, double max_dist2, std::vector<Neighbor>& out);
Color density_estimate(const std::vector<PhotonContribution>& found, double radius2, PhotonKernel kernel);
}  // namespace student

/// Which of a photon path's non-specular hits are stored.
enum class PhotonPaths {
    caustic,   ///< the first non-specular hit after one or more specular bounces (L S+ D)
    all,       ///< every non-specular hit (the global map, L (S|D)* D)
    indirect,  ///< every non-specular hit but the first (SPPM: direct light comes from light sampling)
};

/// One batch of photon paths.
struct PhotonTracing {
    uint64_t count = 0;       ///< photons emitted (N of equation 2)
    PhotonPaths store = PhotonPaths::all;
    uint64_t stream = 0;      ///< which random streams (a map, or an SPPM pass): same stream, same photons
};

/// Traces tracing.count photons from context's lights (equation 2, Russian
/// roulette on albedo, at most settings.photon.max_bounces hits) and
/// returns the stored ones in a fixed order: the same photons at any
/// `threads`. Uses context.stages.photon.emit_photon.
std::vector<Photon> trace_photons(const RenderContext& context, const PhotonTracing& tracing, int threads);

/// The map of `photons` (from `emitted` emitted), its tree built by
/// context.stages.photon.build_kdtree (and the index when
/// context.stages.photon.k_nearest is the reference's).
PhotonMap make_photon_map(const RenderContext& context, std::vector<Photon> photons, uint64_t emitted);

/// How a radiance estimate finds its photons.
struct PhotonLookup {
    int knn = 50;           ///< k nearest (within radius2); 0: every photon within radius2
    double radius2 = 0;     ///< squared search radius (the largest one, with knn), > 0
    PhotonKernel kernel = PhotonKernel::epanechnikov;
};

/// Equation 1 at isect, towards isect.wo, from `map`, with isect's BSDF
/// `bsdf` (not a delta): k nearest (the disk through the k-th photon, or
/// radius2 when fewer are found) or fixed radius.
Color photon_radiance(const RenderContext& context, const PhotonMap& map, const SurfaceInteraction& isect,
                      const BSDF& bsdf, const PhotonLookup& lookup);

/// The scene's size for default radii: the radius of its bounding sphere.
double scene_radius(const RenderContext& context);

}  // namespace pt
