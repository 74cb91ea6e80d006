#include "apps/bench/accuracy_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/timer.h"
#include "image/metrics.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "stages/effects.h"
#include "scene/scene.h"

namespace pt::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMostSpp = 1 << 20;

/// "16 spp" or, for adaptive sampling, "max 256 spp (mean 172.3)".
std::string spp_words(const TechniqueRender& r, int spp) {
    char buf[64];
    if (std::fabs(r.mean_spp - spp) < 1e-9)
        std::snprintf(buf, sizeof buf, "%d spp", spp);
    else
        std::snprintf(buf, sizeof buf, "max %d spp (mean %.1f)", spp, r.mean_spp);
    return buf;
}

void log_render(std::ostream& log, const std::string& what, const TechniqueRender& r, int spp,
                const AccuracyRow& row) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "bench accuracy: %s: %s, %.2f s, relMSE %.4g\n", what.c_str(),
                  spp_words(r, spp).c_str(), r.seconds, row.relmse);
    log << buf << std::flush;
}

/// The rows that enter the ratios (file comment of the header): 2 spp or more.
std::vector<AccuracyRow> jittered_rows(const std::vector<AccuracyRow>& rows) {
    std::vector<AccuracyRow> out;
    for (const AccuracyRow& r : rows)
        if (r.spp >= 2) out.push_back(r);
    return out;
}

}  // namespace

TechniqueRenderer::TechniqueRenderer(const Scene& scene, const RenderSettings& baseline,
                                     Technique technique, int threads, BenchClock clock)
    : scene_(scene), technique_(std::move(technique)), threads_(threads), clock_(clock) {
    config_.settings = baseline;
    technique_.apply(config_);
    const IntegratorKind kind = choose_integrator(scene, analyze_effects(scene, config_.settings),
                                                  config_.settings, nullptr);
    integrator_ = make_integrator(kind);
    Timer timer;
    accelerator_ = build_accelerator(scene, config_.stages, config_.accelerator);
    build_seconds_ = timer.seconds();
}

TechniqueRender TechniqueRenderer::render(int spp, uint64_t seed, double time_limit) const {
    RenderSettings settings = config_.settings;
    settings.spp = spp;
    settings.seed = seed;
    RenderContext context{scene_, *accelerator_, config_.stages, settings, *integrator_};
    RenderOptions options;
    options.threads = threads_;
    // The limit is wall-clock time (the renderer's). With --clock cpu the
    // machine may be shared: allow a load of 4 before cutting a render off.
    options.time_limit = clock_ == BenchClock::cpu ? 4 * time_limit : time_limit;
    CpuTimer cpu;
    RenderResult result = render_image(context, options);
    TechniqueRender r;
    r.image = std::move(result.image);
    // CPU seconds per thread: what the render would take on idle cores.
    r.seconds = clock_ == BenchClock::cpu ? cpu.seconds() / threads_ : result.seconds;
    r.counters = result.counters;
    r.mean_spp = double(result.counters.camera_rays) / double(r.image.pixel_count());
    r.complete = result.complete;
    r.sample_counts = std::move(result.sample_counts);
    return r;
}

AccuracyRow measure(const TechniqueRender& render, int spp, const Image& reference) {
    AccuracyRow row;
    row.spp = spp;
    row.mean_spp = render.mean_spp;
    row.seconds = render.seconds;
    row.rays = render.counters.rays();
    row.rmse = rmse(render.image, reference);
    row.relmse = relmse(render.image, reference);
    row.efficiency = row.relmse > 0 && row.seconds > 0 ? 1.0 / (row.relmse * row.seconds) : kNaN;
    return row;
}

SweepResult sweep(const TechniqueRenderer& renderer, const Image& reference,
                  const SweepOptions& options, std::ostream& log) {
    SweepResult result;
    result.technique = renderer.technique();
    const std::string& name = result.technique.name;
    double spent = 0;
    for (int spp = 1; spp <= options.max_spp; spp *= 2) {
        // The first render is cut off at the budget; the later ones are
        // predicted to fit, and cut off only if they run away (twice the budget).
        const double limit = result.rows.empty() ? options.budget : 2 * options.budget;
        TechniqueRender r = renderer.render(spp, options.seed, limit);
        spent += r.seconds;
        if (!r.complete) {
            log << "bench accuracy: " << name << ": " << spp << " spp did not finish within "
                << limit << " s\n";
            if (result.rows.empty()) {
                result.finished = false;
                result.cut_at = r.seconds;
            }
            break;
        }
        result.rows.push_back(measure(r, spp, reference));
        log_render(log, name, r, spp, result.rows.back());
        if (spent + 2 * r.seconds > options.budget) break;
    }
    return result;
}

