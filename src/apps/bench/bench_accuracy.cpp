// bench accuracy: what accuracy costs in time. For one scene: a converged
// reference (rendered once and cached), then each technique at 1, 2, 4, ...
// samples per pixel within a time budget, with spp, seconds, RMSE, relMSE
// and efficiency 1 / (relMSE x seconds) per render; the efficiency ratios
// of each technique against its baseline; a Markdown table, a JSON file
// and a log-log plot of error against time (drawn by image/plot.h, no
// gnuplot). With --equal-time S, every technique renders for S seconds and
// the images are written side by side with their error heat maps.
#include <filesystem>
#include <iostream>
#include <thread>

#include "apps/bench/accuracy_reference.h"
#include "apps/bench/accuracy_report.h"
#include "apps/bench/accuracy_sweep.h"
#include "apps/bench/accuracy_techniques.h"
#include "apps/bench/bench_command.h"
#include "apps/bench/bench_util.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "image/colormap.h"
#include "image/image_io.h"
#include "render/integrators.h"
#include "render/sample_rate_image.h"
#include "stages/effects.h"
#include "scene/scene.h"
#include "scene/scene_loader.h"

namespace pt::bench {
namespace {

const char* const kUsage =
    "accuracy SCENE [--budget SECONDS] [--equal-time SECONDS] [--techniques LIST]\n"
    "            [-r W H] [-t N] [-l N] [-m N] [-a N TOL] [--seed N] [--max-spp N]\n"
    "            [--reference FILE.pfm] [--reference-spp N] [--cache DIR] [--no-cache] [--out DIR]";

const char* const kHelp = R"(bench accuracy: what accuracy costs in time, for one scene.

