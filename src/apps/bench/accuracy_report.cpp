#include "apps/bench/accuracy_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "apps/bench/bench_util.h"
#include "image/bitmap_font.h"
#include "image/colormap.h"
#include "image/plot.h"
#include "image/tonemap.h"

namespace pt::bench {
namespace {

/// `value` with `digits` significant digits ("0.0003655"), or "n/a" for NaN.
std::string sig(double value, int digits = 4) {
    if (!std::isfinite(value)) return "n/a";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, value);
    return buf;
}

/// The spp cell: "16", "1*" (pixel centres), or "172.3 of 256" (adaptive).
std::string spp_cell(const AccuracyRow& row) {
    if (std::fabs(row.mean_spp - row.spp) > 1e-9)
        return fixed(row.mean_spp, 1) + " of " + std::to_string(row.spp);
    return std::to_string(row.spp) + (row.spp == 1 ? "*" : "");
}

std::vector<std::string> row_cells(const std::string& name, const AccuracyRow& row) {
    return {name,          spp_cell(row),   fixed(row.seconds, 3), fixed(row.rays * 1e-6, 2),
            sig(row.rmse), sig(row.relmse), sig(row.efficiency)};
}

const std::vector<std::string> kHeader = {"technique", "spp",    "seconds",   "Mrays",
                                          "RMSE",      "relMSE", "efficiency"};

/// A technique's colour: the depth caps on a ramp from dark (depth-1) to
/// light (depth-8); the others by their place in the full table, so that a
/// technique keeps its colour whichever subset is run.
Color technique_color(const std::string& name) {
    if (name.rfind("depth-", 0) == 0) return viridis_srgb((std::stoi(name.substr(6)) - 1) / 8.0);
    size_t i = 0;
    for (const Technique& t : all_techniques()) {
        if (t.name == name) return plot_color(i);
        if (t.name.rfind("depth-", 0) != 0) ++i;
    }
    return plot_color(i);
}

nlohmann::json row_json(const AccuracyRow& r) {
    return {
        {"spp", r.spp},   {"mean_spp", r.mean_spp}, {"seconds", r.seconds},      {"rays", r.rays},
        {"rmse", r.rmse}, {"relmse", r.relmse},     {"efficiency", r.efficiency}};
}

}  // namespace

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string first;
    return in >> first ? first : "unknown";
}

