// Photon mapping, Jensen's two-pass method (Jensen 1996; "Realistic Image
// Synthesis Using Photon Mapping", 2001, chapter 9). The photon pass fills
// two maps (stages/photon.h): a caustic map (paths L S+ D) and a global
// map (every non-specular hit, L (S|D)* D). The camera pass splits the
// radiance leaving the first non-specular point x that a camera ray sees
// (through mirrors and glass) into parts that each map or estimator
// covers once:
//
//     L(x) = Le                      emission seen (directly or in specular surfaces)
//          + L_direct                light sampling with shadow rays      (L D E)
//          + L_caustic               density estimate in the caustic map  (L S+ D E)
//          + L_indirect              final gathering: one BSDF-sampled ray per camera
//                                    sample, followed through specular surfaces to a
//                                    non-specular point y, where the global map's
//                                    estimate stands for all light leaving y
//                                    (L (S|D)* D (S*) D E)
//
// Emission found by the gather ray is not counted: L_direct has it, and
// light through specular surfaces to x is L_caustic's. The estimates from
// the maps are biased (blurred over the search disk) and consistent.
// `-m` does not apply: photon paths end by Russian roulette.
// `--photon-view caustic|global` shows one map's estimate at the first
// non-specular point instead, as the course notes' figures do.
#include <cmath>
#include <mutex>

#include "render/integrators.h"
#include "render/photon_paths.h"
#include "stages/mis.h"
#include "stages/photon.h"
#include "stages/render_context.h"

namespace pt {
namespace {

/// Search radius as a fraction of the scene's radius: the largest for
/// k-nearest queries, the only one for fixed-radius queries.
constexpr double kKnnMaxRadius = 0.05;
constexpr double kFixedRadius = 0.01;

class PhotonMappingIntegrator final : public Integrator {
  public:
    void prepare(const RenderContext& context, int threads) const override {
        const PhotonSettings& ps = context.settings.photon;
        global_ = make_photon_map(context, trace_photons(context, {ps.photons, PhotonPaths::all, 1}, threads),
                                  ps.photons);
        caustic_ = make_photon_map(
            context, trace_photons(context, {ps.caustic_photons, PhotonPaths::caustic, 2}, threads), ps.caustic_photons);
        const double r = photon_radius(context, ps.knn > 0 ? kKnnMaxRadius : kFixedRadius);
        lookup_ = {ps.knn, r * r, ps.kernel};
    }

    Color Li(const RenderContext& context, const Ray& ray, Rng& rng) const override {
        const PhotonView view = context.settings.photon.view;
        Color L;
        std::optional<DiffuseVertex> x = trace_to_diffuse(context, ray, Color(1.0), rng,
                                                          view == PhotonView::none ? &L : nullptr);
        if (!x) return L;
        const BSDF bsdf = context.bsdf_at(x->isect);
        if (view == PhotonView::caustic) return x->beta * photon_radiance(context, caustic_, x->isect, bsdf, lookup_);
        if (view == PhotonView::global) return x->beta * photon_radiance(context, global_, x->isect, bsdf, lookup_);

        const Vec3 wo = bsdf.to_local(x->isect.wo);
        L += x->beta * sample_lights_mis(context, x->isect, bsdf, wo, 0, rng);
        L += x->beta * photon_radiance(context, caustic_, x->isect, bsdf, lookup_);

        // Final gathering: one step of path tracing, then the global map.
        BSDFSample bs = bsdf.sample_f(wo, rng.next_2d());
        if (!bs.valid() || bs.f.is_black()) return L;
        const Color weight = x->beta * bs.f * (std::fabs(bs.wi.z) / bs.pdf);
        std::optional<DiffuseVertex> y =
            trace_to_diffuse(context, x->isect.spawn_ray(bsdf.to_world(bs.wi)), weight, rng, nullptr);
        if (y) L += y->beta * photon_radiance(context, global_, y->isect, context.bsdf_at(y->isect), lookup_);
        return L;
    }

    IntegratorKind kind() const override { return IntegratorKind::pm; }

  private:
    mutable PhotonMap global_, caustic_;
    mutable PhotonLookup lookup_;
};

}  // namespace

std::unique_ptr<Integrator> make_pm_integrator() {
    return std::make_unique<PhotonMappingIntegrator>();
}

}  // namespace pt