  SCENE               a .json scene or .obj mesh
  --budget S          seconds of renders per technique: each renders at
                      1, 2, 4, ... spp while its total stays within S  [10]
  --equal-time S      also render every technique for about S seconds and
                      write the images side by side with their error
                      (alone, without --budget: only the equal-time renders)
  --techniques LIST   all, or some of: hemisphere, light, mis, mis-balance,
                      adaptive, adaptive-cs184, adaptive-noguard, linear-scan,
                      sampler-independent ... sampler-zsobol (or samplers
                      for all five), path, bdpt (bidirectional), pm, sppm (photon mapping: give
                      -m 100000 to compare with the uncapped path tracer),
                      tracking-delta (media: shadow rays by delta, not
                      ratio, tracking), and for the path tracer (-m 2 or
                      more) rr-off, depth-1 ... depth-8 [all]
  -r W H              resolution        [the scene's film, longer side 256]
  -t N                threads                    [all hardware threads]
  -l N, -m N          samples per area light, maximum depth   [1, 1]
                      (-m 100000: no cap; Russian roulette ends the paths)
  -a N TOL            adaptive sampling's batch and tolerance [32 0.05]
  --seed N            seed of every render                    [1]
  --clock wall|cpu    seconds as wall-clock time, or as the process's CPU
                      seconds per thread (wall time on idle cores; robust
                      when other processes share the machine)  [wall]
  --max-spp N         the sweep stops at N spp at the latest  [4096]
  --reference FILE    a converged reference (PFM, linear) instead of the cache;
                      its spp is read from FILE.json beside it when there is one
  --reference-spp N   samples per pixel of the reference      [1024]
  --cache DIR         where references are cached  [build/accuracy_cache]
  --no-cache          render the reference without reading or writing the cache
  --out DIR           output folder                           [accuracy]

Writes DIR/NAME_accuracy.md (also printed), NAME_accuracy.json,
NAME_accuracy.png (sqrt(relMSE) against seconds, log-log), NAME_reference.png,
and with --equal-time NAME_equal_time.png (all side by side), and per technique
NAME_equal_time_TECHNIQUE.png, its heat map NAME_equal_time_TECHNIQUE_error.png
(per-pixel relMSE, 1e-4 to 1, viridis) and, for adaptive sampling, its
sample-rate image NAME_equal_time_TECHNIQUE_rate.png.
Efficiency is 1 / (relMSE x seconds). Progress lines go to stderr.
)";

struct AccuracyOptions {
    std::string scene_path;
    bool run_sweep = true;
    SweepOptions sweep;
    double equal_time = 0;  ///< 0: none
    std::vector<Technique> techniques;
    int width = 0, height = 0;  ///< 0: from the scene's film
    int threads = 1;
    BenchClock clock = BenchClock::wall;
    RenderSettings baseline;
    std::string reference_path;
    int reference_spp = 1024;
    std::string cache_dir = PT_ACCURACY_CACHE_DIR;
    std::string out_dir = "accuracy";
};

double positive_seconds(const Args& a, const std::string& flag, double fallback) {
    double v = a.get_double(flag, fallback, 0);
    if (!(v > 0)) throw InputError("accuracy: " + flag + ": expected a number of seconds > 0");
    return v;
}

AccuracyOptions parse_accuracy_options(const Args& a) {
    AccuracyOptions o;
    if (a.positionals().size() != 1)
        throw InputError(a.positionals().empty()
                             ? "accuracy: expected a SCENE (see bench accuracy --help)"
                             : "accuracy: unexpected argument '" + a.positionals()[1] +
                                   "' (one SCENE only)");
    o.scene_path = a.positionals()[0];
    o.run_sweep = a.has("--budget") || !a.has("--equal-time");
    o.sweep.budget = positive_seconds(a, "--budget", 10);
    if (a.has("--equal-time")) o.equal_time = positive_seconds(a, "--equal-time", 1);
    o.techniques = select_techniques(a.get("--techniques", "all"));
    if (a.has("-r")) {
        o.width = parse_int("accuracy: -r (width)", a.values("-r")[0], 1, 1 << 14);
        o.height = parse_int("accuracy: -r (height)", a.values("-r")[1], 1, 1 << 14);
    }
    o.threads = a.get_int("-t", int(std::max(1u, std::thread::hardware_concurrency())), 1, 4096);
    o.baseline.light_samples = a.get_int("-l", 1, 1, 1 << 20);
    o.baseline.max_depth = a.get_int("-m", 1, 0, 100000);
    // SPPM (the baseline `auto` picks for point-light caustics, and the
    // reference then) runs one pass per spp, so that doubling spp doubles its work.
    o.baseline.photon.passes = 0;
    if (a.has("-a")) {
        o.baseline.samples_per_batch =
            parse_int("accuracy: -a (samples per batch)", a.values("-a")[0], 1, 1 << 20);
        const std::string& tol = a.values("-a")[1];
        char* end = nullptr;
        o.baseline.max_tolerance = std::strtod(tol.c_str(), &end);
        if (tol.empty() || *end != '\0' || !(o.baseline.max_tolerance > 0))
            throw InputError("accuracy: -a (max tolerance): expected a number > 0, got '" + tol +
                             "'");
    }
    const std::string clock = a.get("--clock", "wall");
    if (clock != "wall" && clock != "cpu")
        throw InputError("accuracy: --clock: expected wall or cpu, got '" + clock + "'");
    o.clock = clock == "cpu" ? BenchClock::cpu : BenchClock::wall;
    o.sweep.seed = uint64_t(a.get_int("--seed", 1, 0, 1 << 30));
    o.sweep.max_spp = a.get_int("--max-spp", 4096, 1, 1 << 20);
    o.reference_path = a.get("--reference", "");
    o.reference_spp = a.get_int("--reference-spp", 1024, 2, 1 << 24);
    o.cache_dir = a.has("--no-cache") ? "" : a.get("--cache", o.cache_dir);
    o.out_dir = a.get("--out", o.out_dir);
    std::error_code ec;
    std::filesystem::create_directories(o.out_dir, ec);
    if (!std::filesystem::is_directory(o.out_dir))
        throw InputError("accuracy: --out: cannot create the folder '" + o.out_dir + "'");
    check_output_path(o.out_dir + "/accuracy", "accuracy: --out");
    return o;
}

/// The scene at the bench's resolution (-r, else the film with its longer side 256).
Scene load_accuracy_scene(const AccuracyOptions& o) {
    Scene scene = load_scene(o.scene_path);
    if (o.width > 0) {
        scene.film_width = o.width, scene.film_height = o.height;
    } else {
        const double scale = 256.0 / std::max(scene.film_width, scene.film_height);
        scene.film_width = std::max(1, int(std::lround(scene.film_width * scale)));
        scene.film_height = std::max(1, int(std::lround(scene.film_height * scale)));
    }
    scene.camera.aspect = double(scene.film_width) / scene.film_height;
    scene.camera.finalize(o.scene_path + ": camera");
    return scene;
}

std::string command_line(const std::vector<std::string>& args) {
    std::string line = "bench accuracy";
    for (const std::string& a : args)
        line += " " + (a.empty() ? "''" : a);
    return line;
}

int run_accuracy(const std::vector<std::string>& args) {
    Args a("accuracy", args,
           {{"--budget", 1},
            {"--equal-time", 1},
            {"--techniques", 1},
            {"-r", 2},
            {"-t", 1},
            {"-l", 1},
            {"-m", 1},
            {"-a", 2},
            {"--seed", 1},
            {"--clock", 1},
            {"--max-spp", 1},
            {"--reference", 1},
            {"--reference-spp", 1},
            {"--cache", 1},
            {"--no-cache", 0},
            {"--out", 1},
            {"-h", 0},
            {"--help", 0}});
    if (a.has("-h") || a.has("--help")) {
        std::cout << "usage: bench " << kUsage << "\n" << kHelp;
        return kExitOk;
    }
    // Every input is checked before the first render.
    const AccuracyOptions o = parse_accuracy_options(a);
    const Scene scene = load_accuracy_scene(o);
    AccuracyReport report;
    report.command = command_line(args);
    report.scene_name = scene.name;
    report.scene_path = o.scene_path;
    report.width = scene.film_width;
    report.height = scene.film_height;
    report.threads = o.threads;
    report.seed = o.sweep.seed;
    report.clock = o.clock;
    report.integrator = to_string(
        choose_integrator(scene, analyze_effects(scene, o.baseline), o.baseline, nullptr));
    Reference reference;
    if (!o.reference_path.empty())
        reference = read_reference(o.reference_path, scene.film_width, scene.film_height);

    report.load_before = load_average();
    std::cerr << "bench accuracy: " << scene.name << ", " << scene.film_width << "x"
              << scene.film_height << ", " << o.threads << " threads, " << o.techniques.size()
              << " techniques\n";
    if (o.reference_path.empty())
        reference = converged_reference(scene, o.baseline, o.reference_spp, o.threads, o.cache_dir,
                                        std::cerr);
    report.reference = &reference;
    const std::string prefix = o.out_dir + "/" + scene.name;
    write_png(reference.image, prefix + "_reference.png");

    const bool path_baseline = report.integrator == to_string(IntegratorKind::path);
    for (const Technique& t : o.techniques) {
        // Roulette and depth caps mean something only to the path tracer, and
        // a cap only below the baseline's -m (the reference's depth).
        if (t.path_only && !path_baseline) {
            std::cerr << "bench accuracy: skipping " << t.name << ": it needs the path integrator "
                      << "as the baseline (-m 2 or more), not " << report.integrator << "\n";
            continue;
        }
        if (t.name.rfind("depth-", 0) == 0 && std::stoi(t.name.substr(6)) >= o.baseline.max_depth) {
            std::cerr << "bench accuracy: skipping " << t.name << ": not below the baseline's -m "
                      << o.baseline.max_depth << "\n";
            continue;
        }
        TechniqueRenderer renderer(scene, o.baseline, t, o.threads, o.clock);
        const SweepResult* swept = nullptr;
        if (o.run_sweep) {
            report.sweeps.push_back(sweep(renderer, reference.image, o.sweep, std::cerr));
            swept = &report.sweeps.back();
        }
        if (o.equal_time > 0)
            report.equal_time_results.push_back(render_equal_time(
                renderer, reference.image, o.equal_time, swept, o.sweep.seed, std::cerr));
    }
    report.budget = o.run_sweep ? o.sweep.budget : 0;
    report.equal_time = o.equal_time;
    report.comparisons = compare_with_baselines(report.sweeps, report.equal_time_results);
    report.load_after = load_average();

    const std::string markdown = accuracy_markdown(report);
    write_file_atomically(prefix + "_accuracy.md", markdown);
    write_file_atomically(prefix + "_accuracy.json", accuracy_json(report).dump(2) + "\n");
    std::vector<std::string> written = {prefix + "_accuracy.md", prefix + "_accuracy.json",
                                        prefix + "_reference.png"};
    if (o.run_sweep) {
        write_png(accuracy_plot(report), prefix + "_accuracy.png");
        written.push_back(prefix + "_accuracy.png");
    }
    if (o.equal_time > 0) {
        write_png(equal_time_composite(report), prefix + "_equal_time.png");
        written.push_back(prefix + "_equal_time.png");
        // Each render, its error heat map and, for adaptive sampling, its sample rates.
        for (const EqualTimeResult& e : report.equal_time_results) {
            if (!e.finished) continue;
            const std::string base = prefix + "_equal_time_" + e.technique.name;
            write_png(e.image, base + ".png");
            write_png(error_heatmap(e.image, reference.image), base + "_error.png");
            if (e.adaptive)
                write_png(
                    make_sample_rate_image(e.sample_counts, scene.film_width, scene.film_height),
                    base + "_rate.png");
        }
    }
    std::cout << markdown;
    for (const std::string& path : written)
        std::cerr << "bench accuracy: wrote " << path << "\n";
    return kExitOk;
}

const BenchCommandRegistration kRegistration({"accuracy", kUsage,
                                              "what accuracy costs in time: error against "
                                              "seconds per technique, table, JSON and plot",
                                              run_accuracy});

}  // namespace
}  // namespace pt::bench