EqualTimeResult render_equal_time(const TechniqueRenderer& renderer, const Image& reference,
                                  double seconds, const SweepResult* sweep, uint64_t seed,
                                  std::ostream& log) {
    EqualTimeResult result;
    result.technique = renderer.technique();
    result.adaptive = renderer.adaptive();
    const std::string what = "equal time: " + result.technique.name;
    // Samples per second: from the sweep's longest render, else measured.
    double spp_per_second = 0;
    if (sweep && !sweep->rows.empty())
        spp_per_second = sweep->rows.back().spp / std::max(sweep->rows.back().seconds, 1e-6);
    for (int spp = 2; spp_per_second == 0; spp *= 2) {
        TechniqueRender r = renderer.render(spp, seed, 2 * seconds);
        if (!r.complete) {
            log << "bench accuracy: " << what << ": " << spp << " spp did not finish within "
                << 2 * seconds << " s\n";
            result.finished = false;
            return result;
        }
        if (r.seconds >= seconds / 8 || spp >= kMostSpp)
            spp_per_second = spp / std::max(r.seconds, 1e-6);
    }
    double best_miss = INFINITY;
    int spp = int(std::clamp(std::lround(spp_per_second * seconds), 2L, long(kMostSpp)));
    for (int attempt = 0; attempt < 3; ++attempt) {
        TechniqueRender r = renderer.render(spp, seed, 2 * seconds);
        if (!r.complete) break;
        const double miss = std::fabs(r.seconds - seconds) / seconds;
        AccuracyRow row = measure(r, spp, reference);
        log_render(log, what, r, spp, row);
        if (miss < best_miss) {
            best_miss = miss;
            result.row = row;
            result.image = std::move(r.image);
            result.sample_counts = std::move(r.sample_counts);
        }
        if (miss <= 0.25) break;
        spp = int(
            std::clamp(std::lround(spp * seconds / std::max(r.seconds, 1e-6)), 2L, long(kMostSpp)));
    }
    result.finished = !result.image.empty();
    return result;
}

double relmse_at(const std::vector<AccuracyRow>& all_rows, double seconds) {
    std::vector<AccuracyRow> rows = jittered_rows(all_rows);
    std::sort(rows.begin(), rows.end(),
              [](const AccuracyRow& a, const AccuracyRow& b) { return a.seconds < b.seconds; });
    for (size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].seconds == seconds) return rows[i].relmse;
        if (i + 1 < rows.size() && rows[i].seconds < seconds && seconds < rows[i + 1].seconds) {
            const double t = std::log(seconds / rows[i].seconds) /
                             std::log(rows[i + 1].seconds / rows[i].seconds);
            return std::exp((1 - t) * std::log(rows[i].relmse) + t * std::log(rows[i + 1].relmse));
        }
    }
    return kNaN;
}

std::vector<Comparison> compare_with_baselines(const std::vector<SweepResult>& sweeps,
                                               const std::vector<EqualTimeResult>& equal_time) {
    auto swept = [&](const std::string& name) -> const SweepResult* {
        for (const SweepResult& s : sweeps)
            if (s.technique.name == name) return &s;
        return nullptr;
    };
    auto equal = [&](const std::string& name) -> const EqualTimeResult* {
        for (const EqualTimeResult& e : equal_time)
            if (e.technique.name == name && e.finished) return &e;
        return nullptr;
    };
    auto longest = [](const std::vector<AccuracyRow>& rows) {
        double t = 0;
        for (const AccuracyRow& r : rows)
            t = std::max(t, r.seconds);
        return t;
    };
    std::vector<Technique> techniques;
    for (const SweepResult& s : sweeps)
        techniques.push_back(s.technique);
    if (sweeps.empty())
        for (const EqualTimeResult& e : equal_time)
            techniques.push_back(e.technique);

    std::vector<Comparison> out;
    for (const Technique& t : techniques) {
        bool baseline_ran = swept(t.baseline) != nullptr;
        for (const EqualTimeResult& e : equal_time)
            baseline_ran |= e.technique.name == t.baseline;
        if (t.baseline.empty() || !baseline_ran) continue;
        Comparison c{t.name, t.baseline, kNaN, kNaN, kNaN};
        const SweepResult *a = swept(t.name), *b = swept(t.baseline);
        if (a && b) {
            std::vector<AccuracyRow> ra = jittered_rows(a->rows), rb = jittered_rows(b->rows);
            if (!ra.empty() && !rb.empty()) {
                c.matched_seconds = std::min(longest(ra), longest(rb));
                // Efficiencies at equal time T: (1 / (e_a T)) / (1 / (e_b T)) = e_b / e_a.
                c.matched_ratio =
                    relmse_at(rb, c.matched_seconds) / relmse_at(ra, c.matched_seconds);
            }
        }
        const EqualTimeResult *ea = equal(t.name), *eb = equal(t.baseline);
        if (ea && eb) c.equal_time_ratio = ea->row.efficiency / eb->row.efficiency;
        out.push_back(c);
    }
    return out;
}

double fitted_slope(const std::vector<AccuracyRow>& rows) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (const AccuracyRow& row : rows) {
        if (row.spp < 2 || !(row.relmse > 0)) continue;
        const double x = std::log(double(row.spp)), y = std::log(row.relmse);
        sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
    }
    if (n < 3) return std::nan("");
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace pt::bench
