// bench cycles: this renderer beside Blender's Cycles on one scene, each
// against the same converged reference (issue 16, item 5).
//
// The scene is loaded by the project's loader and handed to Blender as
// world-space triangles per material with the camera's basis
// (scripts/cycles_render.py builds the Blender scene from that, so the two
// renderers see the same geometry, camera, film, box filter and depth).
// Cycles renders at each --cycles-spp; this renderer at 2, 4, ... --max-spp
// with --sampler. Every image's RMSE against the reference (linear, and
// clamped to [0, 1] as a PNG shows it) and its seconds make the table;
// then, for each Cycles render, the time this renderer needs for the same
// error: on the straight line in log-log between the two renders that
// bracket it, and the first render that reaches it.
//
// Seconds are CPU seconds per thread by default (the process's user +
// system time during the render divided by the threads: the wall time on
// idle cores, robust when other processes share the machine); wall seconds
// are in the table too. Cycles' time is its whole render call (scene sync,
// its BVH, the samples; a warm-up render comes first), this renderer's the
// render without building the BVH (milliseconds for the scenes it takes).
//
// Blender is optional (Debian's `blender`): nothing else in the project
// needs it, and without it this subcommand says so and exits with 2.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "apps/bench/accuracy_reference.h"
#include "apps/bench/accuracy_report.h"
#include "apps/bench/accuracy_sweep.h"
#include "apps/bench/bench_command.h"
#include "apps/bench/bench_util.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/timer.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "scene/scene.h"
#include "scene/scene_loader.h"

namespace pt::bench {
namespace {

const char* const kUsage =
    "cycles SCENE [--cycles-spp LIST] [--cycles-pattern P] [--max-spp N] [--sampler NAME]\n"
    "            [-r W H] [-t N] [-m N] [--seed N] [--clock cpu|wall] [--reference FILE.pfm] [--reference-spp N]\n"
    "            [--cache DIR] [--no-cache] [--blender PATH] [--out DIR]";

const char* const kHelp = R"(bench cycles: this renderer beside Blender's Cycles, each against the
same converged reference, and the time each needs for the same error.

  SCENE               a .json scene or .obj mesh of triangles (and quads) with
                      diffuse, emissive or mirror materials, a pinhole
                      perspective camera, no point, directional or sky light
  --cycles-spp LIST   Cycles' samples per pixel, comma-separated  [4,16,64]
  --cycles-pattern P  Cycles' sampling pattern: pmj (progressive multi-jitter,
                      Blender 3.4's default) or sobol (Sobol-Burley)   [pmj]
  --max-spp N         this renderer renders 2, 4, ... N spp        [64]
  --sampler NAME      this renderer's sampler                     [zsobol]
  -r W H              resolution                     [the scene's film]
  -t N                threads of both renderers        [all hardware threads]
  -m N                maximum depth (-m 1: direct light; Cycles' max
                      bounces N - 1)                                [5]
  --seed N            seed of every render of both renderers        [1]
  --clock cpu|wall    the seconds the ratios use: CPU seconds per thread
                      (robust when the machine is shared) or wall  [cpu]
  --reference FILE    a converged reference (PFM, linear) instead of the cache
  --reference-spp N   samples per pixel of the reference          [1024]
  --cache DIR         where references are cached  [build/accuracy_cache]
  --no-cache          render the reference without reading or writing the cache
  --blender PATH      the Blender executable                     [blender]
  --out DIR           output folder                               [cycles]

Writes DIR/NAME_cycles.md (also printed), NAME_cycles.json, NAME_export.json
(the scene as Blender gets it) and Cycles' images NAME_cycles_SPP_SEED.exr.
Needs Debian's blender (apt-get install blender); nothing else does.
)";

struct CyclesOptions {
    std::string scene_path;
    std::vector<int> cycles_spp = {4, 16, 64};
    std::string cycles_pattern = "pmj";
    int max_spp = 64;
    SamplerKind sampler = SamplerKind::zsobol;
    int width = 0, height = 0;  ///< 0: the scene's film
    int threads = 1;
    int max_depth = 5;
    uint64_t seed = 1;
    BenchClock clock = BenchClock::cpu;
    std::string reference_path;
    int reference_spp = 1024;
    std::string cache_dir = PT_ACCURACY_CACHE_DIR;
    std::string blender = "blender";
    std::string script = PT_SOURCE_DIR "/scripts/cycles_render.py";
    std::string out_dir = "cycles";
};

std::vector<int> parse_spp_list(const std::string& text) {
    std::vector<int> list;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ','))
        list.push_back(parse_int("cycles: --cycles-spp", item, 1, 1 << 16));
    if (list.empty()) throw InputError("cycles: --cycles-spp: expected spp separated by commas");
    return list;
}

