// Photon tracing and radiance estimates from photon maps (stages/photon.h).
//
// Determinism: photon i of a batch draws from its own PCG32 stream, seeded
// from (seed, i, batch stream), and the photons are traced in chunks whose
// results are joined in chunk order, so the stored photons (and every image
// made from them) are the same at any thread count.
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <cmath>
#include <optional>
#include <thread>

#include "core/math.h"
#include "stages/photon.h"
#include "stages/render_context.h"

namespace pt {
namespace {

constexpr uint64_t kPhotonStream = 0x70686F746F6Eull;  // "photon": apart from every camera sample's streams
constexpr uint64_t kChunk = 4096;                      // photons per unit of work

/// Traces photon `index` of the batch, appending the photons it stores.
void trace_one(const RenderContext& context, const PhotonTracing& tracing, uint64_t index, std::vector<Photon>& out) {
    const PhotonSettings& ps = context.settings.photon;
    Rng rng = Rng::substream(ps.fixed_seed ? ps.seed : context.settings.seed, index, tracing.stream, kPhotonStream);
    double light_probability = 0;
    const Light* light = context.lights.sample_by_power(rng.next_1d(), &light_probability);
    if (!light || !(light_probability > 0)) return;
    const Vec2 u_pos = rng.next_2d();
    const Vec2 u_dir = rng.next_2d();
    EmittedPhoton emitted = context.stages.photon.emit_photon(*light, light_probability, tracing.count, u_pos, u_dir);
    if (!emitted.valid || !emitted.flux.is_finite() || emitted.flux.is_black()) return;

    Ray ray = emitted.ray;
    Color flux = emitted.flux;
    bool specular_only = true;  // every bounce so far was specular (a caustic path)
    for (int bounces = 1; bounces <= context.settings.photon.max_bounces; ++bounces) {
        std::optional<SurfaceInteraction> hit = context.intersect(ray);
        if (!hit) return;
        BSDF bsdf = context.bsdf_at(*hit);
        if (!bsdf.is_delta()) {
            bool store = false;
            switch (tracing.store) {
                case PhotonPaths::caustic: store = bounces >= 2 && specular_only; break;
                case PhotonPaths::all: store = true; break;
                case PhotonPaths::indirect: store = bounces >= 2; break;
            }
            if (store) out.push_back({hit->p, hit->wo, flux, bounces});
            // A caustic path ends at its first non-specular hit.
            if (tracing.store == PhotonPaths::caustic) return;
        }
        // The photon's next direction, drawn from the BSDF; its flux is
        // weighed by f |cos| / pdf, without glass's eta^2 (a radiance factor).
        const Vec3 wo = bsdf.to_local(hit->wo);
        BSDFSample bs = bsdf.sample_f(wo, rng.next_2d());
        if (!bs.valid() || bs.f.is_black()) return;
        Color weight = bs.f * (std::fabs(bs.wi.z) / bs.pdf) * (bs.eta * bs.eta);
        // Russian roulette on the albedo (Jensen section 5.2): survive with
        // q, keep the photon's power by dividing by q.
        const double q = std::min(1.0, weight.max_component());
        if (!(q > 0) || rng.next_1d() >= q) return;
        flux *= weight / q;
        if (!flux.is_finite()) return;
        specular_only = specular_only && bs.is_delta;
        ray = hit->spawn_ray(bsdf.to_world(bs.wi));
    }
}

/// Whether the map's k-nearest queries are the reference's (which may use the index).
bool uses_reference_query(const RenderContext& context) {
    const KNearestFn reference_query = reference::k_nearest;
    return context.stages.photon.k_nearest == reference_query;
}

}  // namespace

std::vector<Photon> trace_photons(const RenderContext& context, const PhotonTracing& tracing, int threads) {
    const uint64_t chunks = (tracing.count + kChunk - 1) / kChunk;
    std::vector<std::vector<Photon>> stored(chunks);
    std::atomic<uint64_t> next{0};
    std::mutex mutex;
    std::exception_ptr failure;  // the first exception of any thread (a student stage's NotImplemented)
    auto worker = [&] {
        try {
            for (uint64_t c = next++; c < chunks; c = next++) {
                const uint64_t end = std::min(tracing.count, (c + 1) * kChunk);
                for (uint64_t i = c * kChunk; i < end; ++i) trace_one(context, tracing, i, stored[c]);
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex);
            if (!failure) failure = std::current_exception();
            next = chunks;
        }
    };
    std::vector<std::thread> pool;
    const int count = int(std::max<uint64_t>(1, std::min<uint64_t>(uint64_t(std::max(threads, 1)), chunks)));
    for (int t = 1; t < count; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    size_t total = 0;
    for (const auto& s : stored) total += s.size();
    std::vector<Photon> photons;
    photons.reserve(total);
    for (auto& s : stored) photons.insert(photons.end(), s.begin(), s.end());
    return photons;
}

PhotonMap make_photon_map(const RenderContext& context, std::vector<Photon> photons, uint64_t emitted) {
    PhotonMap map;
    std::vector<Vec3> points(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) points[i] = photons[i].p;
    map.tree = context.stages.photon.build_kdtree(points);
    // The index only speeds up the reference query (same answers, bit for
    // bit); a student's k_nearest reads the tree alone.
    if (uses_reference_query(context)) map.index = build_knn_index(map.tree);
    map.photons = std::move(photons);
    map.emitted = emitted;
    return map;
}

Color photon_radiance(const RenderContext& context, const PhotonMap& map, const SurfaceInteraction& isect,
                      const BSDF& bsdf, const PhotonLookup& lookup) {
    if (map.empty() || !(lookup.radius2 > 0)) return Color(0);
    thread_local std::vector<Neighbor> found;
    thread_local std::vector<PhotonContribution> contributions;
    double radius2 = lookup.radius2;
    if (lookup.knn > 0) {
        if (uses_reference_query(context) && map.index.tree_size == map.tree.size())
            reference::k_nearest(map.tree, map.index, isect.p, lookup.knn, lookup.radius2, found);
        else
            context.stages.photon.k_nearest(map.tree, isect.p, lookup.knn, lookup.radius2, found);
        // The disk through the k-th photon; the whole search disk when fewer were found.
        if (found.size() == size_t(lookup.knn)) radius2 = found.back().dist2;
        if (!(radius2 > 0)) return Color(0);  // k photons on one point: no area to divide by
    } else {
        within_radius(map.tree, isect.p, radius2, found);
    }
    const Vec3 wo = bsdf.to_local(isect.wo);
    contributions.clear();
    for (const Neighbor& n : found) {
        const Photon& photon = map.photons[n.id];
        Color f = bsdf.f(wo, bsdf.to_local(photon.wi));
        if (f.is_black()) continue;
        contributions.push_back({std::min(n.dist2, radius2), f * photon.flux});
    }
    return context.stages.photon.density_estimate(contributions, radius2, lookup.kernel);
}

double scene_radius(const RenderContext& context) {
    const BBox& b = context.scene.bounds;
    if (b.empty()) return 1.0;
    return std::max(0.5 * b.extent().norm(), 1e-12);
}

}  // namespace pt
