#include "grade/image_case.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "scene/scene_loader.h"

namespace pt {
namespace {

using nlohmann::json;

int positive_int(const json& j, const std::string& key, const std::string& where) {
    if (!j[key].is_number_integer() || j[key].get<long long>() < 1 ||
        j[key].get<long long>() > 1 << 20)
        throw InputError(where + "." + key + ": expected a positive integer, got " + j[key].dump());
    return j[key].get<int>();
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "";
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string directory_of(const std::string& path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : path.substr(0, slash);
}

/// The text of an OBJ file and of the MTL files it names.
std::string obj_with_materials(const std::string& path) {
    std::string text = read_text(path);
    std::istringstream lines(text);
    std::string line, all = text;
    while (std::getline(lines, line)) {
        if (line.rfind("mtllib ", 0) == 0)
            all += read_text(directory_of(path) + "/" + line.substr(7));
    }
    return all;
}

uint64_t fnv1a(const std::string& s, uint64_t h = 1469598103934665603ull) {
    for (unsigned char c : s)
        h = (h ^ c) * 1099511628211ull;
    return h;
}

/// Photon mapping's keys (Part 8): "photons", "caustic_photons", "knn"
/// (0: fixed radius), "radius", "photon_kernel", "photon_view" and
/// "photon_seed" (required with pm: one photon map for every render, so
/// that renders differ only by camera noise and the noise rule applies).
void parse_photon_keys(const json& j, ImageCase& c, const std::string& where) {
    PhotonSettings& ps = c.settings.photon;
    const bool pm = c.settings.integrator == IntegratorKind::pm;
    for (const char* k :
         {"photons", "caustic_photons", "knn", "radius", "photon_kernel", "photon_view", "photon_seed"})
        if (j.contains(k) && !pm)
            throw InputError(where + "." + k + ": applies only to \"integrator\": \"pm\"");
    if (!pm) return;
    if (!j.contains("photon_seed") || !j["photon_seed"].is_number_integer() ||
        j["photon_seed"].get<long long>() < 0)
        throw InputError(where + ".photon_seed: expected a non-negative integer (pm needs one photon map "
                         "for every render)");
    ps.fixed_seed = true;
    ps.seed = j["photon_seed"].get<uint64_t>();
    if (j.contains("photons")) ps.photons = uint64_t(positive_int(j, "photons", where));
    if (j.contains("caustic_photons")) ps.caustic_photons = uint64_t(positive_int(j, "caustic_photons", where));
    if (j.contains("knn")) {
        if (!j["knn"].is_number_integer() || j["knn"].get<long long>() < 0 || j["knn"].get<long long>() > 100000)
            throw InputError(where + ".knn: expected an integer from 0 to 100000");
        ps.knn = j["knn"].get<int>();
    }
    if (j.contains("radius")) {
        if (!j["radius"].is_number() || !(j["radius"].get<double>() > 0))
            throw InputError(where + ".radius: expected a positive number");
        ps.radius = j["radius"].get<double>();
    }
    if (j.contains("photon_kernel")) {
        std::string k = j["photon_kernel"].is_string() ? j["photon_kernel"].get<std::string>() : "";
        bool ok = false;
        for (PhotonKernel x : {PhotonKernel::box, PhotonKernel::cone, PhotonKernel::epanechnikov})
            if (k == to_string(x)) ps.kernel = x, ok = true;
        if (!ok) throw InputError(where + ".photon_kernel: expected box, cone or epanechnikov");
    }
    if (j.contains("photon_view")) {
        std::string v = j["photon_view"].is_string() ? j["photon_view"].get<std::string>() : "";
        bool ok = false;
        for (PhotonView x : {PhotonView::none, PhotonView::caustic, PhotonView::global})
            if (v == to_string(x)) ps.view = x, ok = true;
        if (!ok) throw InputError(where + ".photon_view: expected none, caustic or global");
    }
}

}  // namespace

ImageCase parse_image_case(const json& j, const std::string& where) {
    if (!j.is_object()) throw InputError(where + ": expected an object");
    const std::set<std::string> keys = {"label",
                                        "scene",
                                        "integrator",
                                        "width",
                                        "height",
                                        "spp",
                                        "converged_spp",
                                        "light_samples",
                                        "max_depth",
                                        "direct",
                                        "mis_heuristic",
                                        "accumulate_bounces",
                                        "max_mean_spp",
                                        "bias_spp",
                                        "samples_per_batch",
                                        "max_tolerance",
                                        "russian_roulette",
                                        "rr_depth",
                                        "sampler",
                                        "photons",
                                        "caustic_photons",
                                        "knn",
                                        "radius",
                                        "photon_kernel",
                                        "photon_view",
                                        "photon_seed"};
    for (auto it = j.begin(); it != j.end(); ++it)
        if (!keys.count(it.key())) throw InputError(where + ": unknown key \"" + it.key() + "\"");
    for (const char* k : {"scene", "integrator", "spp"})
        if (!j.contains(k)) throw InputError(where + ": missing \"" + std::string(k) + "\"");
    ImageCase c;
    if (!j["scene"].is_string()) throw InputError(where + ".scene: expected a path");
    c.scene = j["scene"].get<std::string>();
    c.label = j.value("label", c.scene);
    std::string kind = j["integrator"].is_string() ? j["integrator"].get<std::string>() : "";
    bool found = false;
    for (IntegratorKind k :
         {IntegratorKind::normals, IntegratorKind::depth, IntegratorKind::whitted,
          IntegratorKind::direct, IntegratorKind::path, IntegratorKind::pm, IntegratorKind::volpath,
          IntegratorKind::bdpt})
        if (kind == to_string(k)) c.settings.integrator = k, found = true;
    if (!found)
        throw InputError(where +
                         ".integrator: expected normals, depth, whitted, direct, path, pm, volpath or bdpt");
    c.settings.spp = positive_int(j, "spp", where);
    if (j.contains("width")) c.width = positive_int(j, "width", where);
    if (j.contains("height")) c.height = positive_int(j, "height", where);
    c.converged_spp = j.contains("converged_spp") ? positive_int(j, "converged_spp", where) : 1024;
    if (c.converged_spp != c.settings.spp && c.converged_spp < 64)
        throw InputError(
            where +
            ".converged_spp: expected at least 64 (the variance comes from 64 batches), or "
            "equal to spp for a render without noise");
    if (j.contains("bias_spp")) {
        c.bias_spp = positive_int(j, "bias_spp", where);
    } else {
        c.bias_spp = c.settings.spp == c.converged_spp
                         ? c.settings.spp
                         : std::min(16 * c.settings.spp, c.converged_spp);
    }
    if (j.contains("light_samples"))
        c.settings.light_samples = positive_int(j, "light_samples", where);
    if (j.contains("max_depth")) {  // 0: emission only (zero_bounce_radiance)
        if (!j["max_depth"].is_number_integer() || j["max_depth"].get<long long>() < 0 ||
            j["max_depth"].get<long long>() > 1000)
            throw InputError(where + ".max_depth: expected an integer from 0 to 1000, got " +
                             j["max_depth"].dump());
        c.settings.max_depth = j["max_depth"].get<int>();
    }
    if (j.contains("accumulate_bounces")) {
        if (!j["accumulate_bounces"].is_boolean())
            throw InputError(where + ".accumulate_bounces: expected true or false");
        c.settings.accumulate_bounces = j["accumulate_bounces"].get<bool>();
    }
    if (j.contains("russian_roulette")) {  // --rr-depth off
        if (!j["russian_roulette"].is_boolean())
            throw InputError(where + ".russian_roulette: expected true or false");
        c.settings.russian_roulette = j["russian_roulette"].get<bool>();
    }
    if (j.contains("rr_depth")) {  // --rr-depth N: roulette after N bounces
        if (!j["rr_depth"].is_number_integer() || j["rr_depth"].get<long long>() < 0 ||
            j["rr_depth"].get<long long>() > 100000)
            throw InputError(where + ".rr_depth: expected an integer from 0 to 100000, got " +
                             j["rr_depth"].dump());
        if (!c.settings.russian_roulette)
            throw InputError(where + ".rr_depth: has no effect with \"russian_roulette\": false");
        c.settings.rr_depth = j["rr_depth"].get<int>();
    }
    if (j.contains("direct")) {
        std::string d = j["direct"].is_string() ? j["direct"].get<std::string>() : "";
        found = false;
        for (DirectStrategy s :
             {DirectStrategy::light, DirectStrategy::hemisphere, DirectStrategy::mis})
            if (d == to_string(s)) c.settings.direct = s, found = true;
        if (!found) throw InputError(where + ".direct: expected light, hemisphere or mis");
    }
    if (j.contains("mis_heuristic")) {  // --mis-heuristic
        std::string h = j["mis_heuristic"].is_string() ? j["mis_heuristic"].get<std::string>() : "";
        if (h != "power" && h != "balance")
            throw InputError(where + ".mis_heuristic: expected power or balance");
        c.settings.mis_heuristic = h == "power" ? MisHeuristic::power : MisHeuristic::balance;
    }
    if (j.contains("sampler")) {  // --sampler (Part 6)
        if (!j["sampler"].is_string()) throw InputError(where + ".sampler: expected a sampler name");
        c.settings.sampler = parse_sampler_kind(j["sampler"].get<std::string>(), where + ".sampler");
    }
    parse_photon_keys(j, c, where);
    if (j.contains("max_mean_spp")) {
        if (!j["max_mean_spp"].is_number())
            throw InputError(where + ".max_mean_spp: expected a number");
        c.max_mean_spp = j["max_mean_spp"].get<double>();
        c.settings.adaptive = true;
    }
    if (j.contains("samples_per_batch") || j.contains("max_tolerance")) {
        if (!c.max_mean_spp)
            throw InputError(where +
                             ": samples_per_batch and max_tolerance need max_mean_spp (adaptive "
                             "sampling)");
        if (j.contains("samples_per_batch"))
            c.settings.samples_per_batch = positive_int(j, "samples_per_batch", where);
        if (j.contains("max_tolerance")) {
            if (!j["max_tolerance"].is_number() || !(j["max_tolerance"].get<double>() > 0))
                throw InputError(where + ".max_tolerance: expected a positive number");
            c.settings.max_tolerance = j["max_tolerance"].get<double>();
        }
    }
    return c;
}

Scene load_case_scene(const ImageCase& c, const std::string& assets_dir) {
    Scene scene = load_scene(assets_dir + "/" + c.scene);
    scene.film_width = c.width;
    scene.film_height = c.height;
    scene.camera.aspect = double(c.width) / c.height;
    scene.camera.finalize(scene.path + ": camera");
    return scene;
}

std::string case_fingerprint(const ImageCase& c, const std::string& assets_dir) {
    std::string path = assets_dir + "/" + c.scene;
    std::string text = read_text(path);
    if (text.empty()) throw InputError("cannot read scene " + path);
    std::string inputs = text;
    if (path.size() > 4 && path.substr(path.size() - 4) == ".obj") {
        inputs = obj_with_materials(path);
    } else {
        try {
            json scene = json::parse(text);
            for (const json& o : scene.value("objects", json::array()))
                if (o.contains("file") && o["file"].is_string())
                    inputs +=
                        obj_with_materials(directory_of(path) + "/" + o["file"].get<std::string>());
        } catch (const json::exception&) {
            // load_case_scene reports malformed scenes with their JSON path.
        }
    }
    std::ostringstream settings;
    const RenderSettings& s = c.settings;
    settings << c.width << "x" << c.height << " " << to_string(s.integrator) << " l"
             << s.light_samples << " m" << s.max_depth << " o" << s.accumulate_bounces << " "
             << to_string(s.direct) << " a" << s.adaptive << " " << s.samples_per_batch << " "
             << s.max_tolerance;
    // Roulette only when it differs from the default (on, --rr-depth 3), so
    // that the fingerprints, and the caches, of older cases stay valid.
    if (!s.russian_roulette)
        settings << " rr-off";
    else if (s.rr_depth != RenderSettings{}.rr_depth)
        settings << " rr" << s.rr_depth;
    if (s.mis_heuristic != MisHeuristic::power) settings << " " << to_string(s.mis_heuristic);
    // Parts 6 and 8 likewise: only what differs from the defaults.
    if (s.sampler != SamplerKind::independent) settings << " sampler " << to_string(s.sampler);
    if (s.integrator == IntegratorKind::pm) {
        const PhotonSettings& ps = s.photon;
        settings << " photons " << ps.photons << " " << ps.caustic_photons << " knn " << ps.knn
                 << " r " << ps.radius << " " << to_string(ps.kernel) << " " << to_string(ps.view)
                 << " seed " << ps.seed;
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  (unsigned long long)fnv1a(settings.str(), fnv1a(inputs)));
    return hex;
}

RenderResult render_case(const Scene& scene, const ImageCase& c, const Stages& stages, int spp,
                         uint64_t seed, int threads) {
    RenderSettings settings = c.settings;
    settings.spp = spp;
    settings.seed = seed;
    std::unique_ptr<Integrator> integrator = make_integrator(settings.integrator);
    std::unique_ptr<Accelerator> accelerator =
        build_accelerator(scene, stages, AcceleratorSettings{});
    RenderContext context{scene, *accelerator, stages, settings, *integrator};
    RenderOptions options;
    options.threads = threads;
    return render_image(context, options);
}

}  // namespace pt