CyclesOptions parse_cycles_options(const Args& a) {
    CyclesOptions o;
    if (a.positionals().size() != 1)
        throw InputError(a.positionals().empty() ? "cycles: expected a SCENE (see bench cycles --help)"
                                                 : "cycles: unexpected argument '" +
                                                       a.positionals()[1] + "' (one SCENE only)");
    o.scene_path = a.positionals()[0];
    if (a.has("--cycles-spp")) o.cycles_spp = parse_spp_list(a.get("--cycles-spp", ""));
    o.cycles_pattern = a.get("--cycles-pattern", o.cycles_pattern);
    if (o.cycles_pattern != "pmj" && o.cycles_pattern != "sobol")
        throw InputError("cycles: --cycles-pattern: expected pmj or sobol, got '" + o.cycles_pattern + "'");
    o.max_spp = a.get_int("--max-spp", o.max_spp, 2, 1 << 16);
    if (a.has("--sampler")) o.sampler = parse_sampler_kind(a.get("--sampler", ""), "cycles: --sampler");
    if (a.has("-r")) {
        o.width = parse_int("cycles: -r (width)", a.values("-r")[0], 1, 1 << 14);
        o.height = parse_int("cycles: -r (height)", a.values("-r")[1], 1, 1 << 14);
    }
    o.threads = a.get_int("-t", int(std::max(1u, std::thread::hardware_concurrency())), 1, 4096);
    o.max_depth = a.get_int("-m", o.max_depth, 1, 1000);
    o.seed = uint64_t(a.get_int("--seed", 1, 0, 1 << 30));
    const std::string clock = a.get("--clock", "cpu");
    if (clock != "wall" && clock != "cpu")
        throw InputError("cycles: --clock: expected cpu or wall, got '" + clock + "'");
    o.clock = clock == "cpu" ? BenchClock::cpu : BenchClock::wall;
    o.reference_path = a.get("--reference", "");
    o.reference_spp = a.get_int("--reference-spp", o.reference_spp, 2, 1 << 24);
    o.cache_dir = a.has("--no-cache") ? "" : a.get("--cache", o.cache_dir);
    o.blender = a.get("--blender", o.blender);
    o.out_dir = a.get("--out", o.out_dir);
    std::error_code ec;
    std::filesystem::create_directories(o.out_dir, ec);
    if (!std::filesystem::is_directory(o.out_dir))
        throw InputError("cycles: --out: cannot create the folder '" + o.out_dir + "'");
    check_output_path(o.out_dir + "/cycles", "cycles: --out");
    return o;
}

/// `text` quoted for /bin/sh.
std::string shell_quote(const std::string& text) {
    std::string q = "'";
    for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

/// Runs `command` (stderr joined to stdout) and returns its output lines; the exit status in `status`.
std::vector<std::string> run_command(const std::string& command, int* status) {
    std::vector<std::string> lines;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) {
        *status = -1;
        return lines;
    }
    std::array<char, 4096> buf{};
    std::string line;
    while (std::fgets(buf.data(), int(buf.size()), pipe)) {
        line += buf.data();
        if (!line.empty() && line.back() == '\n') {
            line.pop_back();
            lines.push_back(line);
            line.clear();
        }
    }
    if (!line.empty()) lines.push_back(line);
    *status = pclose(pipe);
    return lines;
}

/// The Blender version line, or InputError when it does not run.
std::string blender_version(const std::string& blender) {
    int status = 0;
    std::vector<std::string> lines = run_command(shell_quote(blender) + " --version", &status);
    if (status != 0 || lines.empty())
        throw InputError("cycles: Blender not found ('" + blender +
                         " --version' failed): install Debian's blender (apt-get install blender) "
                         "or give --blender PATH; nothing else in the project needs it");
    for (const std::string& l : lines)
        if (l.rfind("Blender ", 0) == 0) return l;
    return lines.front();
}

