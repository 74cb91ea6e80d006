// bench scaling: how the reference BVH grows with the triangle count. A
// (2,3) torus knot is tessellated at about 1k, 10k, 100k, 1M and 4M
// triangles (generated at run time, never stored); for each, the build time
// and the time per ray (primary, diffuse bounce, shadow), then the fitted
// growth: time per ray against log2 n (a BVH query should cost O(log n))
// and build time against n (binned SAH: O(n log n)).
#include <cmath>
#include <iostream>

#include <nlohmann/json.hpp>

#include "apps/bench/bench_command.h"
#include "apps/bench/bench_util.h"
#include "apps/bench/embree_kernel.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/timer.h"
#include "scene/framing.h"
#include "scene/mesh.h"
#include "scene/scene.h"
#include "scene/scene_loader.h"
#include "stages/bvh.h"
#include "stages/stages.h"

namespace pt::bench {
namespace {

const char* const kUsage =
    "scaling [--sizes LIST] [-r W H] [--kernel-seconds SECONDS] [--json FILE]";

const char* const kHelp = R"(bench scaling: build time and time per ray against the triangle count.

  --sizes LIST        triangle counts, e.g. 1k,10k,100k,1M,4M   [1k,10k,100k,1M,4M]
  -r W H              resolution of the ray sets               [320 240]
  --kernel-seconds S  time spent per ray kind and size         [0.5]
  --json FILE         also write every figure as JSON

The mesh is a (2,3) torus knot of 2 x segments x sides triangles, with
segments = 8 sides, so its shape stays the same and only the tessellation
grows. One thread throughout. 4M triangles need about 0.7 GB of memory.
)";

/// "10k" -> 10000, "1M" -> 1000000, "2500" -> 2500.
uint64_t parse_size(const std::string& text) {
    char* end = nullptr;
    double v = std::strtod(text.c_str(), &end);
    std::string unit = end ? end : "";
    double scale = unit == ""                   ? 1
                   : unit == "k" || unit == "K" ? 1e3
                   : unit == "M" || unit == "m" ? 1e6
                                                : -1;
    if (text.empty() || end == text.c_str() || scale < 0 || !(v * scale >= 16) || v * scale > 2e8)
        throw InputError(
            "scaling: --sizes: expected counts between 16 and 200M such as 1k,10k,1M, got '" +
            text + "'");
    return uint64_t(v * scale);
}

std::vector<uint64_t> parse_sizes(const std::string& list) {
    std::vector<uint64_t> sizes;
    size_t start = 0;
    while (start <= list.size()) {
        size_t comma = list.find(',', start);
        if (comma == std::string::npos) comma = list.size();
        sizes.push_back(parse_size(list.substr(start, comma - start)));
        start = comma + 1;
    }
    return sizes;
}

/// The knot with about `triangles` triangles, framed by a camera.
Scene knot_scene(uint64_t triangles, int width, int height) {
    // 2 * segments * sides = triangles with segments = 8 sides.
    int sides = std::max(3, int(std::lround(std::sqrt(double(triangles) / 16.0))));
    int segments = std::max(3, int(std::lround(double(triangles) / (2.0 * sides))));
    Scene scene;
    scene.name = "knot";
    scene.path = "torus knot";
    scene.materials.push_back(Material());
    add_mesh(scene, make_torus_knot(2, 3, 1.0, 0.3, segments, sides), Transform());
    scene.finalize();
    scene.film_width = width;
    scene.film_height = height;
    scene.camera.aspect = double(width) / height;
    frame_camera_on(scene.camera, scene.bounds);
    scene.camera.finalize("torus knot: camera");
    return scene;
}

struct SizeResult {
    uint64_t triangles = 0;
    double build_seconds = 0;
    AcceleratorInfo info;
    double tree_bytes_per_triangle = 0;  ///< nodes and references only
    double ns[3] = {0, 0, 0};            ///< per ray: primary, diffuse, shadow
    uint64_t rays[3] = {0, 0, 0};
    double nodes = 0, tests = 0;                       ///< per diffuse ray
    double embree_build_seconds = -1, embree_ns = -1;  ///< diffuse rays
};

SizeResult measure(uint64_t size, int width, int height, double kernel_seconds) {
    std::cerr << "bench scaling: " << short_count(size) << " triangles\n";
    Scene scene = knot_scene(size, width, height);
    SizeResult r;
    r.triangles = scene.triangles.size();
    AcceleratorSettings settings;
    IntersectStage reference{reference::intersect_triangle, reference::intersect_sphere};
    CpuTimer timer;  // CPU time of the one-thread build, as Embree's below and bench accel's
    std::unique_ptr<Accelerator> bvh = make_reference_bvh(scene, reference, settings);
    r.build_seconds = timer.seconds();
    r.info = bvh->info();
    r.tree_bytes_per_triangle = double(r.info.tree_bytes) / double(r.triangles);

    std::unique_ptr<EmbreeKernel> embree;
    if (EmbreeKernel::available()) {
        embree = std::make_unique<EmbreeKernel>(scene);
        r.embree_build_seconds = embree->build_seconds();
    }
    RaySets sets = make_ray_sets(scene, *bvh, width, height);
    for (int kind = 0; kind < 3; ++kind) {
        const std::vector<Ray>& rays = kind == 0   ? sets.primary
                                       : kind == 1 ? sets.diffuse
                                                   : sets.shadow;
        r.rays[kind] = rays.size();
        if (rays.empty()) continue;
        const bool any_hit = kind == 2;
        if (kind == 1) {
            KernelPass first = trace_pass(*bvh, rays, false);
            r.nodes = double(first.counters.nodes_visited) / double(rays.size());
            r.tests = double(first.counters.primitive_tests) / double(rays.size());
        }
        std::vector<std::function<double()>> passes = {
            [&] { return trace_pass(*bvh, rays, any_hit).seconds; }};
        if (embree && kind == 1)
            passes.push_back([&] { return embree->trace(rays, false).seconds; });
        std::vector<double> best = best_times(passes, kernel_seconds);
        r.ns[kind] = best[0] / double(rays.size()) * 1e9;
        if (passes.size() > 1) r.embree_ns = best[1] / double(rays.size()) * 1e9;
    }
    return r;
}

int run_scaling(const std::vector<std::string>& args) {
    Args a("scaling", args,
           {{"--sizes", 1},
            {"-r", 2},
            {"--kernel-seconds", 1},
            {"--json", 1},
            {"-h", 0},
            {"--help", 0}});
    if (a.has("-h") || a.has("--help")) {
        std::cout << "usage: bench " << kUsage << "\n" << kHelp;
        return kExitOk;
    }
    if (!a.positionals().empty())
        throw InputError("scaling: unexpected argument '" + a.positionals()[0] +
                         "' (see bench scaling --help)");
    std::vector<uint64_t> sizes = parse_sizes(a.get("--sizes", "1k,10k,100k,1M,4M"));
    int width = 320, height = 240;
    if (a.has("-r")) {
        width = parse_int("scaling: -r (width)", a.values("-r")[0], 1, 1 << 14);
        height = parse_int("scaling: -r (height)", a.values("-r")[1], 1, 1 << 14);
    }
    double kernel_seconds = a.get_double("--kernel-seconds", 0.5, 0);
    if (a.has("--json")) check_output_path(a.get("--json", ""), "scaling: --json");

    std::vector<SizeResult> results;
    for (uint64_t size : sizes)
        results.push_back(measure(size, width, height, kernel_seconds));

    const bool embree = EmbreeKernel::available();
    std::cout << "\n### Scaling of the reference BVH (torus knot, " << width << "x" << height
              << " rays per kind, 1 thread)\n\n";
    std::vector<std::string> header = {"triangles",       "build s",        "build ns / (n log2 n)",
                                       "nodes",           "depth",          "bytes/tri (tree)",
                                       "bytes/tri (all)", "primary ns/ray", "diffuse ns/ray",
                                       "shadow ns/ray",   "nodes/ray",      "tests/ray"};
    if (embree) {
        header.push_back("Embree build s");
        header.push_back("Embree diffuse ns/ray");
    }
    Table t(header, 0);
    std::vector<double> log_n, log_build, ns_primary, ns_diffuse, ns_shadow, log_n_build, nodes;
    for (const SizeResult& r : results) {
        double n = double(r.triangles);
        std::vector<std::string> row = {count(r.triangles),
                                        fixed(r.build_seconds, 3),
                                        fixed(r.build_seconds / (n * std::log2(n)) * 1e9, 1),
                                        count(r.info.nodes),
                                        std::to_string(r.info.depth),
                                        fixed(r.tree_bytes_per_triangle, 1),
                                        fixed(double(r.info.bytes) / n, 1),
                                        fixed(r.ns[0], 0),
                                        fixed(r.ns[1], 0),
                                        fixed(r.ns[2], 0),
                                        fixed(r.nodes, 1),
                                        fixed(r.tests, 2)};
        if (embree) {
            row.push_back(fixed(r.embree_build_seconds, 3));
            row.push_back(fixed(r.embree_ns, 0));
        }
        t.add(row);
        log_n.push_back(std::log2(n));
        ns_primary.push_back(r.ns[0]);
        ns_diffuse.push_back(r.ns[1]);
        ns_shadow.push_back(r.ns[2]);
        nodes.push_back(r.nodes);
        // Builds below 10 ms are mostly fixed costs: leave them out of the fit.
        if (r.build_seconds >= 0.01) {
            log_n_build.push_back(std::log(n));
            log_build.push_back(std::log(r.build_seconds));
        }
    }
    std::cout << t.markdown();
    if (results.size() >= 2) {
        std::cout << "\nFitted growth (least squares):\n\n";
        const char* names[3] = {"primary", "diffuse", "shadow"};
        const std::vector<double>* ys[3] = {&ns_primary, &ns_diffuse, &ns_shadow};
        for (int k = 0; k < 3; ++k) {
            LineFit f = fit_line(log_n, *ys[k]);
            std::cout << "- " << names[k] << " rays: ns/ray = " << fixed(f.a, 0) << " + "
                      << fixed(f.b, 1) << " log2 n (R^2 = " << fixed(f.r2, 3)
                      << "): " << fixed(f.b, 1) << " ns more per doubling of n\n";
        }
        // The hardware-independent count: what O(log n) is about. Time per
        // ray also pays for caches, which a larger tree fits less well.
        LineFit fn = fit_line(log_n, nodes);
        std::cout << "- nodes visited per diffuse ray = " << fixed(fn.a, 1) << " + "
                  << fixed(fn.b, 2) << " log2 n (R^2 = " << fixed(fn.r2, 3) << ")\n";
        if (log_build.size() >= 2) {
            LineFit f = fit_line(log_n_build, log_build);
            // The exponent that exact n log n growth would show over the same sizes.
            std::vector<double> log_nlogn;
            for (double ln : log_n_build)
                log_nlogn.push_back(ln + std::log(ln / std::log(2.0)));
            LineFit ideal = fit_line(log_n_build, log_nlogn);
            std::cout << "- build: seconds ~ n^" << fixed(f.b, 2) << " (R^2 = " << fixed(f.r2, 3)
                      << "); exact n log n growth would show n^" << fixed(ideal.b, 2)
                      << " over these sizes\n";
        }
    }
    if (a.has("--json")) {
        nlohmann::json j;
        for (const SizeResult& r : results) {
            nlohmann::json s = {
                {"triangles", r.triangles},
                {"build_seconds", r.build_seconds},
                {"nodes", r.info.nodes},
                {"depth", r.info.depth},
                {"bytes", r.info.bytes},
                {"tree_bytes_per_triangle", r.tree_bytes_per_triangle},
                {"ns_per_ray", {{"primary", r.ns[0]}, {"diffuse", r.ns[1]}, {"shadow", r.ns[2]}}},
                {"rays", {{"primary", r.rays[0]}, {"diffuse", r.rays[1]}, {"shadow", r.rays[2]}}},
                {"diffuse_nodes_per_ray", r.nodes},
                {"diffuse_tests_per_ray", r.tests}};
            if (r.embree_build_seconds >= 0) {
                s["embree_build_seconds"] = r.embree_build_seconds;
                s["embree_diffuse_ns_per_ray"] = r.embree_ns;
            }
            j["sizes"].push_back(s);
        }
        write_file_atomically(a.get("--json", ""), j.dump(2) + "\n");
    }
    return kExitOk;
}

const BenchCommandRegistration kRegistration({"scaling", kUsage,
                                              "build time and time per ray of the reference BVH "
                                              "from 1k to 4M triangles, with fitted growth",
                                              run_scaling});

}  // namespace
}  // namespace pt::bench
