#include "apps/render_app.h"

#include <filesystem>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "apps/options.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/files.h"
#include "core/progress.h"
#include "core/timer.h"
#include "image/exr_io.h"
#include "image/image_io.h"
#include "image/tone_map.h"
#include "render/bvh_view.h"
#include "render/bdpt_strategies.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "render/sample_rate_image.h"
#include "stages/effects.h"
#include "scene/scene_loader.h"
#include "stages/global.h"

namespace pt {
namespace {

/// Fails before rendering, not after, when an output cannot be written or
/// would replace one of the inputs (the scene, the environment map).
void check_outputs(const Options& options, const Scene& scene) {
    std::vector<std::string> inputs = {options.scene_path, options.environment_map};
    if (scene.environment) inputs.push_back(scene.environment->file);
    std::vector<std::pair<std::string, std::string>> outputs = {
        {options.output, "-f"}, {options.hdr_output, "--hdr"}, {options.stats_output, "--stats"},
        {options.bvh_depth_image, "--bvh-depth-image"}};
    if (options.render.adaptive) outputs.push_back({rate_image_path(options.output), "-a (sample-rate image)"});
    for (const auto& [path, flag] : outputs) {
        if (path.empty()) continue;
        refuse_overwriting_input(path, flag, inputs);
        check_output_path(path, flag);
    }
}

/// Applies the flags that change the scene: resolution, lens, environment map.
void apply_scene_overrides(Scene& scene, const Options& options) {
    if (options.resolution) {
        scene.film_width = options.resolution->first;
        scene.film_height = options.resolution->second;
    }
    if (options.lens_radius) scene.camera.lens_radius = *options.lens_radius;
    if (options.focal_distance) scene.camera.focal_distance = *options.focal_distance;
    if (!options.environment_map.empty()) {
        require_readable_file(options.environment_map, "-e");
        std::string ext = file_extension(options.environment_map);
        if (ext != ".hdr" && ext != ".pfm" && ext != ".exr")
            throw InputError("-e: expected a .hdr, .pfm or .exr lat-long map, got '" + options.environment_map + "'");
        EnvironmentLight env;
        env.file = options.environment_map;
        scene.environment = env;
    }
    scene.camera.aspect = double(scene.film_width) / scene.film_height;
    scene.camera.finalize(scene.path + ": camera");
    if (options.cell) {
        const PixelRect& c = *options.cell;
        if (c.x + c.width > scene.film_width || c.y + c.height > scene.film_height)
            throw InputError("-p: the cell does not fit in the " + std::to_string(scene.film_width) + "x" +
                             std::to_string(scene.film_height) + " image");
    }
}

/// True when no pixel received any light. With lights in the scene that is
/// almost always a camera that sees only the backs of things (issue 22: an
/// auto-framed cbox.obj used to render black without a word).
bool every_pixel_black(const Image& image) {
    for (float v : image.data())
        if (v != 0) return false;
    return true;
}

struct PhaseSeconds {
    double load = 0, build = 0, render = 0;
};

void write_stats(const std::string& path, const std::string& program, const Options& options, const Scene& scene,
                 const Effects& effects, const CodePaths& code_paths, IntegratorKind integrator,
                 const AcceleratorInfo& accel, const RenderResult& result, const PhaseSeconds& seconds) {
    const RayCounters& c = result.counters;
    double rays = double(std::max<uint64_t>(c.rays(), 1));
    nlohmann::json j;
    j["program"] = program;
    j["scene"] = scene.path;
    j["resolution"] = {scene.film_width, scene.film_height};
    double pixels = double(options.cell ? uint64_t(options.cell->width) * options.cell->height
                                        : uint64_t(scene.film_width) * scene.film_height);
    j["spp"] = double(result.counters.camera_rays) / pixels;  // measured mean (less than -s with -a)
    j["spp_max"] = options.render.spp;
    j["threads"] = options.threads;
    j["seed"] = options.render.seed;
    j["sampler"] = to_string(options.render.sampler);
    j["student_stages"] = options.student.to_string();
    j["integrator"] = to_string(integrator);
    j["effects"] = effects.names();
    j["code_paths"] = {{"light_sampling", code_paths.light_sampling},
                       {"shadow_rays", code_paths.shadow_rays},
                       {"emission", code_paths.emission},
                       {"refraction", code_paths.refraction},
                       {"lens_sampling", code_paths.lens_sampling}};
    j["max_depth"] = options.render.max_depth;
    j["accumulate_bounces"] = options.render.accumulate_bounces;
    j["direct"] = to_string(options.render.direct);
    j["russian_roulette"] = options.render.russian_roulette
                                ? nlohmann::json{{"rr_depth", options.render.rr_depth},
                                                 {"max_survival", kMaxSurvivalProbability}}
                                : nlohmann::json(false);
    j["clamp"] = options.render.clamp > 0 ? nlohmann::json(options.render.clamp) : nlohmann::json(false);
    j["clamped_samples"] = c.clamped_samples;
    j["seconds"] = {{"load", seconds.load}, {"build", seconds.build}, {"render", seconds.render},
                    {"total", seconds.load + seconds.build + seconds.render}};
    j["rays"] = {{"camera", c.camera_rays}, {"closest_hit", c.closest_hit_rays}, {"shadow", c.shadow_rays},
                 {"total", c.rays()}, {"from_packets", c.packet_rays}};
    j["packets"] = options.packets;
    j["mrays_per_second"] = seconds.render > 0 ? c.rays() / seconds.render * 1e-6 : 0.0;
    j["primitive_tests_per_ray"] = c.primitive_tests / rays;
    j["nodes_visited_per_ray"] = c.nodes_visited / rays;
    j["nonfinite_samples"] = c.nonfinite_samples;
    j["primitives"] = {{"triangles", scene.triangles.size()}, {"spheres", scene.spheres.size()},
                       {"emitters", scene.emitters.size()}};
    j["accelerator"] = {{"name", accel.name}, {"nodes", accel.nodes}, {"depth", accel.depth}, {"bytes", accel.bytes}};
    if (options.render.adaptive) {
        // Per-pixel sample counts, row by row from the top (adaptive sampling only).
        const std::vector<uint32_t>& counts = result.sample_counts;
        uint64_t total = 0;
        for (uint32_t n : counts) total += n;
        nlohmann::json rows = nlohmann::json::array();
        for (int y = 0; y < scene.film_height; ++y)
            rows.push_back(std::vector<uint32_t>(counts.begin() + long(y) * scene.film_width,
                                                 counts.begin() + long(y + 1) * scene.film_width));
        j["adaptive"] = {{"rule", to_string(options.render.adaptive_rule)},
                         {"samples_per_batch", options.render.samples_per_batch},
                         {"max_tolerance", options.render.max_tolerance},
                         {"mean_spp", double(total) / double(std::max<size_t>(counts.size(), 1))},
                         {"sample_counts", rows}};
    }
    write_file_atomically(path, j.dump(2) + "\n");
}

/// Traces the camera rays once more, one per pixel centre, counting the BVH
/// nodes each visits, and writes the heat map (render/bvh_view.h).
void write_bvh_depth_image(const RenderContext& context, const RenderOptions& render_options,
                           const Options& options, const std::string& program) {
    RenderSettings one_ray = context.settings;
    one_ray.spp = 1;
    one_ray.adaptive = false;
    std::unique_ptr<Integrator> cost = make_bvh_cost_integrator();
    RenderContext counting{context.scene, context.accelerator, context.stages, one_ray, *cost};
    RenderOptions quiet = render_options;
    quiet.show_progress = false;
    Image counts = render_image(counting, quiet).image;
    double max = 0, sum = 0;
    for (int y = 0; y < counts.height(); ++y)
        for (int x = 0; x < counts.width(); ++x) {
            max = std::max(max, counts.at(x, y).r);
            sum += counts.at(x, y).r;
        }
    write_png(bvh_cost_heat_map(counts, max), options.bvh_depth_image);
    char line[160];
    std::snprintf(line, sizeof line, "nodes visited per camera ray: mean %.1f, max %.0f (white)",
                  sum / double(counts.pixel_count()), max);
    std::cout << program << ": wrote " << options.bvh_depth_image << ": " << line << "\n";
    if (max == 0)
        std::cout << program << ": note: only the reference BVH counts the nodes it visits (accelerator '"
                  << context.accelerator.info().name << "')\n";
}

int run(const std::vector<std::string>& args, const std::string& program, StageSet default_student) {
    Options options = parse_options(args, default_student);
    if (options.help) {
        std::cout << usage(program, default_student);
        return kExitOk;
    }
    PhaseSeconds seconds;
    Timer timer;
    Scene scene = load_scene(options.scene_path);
    apply_scene_overrides(scene, options);
    if (options.output.empty()) options.output = scene.name + ".png";
    check_outputs(options, scene);
    seconds.load = timer.seconds();

    Stages stages = make_stages(options.student, options.triangle_test == "watertight" ? TriangleTest::watertight
                                                                                      : TriangleTest::moller);
    Effects effects = analyze_effects(scene, options.render);
    std::string reason;
    IntegratorKind kind = choose_integrator(scene, effects, options.render, &reason, options.student);
    std::unique_ptr<Integrator> integrator = make_integrator(kind);
    if (!options.bdpt_strategies.empty()) {
        // --bdpt-strategies: BDPT's per-strategy images (render/bdpt_strategies.h).
        if (kind != IntegratorKind::bdpt)
            throw InputError("--bdpt-strategies: needs --integrator bdpt (the integrator is " +
                             std::string(to_string(kind)) + ")");
        std::error_code ec;
        std::filesystem::create_directories(options.bdpt_strategies, ec);
        if (ec || !std::filesystem::is_directory(options.bdpt_strategies))
            throw InputError("--bdpt-strategies: cannot create the folder '" + options.bdpt_strategies + "'");
        options.render.bdpt_strategy_depth =
            options.bdpt_strategy_depth >= 0 ? options.bdpt_strategy_depth : std::min(options.render.max_depth, 3);
    }
    CodePaths code_paths = plan_code_paths(scene, effects, options.render);
    if (options.student.contains(Stage::adaptive) && !options.render.adaptive)
        std::cout << program << ": note: adaptive sampling is off; add -a N TOL to run your has_converged\n";
    std::cout << program << ": " << scene.path << ": " << scene.triangles.size() << " triangles, "
              << scene.spheres.size() << " spheres, " << scene.emitters.size() << " emitters\n"
              << program << ": student stages: " << options.student.to_string() << "\n"
              << program << ": sampler: " << to_string(options.render.sampler)
              << (options.render.adaptive ? std::string(", adaptive rule ") + to_string(options.render.adaptive_rule) : "")
              << "\n"
              << program << ": effects: " << effects.to_string() << "\n"
              << program << ": integrator: "
              << (options.bvh_view ? std::string("bvh view (--bvh-view)")
                                   : std::string(to_string(kind)) + " (" + reason + ")") << "\n"
              << program << ": skipped: " << skipped_code_paths(code_paths) << "\n";
    std::string note = options.bvh_view ? "" : integrator_note(kind, scene, options.render);
    if (!note.empty()) std::cout << program << ": note: " << note << "\n";

    timer.reset();
    // --bvh-view walks L/R paths of the binary tree: keep the BVH binary.
    AcceleratorSettings accel_settings = options.accelerator;
    if (options.bvh_view) accel_settings.width = 2;
    std::unique_ptr<Accelerator> accelerator = build_accelerator(scene, stages, accel_settings);
    seconds.build = timer.seconds();
    if (options.bvh_view) {
        // The BVH view replaces the integrator (render/bvh_view.h).
        BvhNodeView node = select_bvh_node(*accelerator, *options.bvh_view);
        integrator = make_bvh_view_integrator(scene, node, scene.film_height);
        std::cout << program << ": bvh view: node '" << *options.bvh_view << "' (" << (node.leaf ? "leaf, " : "")
                  << node.primitives.size() << " of " << scene.primitive_count() << " primitives)\n";
    }

    RenderContext context{scene, *accelerator, stages, options.render, *integrator};
    RenderOptions render_options;
    render_options.threads = options.threads;
    render_options.show_progress = !options.quiet && Progress::stderr_is_terminal();
    render_options.cell = options.cell;
    render_options.packets = options.packets;
    RenderResult result = render_image(context, render_options);
    seconds.render = result.seconds;

    // The PNG shows the display transform (--tonemap, --exposure); EXR and
    // PFM keep the linear radiance.
    if (file_extension(options.output) == ".exr") write_exr(result.image, options.output);
    else write_png(options.display.is_identity() ? result.image : tone_map(result.image, options.display), options.output);
    if (!options.hdr_output.empty()) write_image(result.image, options.hdr_output);
    std::string written = options.output;
    if (options.render.adaptive) {
        std::string rate_path = rate_image_path(options.output);
        if (file_extension(rate_path) != ".png") rate_path = rate_path.substr(0, rate_path.size() - 4) + ".png";
        write_png(make_sample_rate_image(result.sample_counts, scene.film_width, scene.film_height), rate_path);
        written += ", " + rate_path;
    }
    if (!options.hdr_output.empty()) written += ", " + options.hdr_output;
    if (!options.bdpt_strategies.empty()) {
        write_strategy_images(result.layers, options.render.bdpt_strategy_depth, options.bdpt_strategies);
        written += ", " + options.bdpt_strategies + "/";
    }
    AcceleratorInfo accel_info = accelerator->info();
    if (!options.stats_output.empty())
        write_stats(options.stats_output, program, options, scene, effects, code_paths, kind, accel_info, result,
                    seconds);

    const RayCounters& c = result.counters;
    double rays = double(std::max<uint64_t>(c.rays(), 1));
    char line[256];
    double pixels = double(options.cell ? uint64_t(options.cell->width) * options.cell->height
                                        : uint64_t(scene.film_width) * scene.film_height);
    std::snprintf(line, sizeof line, "%dx%d, %.4g spp, %.2f s, %.2f Mrays/s, %.1f tests/ray", scene.film_width,
                  scene.film_height, c.camera_rays / pixels, seconds.render,
                  seconds.render > 0 ? c.rays() / seconds.render * 1e-6 : 0.0, c.primitive_tests / rays);
    std::cout << program << ": wrote " << written << "\n" << program << ": " << line << "\n";
    if (c.nonfinite_samples > 0)
        std::cout << program << ": warning: " << c.nonfinite_samples << " NaN/Inf samples were dropped\n";
    if (!options.cell && scene.has_lights() && every_pixel_black(result.image))
        std::cout << program << ": warning: every pixel is black although the scene has lights: the camera may "
                  << "see only the backs of surfaces or the outside of a closed box (check the camera, -m, "
                  << "or the direction of the mesh's normals)\n";
    if (c.clamped_samples > 0)
        std::cout << program << ": note: --clamp scaled down " << c.clamped_samples
                  << " samples (biased: the image is darker than the true mean)\n";
    if (!options.bvh_depth_image.empty()) write_bvh_depth_image(context, render_options, options, program);
    return kExitOk;
}

}  // namespace

int run_render_app(int argc, char** argv, const std::string& program, StageSet default_student) {
    std::vector<std::string> args(argv + 1, argv + argc);
    try {
        return run(args, program, default_student);
    } catch (const InputError& e) {
        std::cerr << program << ": error: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const NotImplemented& e) {
        std::cerr << program << ": " << e.what() << " (no image written)\n";
        return kExitNotImplemented;
    } catch (const std::exception& e) {
        std::cerr << program << ": internal error: " << e.what() << "\n";
        return kExitFailure;
    }
}

}  // namespace pt