/// The scene as Blender gets it: world-space triangles grouped by
/// material, the camera's basis and the render settings. Throws InputError
/// for what the export does not carry.
nlohmann::json export_scene(const Scene& scene, const CyclesOptions& o) {
    const std::string where = "cycles: " + scene.path + ": ";
    if (!scene.spheres.empty())
        throw InputError(where + "spheres are not exported (triangles and quads only)");
    if (!scene.point_lights.empty() || !scene.directional_lights.empty() || scene.environment)
        throw InputError(where + "point, directional and sky lights are not exported (area lights only)");
    const Camera& c = scene.camera;
    if (c.type != CameraType::perspective || c.lens_radius > 0)
        throw InputError(where + "only a pinhole perspective camera is exported");
    nlohmann::json materials = nlohmann::json::array();
    for (const Material& m : scene.materials) {
        if ((m.type != MaterialType::diffuse && m.type != MaterialType::mirror) || m.albedo_texture)
            throw InputError(where + "material '" + m.name + "' is " + to_string(m.type) +
                             (m.albedo_texture ? " with a texture" : "") +
                             ": only untextured diffuse, emissive and mirror materials are exported");
        auto rgb = [](const Color& k) { return nlohmann::json::array({k.r, k.g, k.b}); };
        materials.push_back({{"name", m.name},
                             {"type", m.type == MaterialType::mirror ? "mirror" : "diffuse"},
                             {"albedo", rgb(m.albedo)},
                             {"reflectance", rgb(m.reflectance)},
                             {"emission", rgb(m.emission)}});
    }
    nlohmann::json meshes = nlohmann::json::array();
    for (uint32_t mat = 0; mat < scene.materials.size(); ++mat) {
        std::vector<double> positions, normals;
        std::vector<uint32_t> triangles;
        bool smooth = false;
        for (const TriangleRecord& t : scene.triangles)
            if (t.material == mat && t.n[0] != kNoIndex) smooth = true;
        for (const TriangleRecord& t : scene.triangles) {
            if (t.material != mat) continue;
            const Vec3 p[3] = {scene.positions[t.v[0]], scene.positions[t.v[1]], scene.positions[t.v[2]]};
            const Vec3 flat = normalize(cross(p[1] - p[0], p[2] - p[0]));
            for (int k = 0; k < 3; ++k) {
                triangles.push_back(uint32_t(positions.size() / 3));
                positions.insert(positions.end(), {p[k].x, p[k].y, p[k].z});
                const Vec3 n = t.n[k] == kNoIndex ? flat : scene.normals[t.n[k]];
                if (smooth) normals.insert(normals.end(), {n.x, n.y, n.z});
            }
        }
        if (triangles.empty()) continue;
        nlohmann::json mesh = {{"material", mat}, {"positions", positions}, {"triangles", triangles}};
        if (smooth) mesh["normals"] = normals;
        meshes.push_back(std::move(mesh));
    }
    const double diagonal = (scene.bounds.max - scene.bounds.min).norm();
    const double far = (c.position - 0.5 * (scene.bounds.min + scene.bounds.max)).norm() + diagonal;
    auto vec = [](const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
    return {{"width", scene.film_width},
            {"height", scene.film_height},
            {"threads", o.threads},
            {"max_depth", o.max_depth},
            {"pattern", o.cycles_pattern == "sobol" ? "SOBOL" : "PROGRESSIVE_MULTI_JITTER"},
            {"camera",
             {{"position", vec(c.position)},
              {"right", vec(c.right)},
              {"up", vec(c.true_up)},
              {"backward", vec(c.backward)},
              {"vfov", c.vfov},
              {"clip_start", std::max(c.near_clip, 1e-6 * diagonal)},
              {"clip_end", 2 * far}}},
            {"materials", materials},
            {"meshes", meshes}};
}

/// One render of either renderer, measured against the reference.
struct CyclesRow {
    std::string renderer;
    int spp = 0;
    double cpu_seconds = 0;   ///< CPU seconds per thread
    double wall_seconds = 0;
    double rmse = 0;          ///< linear, against the reference
    double clamped_rmse = 0;  ///< both images clamped to [0, 1]
    double seconds(BenchClock clock) const { return clock == BenchClock::cpu ? cpu_seconds : wall_seconds; }
};

Image clamped(const Image& image) {
    Image out = image;
    for (float& v : out.data()) v = std::min(1.f, std::max(0.f, v));
    return out;
}

void measure_row(CyclesRow& row, const Image& image, const Image& reference, const Image& reference_clamped) {
    row.rmse = rmse(image, reference);
    row.clamped_rmse = rmse(clamped(image), reference_clamped);
}

/// Seconds this renderer needs for `error` (the straight line in log-log
/// between the two rows that bracket it), NaN when no row is below it or
/// the first row already is; `first` gets the seconds of the first row at
/// or below it (NaN: none).
double seconds_to(const std::vector<CyclesRow>& rows, double CyclesRow::*error, double target,
                  BenchClock clock, double* first) {
    *first = std::nan("");
    for (size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].*error > target) continue;
        *first = rows[i].seconds(clock);
        if (i == 0) return std::nan("");
        const CyclesRow &a = rows[i - 1], &b = rows[i];
        const double f = std::log(target / (a.*error)) / std::log((b.*error) / (a.*error));
        return std::exp(std::log(a.seconds(clock)) + f * std::log(b.seconds(clock) / a.seconds(clock)));
    }
    return std::nan("");
}