std::string accuracy_markdown(const AccuracyReport& r) {
    std::ostringstream md;
    const Reference& ref = *r.reference;
    md << "### What accuracy costs: " << r.scene_name << ", " << r.width << "x" << r.height
       << "\n\n    " << r.command << "\n\n";
    md << "- Reference: " << (ref.spp > 0 ? std::to_string(ref.spp) + " spp" : "spp unknown")
       << (ref.settings.empty() ? "" : " (" + ref.settings + ")");
    if (ref.seconds > 0) md << ", rendered in " << fixed(ref.seconds, 1) << " s";
    md << (ref.source == "cache"  ? ", from the cache"
           : ref.source == "file" ? ", given"
                                  : ", rendered now")
       << (ref.path.empty() ? "" : " (" + ref.path + ")");
    if (ref.own_relmse >= 0)
        md << "; its own relMSE is about " << sig(ref.own_relmse, 2)
           << " (from the spread of its passes), which every relMSE below includes";
    md << ".\n";
    md << "- Baseline: " << r.integrator << " integrator; " << r.threads << " threads, seed "
       << r.seed << ". Seconds are "
       << (r.clock == BenchClock::cpu
               ? "the process's CPU seconds per thread during the render (--clock cpu: "
                 "wall time on idle cores)"
               : "wall-clock render time")
       << " (BVH build excluded); the load average was " << r.load_before << " before and "
       << r.load_after << " after"
       << (r.clock == BenchClock::cpu ? "" : ", so timings are noisy on a shared machine")
       << ": Mrays is the hardware-independent work.\n";
    md << "- Efficiency = 1 / (relMSE x seconds). * 1 spp shoots through the pixel centres "
       << "(aliased; left out of the ratios).\n";

    if (!r.sweeps.empty()) {
        md << "\nThe longest render of each technique:\n\n";
        Table summary(kHeader, 2);
        for (const SweepResult& s : r.sweeps)
            if (!s.rows.empty()) summary.add(row_cells(s.technique.name, s.rows.back()));
        md << summary.markdown();
        md << "\nEach technique at 1, 2, 4, ... spp within a budget of " << fixed(r.budget, 1)
           << " s of renders:\n\n";
        Table t(kHeader, 2);
        for (const SweepResult& s : r.sweeps) {
            for (const AccuracyRow& row : s.rows)
                t.add(row_cells(s.technique.name, row));
            if (!s.finished)
                t.add({s.technique.name, "1", "> " + fixed(s.cut_at, 1),
                       "did not finish within the budget", "", "", ""});
        }
        md << t.markdown();
    }
    if (!r.equal_time_results.empty()) {
        md << "\nEqual time, about " << fixed(r.equal_time, 1) << " s each:\n\n";
        Table t(kHeader, 2);
        for (const EqualTimeResult& e : r.equal_time_results) {
            if (e.finished)
                t.add(row_cells(e.technique.name, e.row));
            else
                t.add({e.technique.name, "2", "> " + fixed(2 * r.equal_time, 1), "did not finish",
                       "", "", ""});
        }
        md << t.markdown();
    }
    if (!r.comparisons.empty()) {
        md << "\nEfficiency against each technique's baseline (> 1: better than the baseline; "
           << "at matched time: the sweep's relMSEs interpolated at the longest time both "
           << "reached; at equal time: the --equal-time renders):\n\n";
        Table c({"technique", "baseline", "at matched time", "at equal time"}, 2);
        for (const Comparison& x : r.comparisons)
            c.add({x.technique, x.baseline,
                   std::isfinite(x.matched_ratio)
                       ? sig(x.matched_ratio, 3) + " (at " + fixed(x.matched_seconds, 2) + " s)"
                       : "n/a",
                   sig(x.equal_time_ratio, 3)});
        md << c.markdown();
    }
    bool samplers = false;
    for (const SweepResult& s : r.sweeps) samplers = samplers || s.technique.theory_smooth != 0;
    if (samplers) {
        md << "\nConvergence: the least-squares slope of log relMSE against log spp (renders of 2 spp "
           << "or more), beside the theory for a smooth integrand and across an edge (stages/sampler.h); "
           << "the reference's own error flattens the slope once a render's relMSE nears it:\n\n";
        Table c({"technique", "fitted slope", "theory, smooth", "theory, edge"}, 1);
        for (const SweepResult& s : r.sweeps)
            if (s.technique.theory_smooth != 0)
                c.add({s.technique.name, sig(fitted_slope(s.rows), 3), sig(s.technique.theory_smooth, 2),
                       sig(s.technique.theory_edge, 2)});
        md << c.markdown();
    }
    md << "\nTechniques:\n\n";
    std::vector<Technique> seen;
    for (const SweepResult& s : r.sweeps)
        seen.push_back(s.technique);
    if (seen.empty())
        for (const EqualTimeResult& e : r.equal_time_results)
            seen.push_back(e.technique);
    for (const Technique& t : seen)
        md << "- `" << t.name << "`: " << t.what << "\n";
    return md.str();
}

nlohmann::json accuracy_json(const AccuracyReport& r) {
    const Reference& ref = *r.reference;
    nlohmann::json j = {
        {"command", r.command},
        {"scene", r.scene_path},
        {"width", r.width},
        {"height", r.height},
        {"threads", r.threads},
        {"seed", r.seed},
        {"clock", r.clock == BenchClock::cpu ? "cpu" : "wall"},
        {"integrator", r.integrator},
        {"load_average", {{"before", r.load_before}, {"after", r.load_after}}},
        {"efficiency", "1 / (relMSE x seconds)"},
        {"reference",
         {{"spp", ref.spp},
          {"seconds", ref.seconds},
          {"own_relmse", ref.own_relmse},
          {"source", ref.source},
          {"path", ref.path},
          {"settings", ref.settings}}},
    };
    if (!r.sweeps.empty()) {
        j["budget_seconds"] = r.budget;
        for (const SweepResult& s : r.sweeps) {
            nlohmann::json t = {{"name", s.technique.name},
                                {"what", s.technique.what},
                                {"baseline", s.technique.baseline},
                                {"finished", s.finished},
                                {"rows", nlohmann::json::array()}};
            if (!s.finished) t["cut_at_seconds"] = s.cut_at;
            const double slope = fitted_slope(s.rows);
            t["fitted_slope"] = std::isfinite(slope) ? nlohmann::json(slope) : nlohmann::json(nullptr);
            if (s.technique.theory_smooth != 0)
                t["theory_slope"] = {{"smooth", s.technique.theory_smooth}, {"edge", s.technique.theory_edge}};
            for (const AccuracyRow& row : s.rows)
                t["rows"].push_back(row_json(row));
            j["techniques"].push_back(t);
        }
    }
    for (const Comparison& c : r.comparisons)
        j["comparisons"].push_back({{"technique", c.technique},
                                    {"baseline", c.baseline},
                                    {"matched_seconds", c.matched_seconds},
                                    {"matched_ratio", c.matched_ratio},
                                    {"equal_time_ratio", c.equal_time_ratio}});
    if (!r.equal_time_results.empty()) {
        j["equal_time"]["seconds"] = r.equal_time;
        for (const EqualTimeResult& e : r.equal_time_results) {
            nlohmann::json t = {{"name", e.technique.name}, {"finished", e.finished}};
            if (e.finished) t.update(row_json(e.row));
            j["equal_time"]["results"].push_back(t);
        }
    }
    return j;
}

