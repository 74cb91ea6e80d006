// SPPM's passes (render/sppm.h). Every loop over pixels or photons is
// split into fixed units whose results do not depend on which thread ran
// them: same seed, same image, at any -t.
#include "render/sppm.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

#include "core/math.h"
#include "core/progress.h"
#include "core/timer.h"
#include "render/integrators.h"
#include "render/photon_paths.h"
#include "stages/mis.h"
#include "stages/photon.h"
#include "stages/render_context.h"

namespace pt {
namespace {

/// Initial radius as a fraction of the scene's bounding-sphere radius.
constexpr double kInitialRadius = 0.02;

/// What SPPM keeps per pixel across passes.
struct PixelState {
    Color direct_sum;            ///< emission and direct light of every pass, summed
    Color tau;                   ///< flux gathered within the current radius (render/sppm.h)
    double photons = 0;          ///< N: photons kept so far
    double radius2 = 0;          ///< R^2, scene units^2
    std::optional<DiffuseVertex> visible;  ///< this pass's visible point
};

/// Runs fn(i) for i in [0, count) on `threads` threads, adding the ray
/// counters of the helper threads to `counters`; rethrows the first failure.
template <class Fn>
void parallel_for(size_t count, int threads, RayCounters& counters, Fn fn) {
    std::atomic<size_t> next{0};
    std::mutex mutex;
    std::exception_ptr failure;
    auto worker = [&] {
        RayCounters& mine = thread_counters();
        const RayCounters before = mine;
        try {
            for (size_t i = next++; i < count; i = next++) fn(i);
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex);
            if (!failure) failure = std::current_exception();
            next = count;
        }
        std::lock_guard<std::mutex> lock(mutex);
        counters += mine - before;
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

class SppmIntegrator final : public Integrator {
  public:
    Color Li(const RenderContext&, const Ray&, Rng&) const override {
        throw std::logic_error("sppm renders whole passes (render_sppm), not single camera rays");
    }
    IntegratorKind kind() const override { return IntegratorKind::sppm; }
};

}  // namespace

std::unique_ptr<Integrator> make_sppm_integrator() {
    return std::make_unique<SppmIntegrator>();
}

RenderResult render_sppm(const RenderContext& context, const RenderOptions& options) {
    const Scene& scene = context.scene;
    const PhotonSettings& ps = context.settings.photon;
    const PixelRect area = options.cell.value_or(PixelRect{0, 0, scene.film_width, scene.film_height});
    const size_t pixel_count = size_t(area.width) * size_t(area.height);
    const double r0 = photon_radius(context, kInitialRadius);
    // One photon per pixel by default: a pass costs about as much in photons
    // as in camera rays. A fixed 100,000 made a 48 x 36 render spend
    // almost all of its time on photons, with 1 camera sample (direct light,
    // antialiasing) per 58 photons per pixel: 2.5 times less efficient on
    // bdpt_caustic (docs/photon_mapping.md).
    const uint64_t photons_per_pass = ps.photons_per_pass > 0 ? ps.photons_per_pass : uint64_t(pixel_count);
    std::vector<PixelState> pixels(pixel_count);
    for (PixelState& p : pixels) p.radius2 = r0 * r0;

    RenderResult result;
    result.image = Image(scene.film_width, scene.film_height);
    result.sample_counts.assign(size_t(scene.film_width) * scene.film_height, 0);
    // passes 0: one pass per camera sample of -s (bench accuracy's sweep doubles -s).
    const int total_passes = ps.passes > 0 ? ps.passes : std::max(1, context.settings.spp);
    Progress progress("sppm", uint64_t(total_passes), options.show_progress);
    Timer timer;
    int passes = 0;
    while (passes < total_passes) {
        const int pass = passes;
        // 1. Camera pass: visible points, emission and direct light.
        parallel_for(pixel_count, options.threads, result.counters, [&](size_t i) {
            const int x = area.x + int(i % size_t(area.width)), y = area.y + int(i / size_t(area.width));
            Rng rng = context.sample_generator(x, y, pass);
            const Vec2 jitter = rng.next_2d();
            rng.seek_dimension(2);
            const Vec2 lens = context.code_paths.lens_sampling ? rng.next_2d() : Vec2(0.5, 0.5);
            rng.seek_dimension(4);
            const Ray ray = context.stages.camera.generate_ray(
                scene.camera, (x + jitter.x) / scene.film_width, 1.0 - (y + jitter.y) / scene.film_height, lens);
            PixelState& p = pixels[i];
            Color L;
            p.visible = trace_to_diffuse(context, ray, Color(1.0), rng, &L);
            if (p.visible) {
                const BSDF bsdf = context.bsdf_at(p.visible->isect);
                L += p.visible->beta *
                     sample_lights_mis(context, p.visible->isect, bsdf, bsdf.to_local(p.visible->isect.wo), 0, rng);
            }
            if (L.is_finite()) p.direct_sum += L;
            else ++thread_counters().nonfinite_samples;
        });
        // 2. Photon pass: this pass's photons and their tree.
        PhotonMap map = make_photon_map(
            context,
            trace_photons(context, {photons_per_pass, PhotonPaths::indirect, 1000 + uint64_t(pass)}, options.threads),
            photons_per_pass);
        // 3. The progressive update at every visible point.
        parallel_for(pixel_count, options.threads, result.counters, [&](size_t i) {
            PixelState& p = pixels[i];
            if (!p.visible) return;
            thread_local std::vector<Neighbor> found;
            within_radius(map.tree, p.visible->isect.p, p.radius2, found);
            const BSDF bsdf = context.bsdf_at(p.visible->isect);
            const Vec3 wo = bsdf.to_local(p.visible->isect.wo);
            Color phi;
            int m = 0;
            for (const Neighbor& n : found) {
                const Photon& photon = map.photons[n.id];
                Color f = bsdf.f(wo, bsdf.to_local(photon.wi));
                if (f.is_black()) continue;
                phi += f * photon.flux;
                ++m;
            }
            if (m == 0) return;
            const double n_new = p.photons + ps.alpha * m;
            const double radius2_new = p.radius2 * n_new / (p.photons + m);
            const Color tau = (p.tau + p.visible->beta * phi) * (radius2_new / p.radius2);
            if (!tau.is_finite()) return;
            p.tau = tau;
            p.photons = n_new;
            p.radius2 = radius2_new;
        });
        ++passes;
        progress.advance(1);
        if (options.time_limit > 0 && timer.seconds() > options.time_limit) break;
    }
    for (size_t i = 0; i < pixel_count; ++i) {
        const int x = area.x + int(i % size_t(area.width)), y = area.y + int(i / size_t(area.width));
        const PixelState& p = pixels[i];
        Color L = p.direct_sum / double(passes) + p.tau / (double(passes) * kPi * p.radius2);
        if (!L.is_finite()) {
            ++result.counters.nonfinite_samples;
            L = Color(0);
        }
        result.image.set(x, y, L);
        result.sample_counts[size_t(y) * scene.film_width + x] = uint32_t(passes);
    }
    result.counters.camera_rays += uint64_t(passes) * pixel_count;
    result.seconds = timer.seconds();
    progress.finish();
    return result;
}

}  // namespace pt