std::string figure(double v, int digits) { return std::isfinite(v) ? fixed(v, digits) : "n/a"; }

int run_cycles(const std::vector<std::string>& args) {
    Args a("cycles", args,
           {{"--cycles-spp", 1}, {"--cycles-pattern", 1}, {"--max-spp", 1}, {"--sampler", 1}, {"-r", 2}, {"-t", 1}, {"-m", 1},
            {"--seed", 1}, {"--clock", 1}, {"--reference", 1}, {"--reference-spp", 1},
            {"--cache", 1}, {"--no-cache", 0}, {"--blender", 1}, {"--out", 1}, {"-h", 0},
            {"--help", 0}});
    if (a.has("-h") || a.has("--help")) {
        std::cout << "usage: bench " << kUsage << "\n" << kHelp;
        return kExitOk;
    }
    // Every input is checked before the first render.
    const CyclesOptions o = parse_cycles_options(a);
    Scene scene = load_scene(o.scene_path);
    if (o.width > 0) scene.film_width = o.width, scene.film_height = o.height;
    scene.camera.aspect = double(scene.film_width) / scene.film_height;
    scene.camera.finalize(o.scene_path + ": camera");
    const nlohmann::json exported = export_scene(scene, o);
    const std::string version = blender_version(o.blender);
    Reference reference;
    if (!o.reference_path.empty())
        reference = read_reference(o.reference_path, scene.film_width, scene.film_height);
    const std::string prefix = o.out_dir + "/" + scene.name;
    const std::string export_path = prefix + "_export.json";
    write_file_atomically(export_path, exported.dump() + "\n");

    RenderSettings baseline;
    baseline.max_depth = o.max_depth;
    const std::string load_before = load_average();
    std::cerr << "bench cycles: " << scene.name << ", " << scene.film_width << "x" << scene.film_height
              << ", -m " << o.max_depth << ", " << o.threads << " threads, " << version << "\n";
    if (o.reference_path.empty())
        reference = converged_reference(scene, baseline, o.reference_spp, o.threads, o.cache_dir, std::cerr);
    const Image reference_clamped = clamped(reference.image);

    // This renderer: 2, 4, ... max spp.
    const Technique technique = select_techniques(std::string("sampler-") + to_string(o.sampler)).at(0);
    TechniqueRenderer renderer(scene, baseline, technique, o.threads, BenchClock::cpu);
    std::vector<CyclesRow> ours;
    for (int spp = 2; spp <= o.max_spp; spp *= 2) {
        Timer wall;
        TechniqueRender r = renderer.render(spp, o.seed, 0);
        CyclesRow row{"pathtracer", spp, r.seconds, wall.seconds()};
        measure_row(row, r.image, reference.image, reference_clamped);
        std::cerr << "bench cycles: pathtracer " << spp << " spp, " << fixed(row.cpu_seconds, 2)
                  << " CPU s per thread, RMSE " << fixed(row.rmse, 4) << "\n";
        ours.push_back(row);
    }

    // Cycles, in one Blender process.
    std::string command = shell_quote(o.blender) + " -b --factory-startup --python " +
                          shell_quote(o.script) + " -- " + shell_quote(export_path) + " " +
                          shell_quote(prefix + "_cycles");
    for (int spp : o.cycles_spp) command += " " + std::to_string(spp) + ":" + std::to_string(o.seed);
    std::cerr << "bench cycles: " << command << "\n";
    int status = 0;
    const std::vector<std::string> lines = run_command(command, &status);
    std::vector<CyclesRow> theirs;
    std::string pattern;
    for (const std::string& line : lines) {
        if (line.rfind("CYCLES_RESULT ", 0) != 0) continue;
        const nlohmann::json j = nlohmann::json::parse(line.substr(14));
        CyclesRow row{"Cycles", j["spp"].get<int>(), j["cpu_seconds"].get<double>() / o.threads,
                      j["wall_seconds"].get<double>()};
        measure_row(row, read_image(j["path"].get<std::string>()), reference.image, reference_clamped);
        std::cerr << "bench cycles: Cycles " << row.spp << " spp, " << fixed(row.cpu_seconds, 2)
                  << " CPU s per thread, RMSE " << fixed(row.rmse, 4) << "\n";
        pattern = j["pattern"].get<std::string>();
        theirs.push_back(row);
    }
    if (status != 0 || theirs.size() != o.cycles_spp.size()) {
        for (size_t i = lines.size() > 20 ? lines.size() - 20 : 0; i < lines.size(); ++i)
            std::cerr << "  blender: " << lines[i] << "\n";
        throw std::runtime_error("cycles: Blender failed (exit status " + std::to_string(status) +
                                 "; its last lines are above)");
    }

    // The report.
    const char* unit = o.clock == BenchClock::cpu ? "CPU s per thread" : "wall s";
    std::ostringstream md;
    md << "# bench cycles: " << scene.name << "\n\n"
       << scene.film_width << "x" << scene.film_height << ", -m " << o.max_depth << " (Cycles' max bounces "
       << o.max_depth - 1 << "), " << o.threads << " threads, box filter, seed " << o.seed << "; "
       << version << ", sampling pattern " << pattern << "; pathtracer --sampler " << to_string(o.sampler)
       << ". Reference: pathtracer, "
       << (reference.spp > 0 ? std::to_string(reference.spp) + " spp (" + reference.source + ")"
                             : "the file " + reference.path + " (spp unknown: no sidecar .json)")
       << ". Load average " << load_before << " before, " << load_average() << " after.\n\n";
    Table table({"renderer", "spp", "CPU s per thread", "wall s", "RMSE", "clamped RMSE"});
    for (const auto* rows : {&ours, &theirs})
        for (const CyclesRow& r : *rows)
            table.add({r.renderer, std::to_string(r.spp), fixed(r.cpu_seconds, 2), fixed(r.wall_seconds, 2),
                       fixed(r.rmse, 4), fixed(r.clamped_rmse, 4)});
    md << table.markdown() << "\n";
    Table ratios({"Cycles spp", "error", "Cycles " + std::string(unit), "pathtracer (interpolated)",
                  "speed ratio", "pathtracer (first render at or below)", "speed ratio"}, 2);
    nlohmann::json json_ratios = nlohmann::json::array();
    for (const CyclesRow& c : theirs)
        for (auto [error, name] : {std::pair{&CyclesRow::rmse, "linear"}, std::pair{&CyclesRow::clamped_rmse, "clamped"}}) {
            double first = 0;
            const double t = seconds_to(ours, error, c.*error, o.clock, &first);
            const double tc = c.seconds(o.clock);
            ratios.add({std::to_string(c.spp), std::string(name) + " " + fixed(c.*error, 4), fixed(tc, 2),
                        figure(t, 2), figure(tc / t, 2), figure(first, 2), figure(tc / first, 2)});
            json_ratios.push_back({{"cycles_spp", c.spp}, {"error", name}, {"target", c.*error},
                                   {"cycles_seconds", tc}, {"pathtracer_seconds", std::isfinite(t) ? t : -1},
                                   {"pathtracer_first_seconds", std::isfinite(first) ? first : -1}});
        }
    md << "Time to Cycles' error (" << unit << "; speed ratio = Cycles' time / pathtracer's, "
       << "above 1: pathtracer is faster; n/a: outside the rendered spp):\n\n" << ratios.markdown();

    nlohmann::json json = {{"scene", o.scene_path}, {"width", scene.film_width}, {"height", scene.film_height},
                           {"max_depth", o.max_depth}, {"threads", o.threads}, {"blender", version},
                           {"pattern", pattern}, {"sampler", to_string(o.sampler)},
                           {"clock", o.clock == BenchClock::cpu ? "cpu" : "wall"},
                           {"reference_spp", reference.spp}, {"ratios", json_ratios}};
    for (const auto* rows : {&ours, &theirs})
        for (const CyclesRow& r : *rows)
            json["renders"].push_back({{"renderer", r.renderer}, {"spp", r.spp}, {"cpu_seconds", r.cpu_seconds},
                                       {"wall_seconds", r.wall_seconds}, {"rmse", r.rmse},
                                       {"clamped_rmse", r.clamped_rmse}});
    write_file_atomically(prefix + "_cycles.md", md.str());
    write_file_atomically(prefix + "_cycles.json", json.dump(2) + "\n");
    std::cout << md.str();
    std::cerr << "bench cycles: wrote " << prefix << "_cycles.md, " << prefix << "_cycles.json\n";
    return kExitOk;
}

const BenchCommandRegistration kRegistration({"cycles", kUsage,
                                              "this renderer beside Blender's Cycles: time to the same "
                                              "error against one reference (needs blender)",
                                              run_cycles});

}  // namespace
}  // namespace pt::bench
