// bench bvh: what the BVH buys. For each scene: build time and size of the
// reference BVH, the render time with and without it (the linear scan
// estimated from a sample of pixels when it would exceed the budget), the
// speedup, rays per second, and the hardware-independent counts; then the
// ray kernels alone (primary, diffuse bounce, shadow rays) against Embree 3
// when the bench is built with it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <thread>

#include <nlohmann/json.hpp>

#include "apps/bench/bench_command.h"
#include "apps/bench/bench_render.h"
#include "apps/bench/bench_util.h"
#include "apps/bench/embree_kernel.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/timer.h"
#include "image/image_io.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "stages/effects.h"
#include "stages/kd_tree.h"
#include "stages/uniform_grid.h"
#include "scene/scene_loader.h"
#include "stages/bvh.h"
#include "stages/stages.h"

namespace pt::bench {
namespace {

const char* const kUsage =
    "bvh [SCENES...] [--shared [DIR]] [--json FILE] [-r W H] [-s N] [-t N] [--budget SECONDS]\n"
    "            [--kernel-seconds SECONDS] [--integrator KIND] [--no-linear] [--no-kernels]";

const char* const kHelp = R"(bench bvh: timing tables with and without the BVH.

  SCENES            .json scenes or .obj meshes          [every scene in assets/scenes]
  --shared [DIR]    also the .obj meshes in DIR          [../shared/meshes]
  --json FILE       also write every figure as JSON
  -r W H            resolution of renders and ray sets   [480 360]
  -s N              camera rays per pixel                [1]
  -t N              threads for the scaling column       [all hardware threads]
  --budget S        longest linear-scan render; beyond, a sample of pixels
                    is timed and the whole extrapolated  [60]
  --kernel-seconds S  time spent per ray kind in the kernel table  [1]
  --integrator KIND auto, normals, depth, ...             [auto]
  --no-linear       skip the renders without the BVH
  --no-kernels      skip the ray-kernel table

Renders and kernels run on one thread (the -t column excepted), so the
figures compare with each other and with Embree's single-ray kernel.
)";

IntegratorKind parse_integrator(const std::string& name) {
    for (IntegratorKind k :
         {IntegratorKind::automatic, IntegratorKind::normals, IntegratorKind::depth,
          IntegratorKind::whitted, IntegratorKind::direct, IntegratorKind::path})
        if (name == to_string(k)) return k;
    throw InputError(
        "bvh: --integrator: expected auto, normals, depth, whitted, direct or path, got '" + name +
        "'");
}

/// The scene without its spheres: what Embree and the kernel table compare on.
Scene triangles_only(const Scene& scene) {
    Scene t = scene;
    t.spheres.clear();
    t.finalize();
    return t;
}

std::optional<Hit> reference_triangle_through_table(const Triangle& t, const Ray& r) {
    return reference::intersect_triangle(t, r);
}

struct KernelRow {
    std::string kind;  ///< primary, diffuse, shadow
    uint64_t rays = 0;
    double mrays = 0;             ///< reference BVH (default width), inlined triangle test
    double mrays_wide4 = 0;       ///< --bvh-width 4 (SSE)
    double mrays_wide8 = 0;       ///< --bvh-width 8 (AVX2 where available)
    double mrays_packets = 0;     ///< default width, closest hits in packets (0: not timed)
    double mrays_table = 0;       ///< reference BVH, triangle test through the stage table
    double mrays_binary = 0;      ///< binary reference BVH (--bvh-width 2)
    double mrays_kdtree = 0;      ///< --accel kdtree
    double mrays_grid = 0;        ///< --accel grid
    double nodes = 0, tests = 0;  ///< per ray
    double embree_mrays = 0;
    double agreement = -1;  ///< fraction of closest hits on the same triangle as Embree's
};

struct SceneResult {
    std::string name;
    uint64_t triangles = 0, spheres = 0;
    double build_seconds = 0;
    AcceleratorInfo info;
    std::string integrator;
    RenderTiming with_bvh, without_bvh, threaded;
    bool has_linear = false;
    int threads = 1;
    std::vector<KernelRow> kernels;
    double embree_build_seconds = -1;
    uint64_t embree_bytes = 0;  ///< Embree's BVH and triangle copies (EmbreeKernel::structure_bytes)
    /// Single-thread builds of the other structures, and their memory.
    double binary_build_seconds = 0, kdtree_build_seconds = 0, grid_build_seconds = 0;
    uint64_t kdtree_bytes = 0, grid_bytes = 0;
};

double per_ray(uint64_t n, const RayCounters& c) {
    return c.rays() ? double(n) / double(c.rays()) : 0.0;
}
double mrays(const RayCounters& c, double seconds) {
    return seconds > 0 ? c.rays() / seconds * 1e-6 : 0.0;
}

/// Builds `make()`'s accelerator, timing it.
template <class Make>
std::unique_ptr<Accelerator> timed_build(Make make, double* seconds) {
    CpuTimer timer;  // one thread: its CPU time, robust to other processes
    std::unique_ptr<Accelerator> a = make();
    *seconds = timer.seconds();
    return a;
}

std::vector<KernelRow> time_kernels(const Scene& full_scene, int width, int height, double seconds,
                                    SceneResult& result) {
    double* embree_build_seconds = &result.embree_build_seconds;
    Scene scene = triangles_only(full_scene);
    AcceleratorSettings settings;
    IntersectStage reference{reference::intersect_triangle, reference::intersect_sphere};
    IntersectStage table{reference_triangle_through_table, reference::intersect_sphere};
    std::unique_ptr<Accelerator> bvh = make_reference_bvh(scene, reference, settings);
    std::unique_ptr<Accelerator> bvh_table = make_reference_bvh(scene, table, settings);
    AcceleratorSettings binary_settings;
    binary_settings.width = 2;
    std::unique_ptr<Accelerator> binary = timed_build(
        [&] { return make_reference_bvh(scene, reference, binary_settings); }, &result.binary_build_seconds);
    AcceleratorSettings wide4_settings, wide8_settings;
    wide4_settings.width = 4;
    wide8_settings.width = 8;
    std::unique_ptr<Accelerator> wide4 = make_reference_bvh(scene, reference, wide4_settings);
    std::unique_ptr<Accelerator> wide8 = make_reference_bvh(scene, reference, wide8_settings);
    std::unique_ptr<Accelerator> kdtree =
        timed_build([&] { return make_kd_tree(scene, reference); }, &result.kdtree_build_seconds);
    std::unique_ptr<Accelerator> grid =
        timed_build([&] { return make_uniform_grid(scene, reference); }, &result.grid_build_seconds);
    result.kdtree_bytes = kdtree->info().tree_bytes;
    result.grid_bytes = grid->info().tree_bytes;
    std::unique_ptr<EmbreeKernel> embree;
    if (EmbreeKernel::available()) {
        embree = std::make_unique<EmbreeKernel>(scene);
        *embree_build_seconds = embree->build_seconds();
        result.embree_bytes = embree->structure_bytes();
    }
    RaySets sets = make_ray_sets(scene, *bvh, width, height);
    std::vector<KernelRow> rows;
    for (int kind = 0; kind < 3; ++kind) {
        const std::vector<Ray>& rays = kind == 0   ? sets.primary
                                       : kind == 1 ? sets.diffuse
                                                   : sets.shadow;
        const bool any_hit = kind == 2;
        KernelRow row;
        row.kind = kind == 0 ? "primary" : kind == 1 ? "diffuse" : "shadow";
        row.rays = rays.size();
        if (rays.empty()) {
            rows.push_back(row);
            continue;
        }
        KernelPass first = trace_pass(*bvh, rays, any_hit);
        row.nodes = double(first.counters.nodes_visited) / double(rays.size());
        row.tests = double(first.counters.primitive_tests) / double(rays.size());
        std::vector<std::function<double()>> passes = {
            [&] { return trace_pass(*bvh, rays, any_hit).seconds; },
            [&] { return trace_pass(*bvh_table, rays, any_hit).seconds; },
            [&] { return trace_pass(*binary, rays, any_hit).seconds; },
            [&] { return trace_pass(*kdtree, rays, any_hit).seconds; },
            [&] { return trace_pass(*grid, rays, any_hit).seconds; },
            [&] { return trace_pass(*wide4, rays, any_hit).seconds; },
            [&] { return trace_pass(*wide8, rays, any_hit).seconds; },
            [&] { return any_hit ? 0.0 : trace_packets(*bvh, rays).seconds; }};
        if (embree) passes.push_back([&] { return embree->trace(rays, any_hit).seconds; });
        std::vector<double> best = best_times(passes, seconds);
        row.mrays = rays.size() / best[0] * 1e-6;
        row.mrays_table = rays.size() / best[1] * 1e-6;
        row.mrays_binary = rays.size() / best[2] * 1e-6;
        row.mrays_kdtree = rays.size() / best[3] * 1e-6;
        row.mrays_grid = rays.size() / best[4] * 1e-6;
        row.mrays_wide4 = rays.size() / best[5] * 1e-6;
        row.mrays_wide8 = rays.size() / best[6] * 1e-6;
        if (!any_hit) row.mrays_packets = rays.size() / best[7] * 1e-6;
        if (embree) {
            row.embree_mrays = rays.size() / best[8] * 1e-6;
            if (!any_hit) {
                std::vector<uint32_t> theirs = embree->closest_triangles(rays);
                uint64_t same = 0;
                for (size_t i = 0; i < rays.size(); ++i) {
                    std::optional<Hit> ours = bvh->intersect(rays[i]);
                    same += (ours ? ours->primitive : UINT32_MAX) == theirs[i] ? 1 : 0;
                }
                row.agreement = double(same) / double(rays.size());
            }
        }
        rows.push_back(row);
    }
    return rows;
}

/// The options of `bench bvh`, all checked before any work starts.
struct BvhOptions {
    int width = 480, height = 360;  ///< -r
    int spp = 1;                    ///< -s
    IntegratorKind integrator = IntegratorKind::automatic;
    int threads = 1;            ///< -t: for the threads table
    double budget = 60;         ///< --budget, seconds
    double kernel_seconds = 1;  ///< --kernel-seconds
    bool linear = true;         ///< not --no-linear
    bool kernels = true;        ///< not --no-kernels
};

SceneResult measure_scene(const std::string& path, const BvhOptions& o) {
    const int width = o.width, height = o.height;
    Scene scene = load_scene(path);
    scene.film_width = width;
    scene.film_height = height;
    scene.camera.aspect = double(width) / height;
    scene.camera.finalize(path + ": camera");

    SceneResult r;
    r.name = scene.name;
    r.triangles = scene.triangles.size();
    r.spheres = scene.spheres.size();
    RenderSettings settings;
    settings.spp = o.spp;
    settings.integrator = o.integrator;
    Effects effects = analyze_effects(scene, settings);
    IntegratorKind kind = choose_integrator(scene, effects, settings, nullptr);
    std::unique_ptr<Integrator> integrator = make_integrator(kind);
    r.integrator = to_string(kind);
    Stages stages = make_stages(StageSet::none());

    std::cerr << "bench bvh: " << r.name << ": building the BVH\n";
    AcceleratorSettings bvh_settings;
    CpuTimer timer;  // the build's CPU time (one thread), robust to other processes
    std::unique_ptr<Accelerator> bvh = build_accelerator(scene, stages, bvh_settings);
    r.build_seconds = timer.seconds();
    r.info = bvh->info();

    RenderContext with{scene, *bvh, stages, settings, *integrator};
    r.with_bvh = time_render(with, 1, 0.5);
    r.threads = o.threads;
    if (r.threads > 1) r.threaded = time_render(with, r.threads, 0.5);

    if (o.linear) {
        const double budget = o.budget;
        std::cerr << "bench bvh: " << r.name << ": rendering without the BVH (budget "
                  << fixed(budget, 0) << " s)\n";
        AcceleratorSettings none;
        none.kind = AccelKind::none;
        std::unique_ptr<Accelerator> linear = build_accelerator(scene, stages, none);
        RenderContext without{scene, *linear, stages, settings, *integrator};
        r.without_bvh = time_render_sampled(without, budget, 1);
        r.has_linear = true;
    }
    if (o.kernels) {
        std::cerr << "bench bvh: " << r.name << ": timing the ray kernels\n";
        r.kernels = time_kernels(scene, width, height, o.kernel_seconds, r);
    }
    return r;
}

std::string linear_cell(const SceneResult& r) {
    if (!r.has_linear) return "-";
    const RenderTiming& t = r.without_bvh;
    // Seconds to three or four significant digits.
    auto digits = [](double v) { return v >= 100 ? 1 : v >= 10 ? 2 : 3; };
    if (!t.estimated) return fixed(t.seconds, digits(t.seconds));
    // The half-width to two significant digits (at most 3 decimals).
    int d = digits(t.seconds);
    int hw = t.half_width > 0 ? std::clamp(1 - int(std::floor(std::log10(t.half_width))), 0, 3) : d;
    return "est. " + fixed(t.seconds, d) + " ± " + fixed(t.half_width, hw);
}

void print_tables(const std::vector<SceneResult>& results, int width, int height, int spp) {
    const bool embree = EmbreeKernel::available();
    int threads = results.empty() ? 1 : results[0].threads;
    std::cout << "\n### BVH against the linear scan (" << width << "x" << height << ", " << spp
              << " spp, 1 thread)\n\n";
    Table main(
        {"scene", "integrator", "triangles", "spheres", "build ms", "nodes", "depth", "tree B/prim",
         "all B/prim", "no BVH s", "BVH s", "speedup", "Mrays/s", "nodes/ray", "tests/ray"},
        2);
    for (const SceneResult& r : results) {
        const RayCounters& c = r.with_bvh.counters;
        uint64_t prims = std::max<uint64_t>(1, r.triangles + r.spheres);
        std::string speedup = "-";
        if (r.has_linear) {
            speedup = fixed(r.without_bvh.seconds / r.with_bvh.seconds, 0);
            if (r.without_bvh.estimated) speedup = "est. " + speedup;
        }
        main.add({r.name, r.integrator, count(r.triangles), count(r.spheres),
                  fixed(r.build_seconds * 1e3, 1), count(r.info.nodes),
                  std::to_string(r.info.depth),
                  fixed(double(r.info.tree_bytes) / prims, 1),
                  fixed(double(r.info.bytes) / prims, 1), linear_cell(r),
                  fixed(r.with_bvh.seconds, 4), speedup, fixed(mrays(c, r.with_bvh.seconds), 2),
                  fixed(per_ray(c.nodes_visited, c), 1), fixed(per_ray(c.primitive_tests, c), 2)});
    }
    std::cout << main.markdown();
    if (threads > 1) {
        std::cout << "\n### Render throughput with " << threads << " threads\n\n";
        Table t(
            {"scene", "1 thread Mrays/s", std::to_string(threads) + " threads Mrays/s", "ratio"});
        for (const SceneResult& r : results) {
            double one = mrays(r.with_bvh.counters, r.with_bvh.seconds);
            double many = mrays(r.threaded.counters, r.threaded.seconds);
            t.add({r.name, fixed(one, 2), fixed(many, 2), fixed(one > 0 ? many / one : 0, 2)});
        }
        std::cout << t.markdown();
    }
    bool any_kernels = false;
    for (const SceneResult& r : results)
        any_kernels |= !r.kernels.empty();
    if (!any_kernels) return;
    std::cout << "\n### Ray kernels, triangles only (1 thread, single rays; "
              << (embree ? EmbreeKernel::version() + " beside the reference BVH"
                         : "built without Embree")
              << ")\n\n";
    std::vector<std::string> header = {"scene",         "rays",           "count",        "BVH8 Mrays/s",
                                       "BVH4 Mrays/s",  "BVH2 Mrays/s",   "kd-tree Mrays/s", "grid Mrays/s",
                                       "packets Mrays/s",
                                       "via table Mrays/s", "nodes/ray",  "tests/ray"};
    if (embree) {
        for (const char* h : {"Embree Mrays/s", "BVH8 / Embree", "BVH4 / Embree", "packets / Embree", "same hit"})
            header.push_back(h);
    }
    Table k(header, 2);
    for (const SceneResult& r : results) {
        for (const KernelRow& row : r.kernels) {
            std::vector<std::string> cells = {r.name,
                                              row.kind,
                                              count(row.rays),
                                              fixed(row.mrays_wide8, 2),
                                              fixed(row.mrays_wide4, 2),
                                              fixed(row.mrays_binary, 2),
                                              fixed(row.mrays_kdtree, 2),
                                              fixed(row.mrays_grid, 2),
                                              row.mrays_packets > 0 ? fixed(row.mrays_packets, 2) : "-",
                                              fixed(row.mrays_table, 2),
                                              fixed(row.nodes, 1),
                                              fixed(row.tests, 2)};
            if (embree) {
                cells.push_back(fixed(row.embree_mrays, 2));
                for (double ours : {row.mrays_wide8, row.mrays_wide4, row.mrays_packets})
                    cells.push_back(row.embree_mrays > 0 && ours > 0 ? fixed(ours / row.embree_mrays, 2) : "-");
                cells.push_back(row.agreement >= 0 ? fixed(100 * row.agreement, 2) + "%" : "-");
            }
            k.add(cells);
        }
    }
    std::cout << k.markdown();
    std::cout << "\n### Builds (1 thread; M tri/s = million triangles per second) and memory\n\n";
    std::vector<std::string> build_header = {"scene", "triangles", "BVH Mtri/s", "BVH2 Mtri/s",
                                             "kd-tree Mtri/s", "grid Mtri/s", "kd-tree B/tri", "grid B/tri"};
    if (embree) {
        build_header.push_back("Embree Mtri/s");
        build_header.push_back("BVH B/tri");
        build_header.push_back("Embree B/tri");
    }
    Table b(build_header, 2);
    auto rate = [](uint64_t n, double s) { return s > 0 ? fixed(double(n) / s * 1e-6, 2) : std::string("-"); };
    for (const SceneResult& r : results) {
        if (r.kernels.empty()) continue;
        uint64_t n = std::max<uint64_t>(1, r.triangles);
        std::vector<std::string> cells = {r.name,
                                          count(r.triangles),
                                          rate(r.triangles, r.build_seconds),
                                          rate(r.triangles, r.binary_build_seconds),
                                          rate(r.triangles, r.kdtree_build_seconds),
                                          rate(r.triangles, r.grid_build_seconds),
                                          fixed(double(r.kdtree_bytes) / n, 1),
                                          fixed(double(r.grid_bytes) / n, 1)};
        if (embree) {
            cells.push_back(rate(r.triangles, r.embree_build_seconds));
            cells.push_back(fixed(double(r.info.bytes) / n, 1));
            cells.push_back(fixed(double(r.embree_bytes) / n, 1));
        }
        b.add(cells);
    }
    std::cout << b.markdown();
}

void write_json(const std::string& path, const std::vector<SceneResult>& results, int width,
                int height) {
    nlohmann::json j;
    j["resolution"] = {width, height};
    j["embree"] = EmbreeKernel::version();
    for (const SceneResult& r : results) {
        nlohmann::json s;
        s["scene"] = r.name;
        s["triangles"] = r.triangles;
        s["spheres"] = r.spheres;
        s["integrator"] = r.integrator;
        s["build_seconds"] = r.build_seconds;
        s["nodes"] = r.info.nodes;
        s["depth"] = r.info.depth;
        s["bytes"] = r.info.bytes;
        const RayCounters& c = r.with_bvh.counters;
        s["bvh_render_seconds"] = r.with_bvh.seconds;
        s["mrays_per_second"] = mrays(c, r.with_bvh.seconds);
        s["nodes_per_ray"] = per_ray(c.nodes_visited, c);
        s["tests_per_ray"] = per_ray(c.primitive_tests, c);
        if (r.has_linear) {
            s["linear_render_seconds"] = r.without_bvh.seconds;
            s["linear_estimated"] = r.without_bvh.estimated;
            s["linear_ci95_half_width"] = r.without_bvh.half_width;
            s["linear_pixels_rendered"] = r.without_bvh.pixels;
            s["speedup"] = r.without_bvh.seconds / r.with_bvh.seconds;
        }
        if (r.threads > 1) {
            s["threads"] = r.threads;
            s["threaded_mrays_per_second"] = mrays(r.threaded.counters, r.threaded.seconds);
        }
        if (r.embree_build_seconds >= 0) {
            s["embree_build_seconds"] = r.embree_build_seconds;
            s["embree_bytes"] = r.embree_bytes;
        }
        if (!r.kernels.empty()) {
            s["binary_build_seconds"] = r.binary_build_seconds;
            s["kdtree_build_seconds"] = r.kdtree_build_seconds;
            s["grid_build_seconds"] = r.grid_build_seconds;
            s["kdtree_bytes"] = r.kdtree_bytes;
            s["grid_bytes"] = r.grid_bytes;
        }
        for (const KernelRow& k : r.kernels) {
            nlohmann::json kj = {{"rays", k.rays},
                                 {"mrays_per_second", k.mrays},
                                 {"via_table_mrays_per_second", k.mrays_table},
                                 {"wide4_mrays_per_second", k.mrays_wide4},
                                 {"wide8_mrays_per_second", k.mrays_wide8},
                                 {"packets_mrays_per_second", k.mrays_packets},
                                 {"binary_mrays_per_second", k.mrays_binary},
                                 {"kdtree_mrays_per_second", k.mrays_kdtree},
                                 {"grid_mrays_per_second", k.mrays_grid},
                                 {"nodes_per_ray", k.nodes},
                                 {"tests_per_ray", k.tests}};
            if (k.embree_mrays > 0) kj["embree_mrays_per_second"] = k.embree_mrays;
            if (k.agreement >= 0) kj["same_hit_as_embree"] = k.agreement;
            s["kernels"][k.kind] = kj;
        }
        j["scenes"].push_back(s);
    }
    write_file_atomically(path, j.dump(2) + "\n");
}

int run_bvh(const std::vector<std::string>& raw) {
    // --shared takes an optional directory: the next argument, unless it is
    // a flag or a scene file.
    std::vector<std::string> args;
    std::string shared_dir;
    bool shared = false;
    for (size_t i = 0; i < raw.size(); ++i) {
        if (raw[i] != "--shared") {
            args.push_back(raw[i]);
            continue;
        }
        shared = true;
        shared_dir = "../shared/meshes";
        if (i + 1 < raw.size() && raw[i + 1][0] != '-') {
            std::string ext = file_extension(raw[i + 1]);
            if (ext != ".json" && ext != ".obj") shared_dir = raw[++i];
        }
    }
    Args a("bvh", args,
           {{"--json", 1},
            {"-r", 2},
            {"-s", 1},
            {"-t", 1},
            {"--budget", 1},
            {"--kernel-seconds", 1},
            {"--integrator", 1},
            {"--no-linear", 0},
            {"--no-kernels", 0},
            {"-h", 0},
            {"--help", 0}});
    if (a.has("-h") || a.has("--help")) {
        std::cout << "usage: bench " << kUsage << "\n" << kHelp;
        return kExitOk;
    }
    BvhOptions o;
    if (a.has("-r")) {
        o.width = parse_int("bvh: -r (width)", a.values("-r")[0], 1, 1 << 14);
        o.height = parse_int("bvh: -r (height)", a.values("-r")[1], 1, 1 << 14);
    }
    o.spp = a.get_int("-s", 1, 1, 1 << 20);
    o.integrator = parse_integrator(a.get("--integrator", "auto"));
    o.threads = a.get_int("-t", int(std::max(1u, std::thread::hardware_concurrency())), 1, 4096);
    o.budget = a.get_double("--budget", 60, 0.001);
    o.kernel_seconds = a.get_double("--kernel-seconds", 1, 0);
    o.linear = !a.has("--no-linear");
    o.kernels = !a.has("--no-kernels");
    std::vector<std::string> scenes = a.positionals();
    if (scenes.empty()) scenes = asset_scenes();
    if (scenes.empty() && !shared)
        throw InputError("bvh: no scenes given and no assets/scenes found");
    if (shared) {
        std::vector<std::string> meshes = obj_files(shared_dir);
        if (meshes.empty())
            std::cerr << "bench bvh: no shared meshes in " << shared_dir << "; skipping them\n";
        scenes.insert(scenes.end(), meshes.begin(), meshes.end());
    }
    if (a.has("--json")) check_output_path(a.get("--json", ""), "bvh: --json");

    // A long run says so before it starts (issue 22: --shared took ten minutes without a word).
    const double per_scene = (o.linear ? o.budget : 0) + (o.kernels ? 3 * o.kernel_seconds : 0);
    if (double(scenes.size()) * per_scene > 120)
        std::cerr << "bench bvh: " << scenes.size() << " scenes, each up to " << fixed(per_scene, 0)
                  << " s (the linear scan up to --budget, 3 ray kernels of --kernel-seconds): up to "
                  << fixed(double(scenes.size()) * per_scene / 60, 0)
                  << " minutes; --no-linear, or --budget 5 --kernel-seconds 0.2, is quicker\n";

    std::vector<SceneResult> results;
    for (const std::string& path : scenes)
        results.push_back(measure_scene(path, o));
    print_tables(results, o.width, o.height, o.spp);
    if (a.has("--json")) write_json(a.get("--json", ""), results, o.width, o.height);
    return kExitOk;
}

const BenchCommandRegistration kRegistration({"bvh", kUsage,
                                              "timing table with and without the BVH; ray kernels and builds of "
                                              "BVH4, BVH2, kd-tree, grid and Embree (when built with it)",
                                              run_bvh});
// `bench accel` (issue 17's name for the comparison of every structure) is the same command.
const BenchCommandRegistration kAccelAlias({"accel", "accel [the options of bench bvh]", "the same as bench bvh", run_bvh});

}  // namespace
}  // namespace pt::bench