Image accuracy_plot(const AccuracyReport& r) {
    LogLogPlot plot;
    plot.title = r.scene_name + " " + std::to_string(r.width) + "x" + std::to_string(r.height) +
                 ": error against time (reference " + std::to_string(r.reference->spp) + " spp)";
    plot.x_label = std::string(r.clock == BenchClock::cpu ? "CPU seconds per thread (" : "seconds (") +
                   std::to_string(r.threads) + " threads)";
    plot.y_label = "relative RMS error, sqrt(relMSE)";
    double t_min = INFINITY, t_max = 0;
    const AccuracyRow* anchor = nullptr;
    for (const SweepResult& s : r.sweeps) {
        if (s.rows.empty()) continue;
        PlotSeries series;
        series.label = s.technique.name;
        series.color = technique_color(s.technique.name);
        for (const AccuracyRow& row : s.rows) {
            series.x.push_back(row.seconds);
            series.y.push_back(std::sqrt(row.relmse));
            t_min = std::min(t_min, row.seconds);
            t_max = std::max(t_max, row.seconds);
        }
        // The slope goes through the baseline's longest render (else the first technique's).
        if (!anchor || s.technique.baseline.empty()) anchor = &s.rows.back();
        plot.series.push_back(series);
    }
    if (anchor)
        plot.series.push_back(power_law_series("1/sqrt(time)", anchor->seconds,
                                               std::sqrt(anchor->relmse), -0.5, t_min / 10,
                                               t_max * 10, Color(0.25)));
    return render_log_log_plot(plot);
}

Image equal_time_composite(const AccuracyReport& r) {
    const int w = r.width, h = r.height, gap = 8, s = w >= 200 ? 2 : 1;
    const int label = 3 * kLineHeight * s + 4;
    int columns = 1;
    for (const EqualTimeResult& e : r.equal_time_results)
        columns += e.finished ? 1 : 0;
    Image out(gap + columns * (w + gap), gap + 2 * (h + gap) + label + gap);
    for (float& v : out.data())
        v = 1.0f;
    auto paste = [&](const Image& image, int x0, int y0) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                out.set(x0 + x, y0 + y, image.at(x, y));
    };
    // Captions are cut to the column's width.
    const size_t fits =
        size_t(std::max(1, (w + kCharAdvance * s - kGlyphWidth * s) / (kCharAdvance * s)));
    auto caption = [&](int x0, const std::vector<std::string>& lines) {
        for (size_t i = 0; i < lines.size(); ++i)
            draw_text(out, x0, gap + h + 4 + int(i) * kLineHeight * s, lines[i].substr(0, fits),
                      Color(0), s);
    };
    const Image& reference = r.reference->image;
    const int heat_y = gap + h + label + gap;
    paste(reference, gap, gap);
    caption(gap, {"reference", std::to_string(r.reference->spp) + " spp", ""});
    // Under the reference: the heat map's scale, 1e-4 (left) to 1 (right).
    for (int x = 0; x < w; ++x) {
        const Color c = viridis_srgb(double(x) / (w - 1));
        const Color lin(srgb_decode(c.r), srgb_decode(c.g), srgb_decode(c.b));
        for (int y = 0; y < 12 * s; ++y)
            out.set(gap + x, heat_y + y, lin);
    }
    draw_text(out, gap, heat_y + 14 * s, w >= 100 ? "relMSE 1e-4" : "1e-4", Color(0), s);
    draw_text(out, gap + w - text_width("1", s), heat_y + 14 * s, "1", Color(0), s);
    int column = 1;
    for (const EqualTimeResult& e : r.equal_time_results) {
        if (!e.finished) continue;
        const int x0 = gap + column++ * (w + gap);
        paste(e.image, x0, gap);
        paste(error_heatmap(e.image, reference), x0, heat_y);
        caption(x0, {e.technique.name,
                     fixed(e.row.mean_spp, 0) + " spp, " + fixed(e.row.seconds, 2) + " s",
                     "relMSE " + sig(e.row.relmse, 3)});
    }
    return out;
}

}  // namespace pt::bench
