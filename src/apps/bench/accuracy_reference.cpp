#include "apps/bench/accuracy_reference.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/timer.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "stages/effects.h"
#include "scene/scene.h"

namespace pt::bench {
namespace {

namespace fs = std::filesystem;

/// Seeds of the reference passes and of the witness: far from the small
/// seeds of the sweep, so that no render shares a random stream with them.
constexpr uint64_t kReferenceSeed = 0xACC0000000ull;
constexpr uint64_t kWitnessSeed = kReferenceSeed - 1;
constexpr int kMaxPasses = 16;

/// FNV-1a, 64 bits: a fingerprint, not a cryptographic hash.
uint64_t fnv1a(const void* data, size_t size, uint64_t h = 0xcbf29ce484222325ull) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i)
        h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string settings_in_words(const RenderSettings& s, IntegratorKind integrator) {
    std::ostringstream out;
    out << to_string(integrator) << ", -m " << s.max_depth << " -o " << s.accumulate_bounces
        << " -l " << s.light_samples << ", --direct " << to_string(s.direct) << ", --sampler "
        << to_string(s.sampler);
    return out.str();
}

/// One render of `spp` samples with `seed`, with the BVH.
Image render_pass(const Scene& scene, const RenderSettings& base, IntegratorKind kind, int spp,
                  uint64_t seed, int threads) {
    Stages stages = make_stages(StageSet::none());
    std::unique_ptr<Accelerator> accelerator =
        build_accelerator(scene, stages, AcceleratorSettings{});
    std::unique_ptr<Integrator> integrator = make_integrator(kind);
    RenderSettings settings = base;
    settings.spp = spp;
    settings.seed = seed;
    RenderContext context{scene, *accelerator, stages, settings, *integrator};
    RenderOptions options;
    options.threads = threads;
    return render_image(context, options).image;
}

std::optional<Image> try_read_pfm(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return std::nullopt;
    try {
        return read_pfm(path);
    } catch (const InputError&) {
        return std::nullopt;  // a damaged cache file is rendered anew
    }
}

/// The mean of the passes, and the estimated relMSE of that mean (file comment).
Reference render_reference(const Scene& scene, const RenderSettings& settings, IntegratorKind kind,
                           int spp, int threads, std::ostream& log) {
    const int passes = std::max(1, std::min(kMaxPasses, spp / 2));
    const int pass_spp = spp / passes;
    Reference r;
    r.spp = passes * pass_spp;
    const size_t n = size_t(scene.film_width) * scene.film_height * 3;
    std::vector<double> sum(n, 0.0), sum_squares(n, 0.0);
    Timer timer;
    double last_line = 0;
    for (int p = 0; p < passes; ++p) {
        Image pass = render_pass(scene, settings, kind, pass_spp, kReferenceSeed + p, threads);
        for (size_t i = 0; i < n; ++i) {
            sum[i] += pass.data()[i];
            sum_squares[i] += double(pass.data()[i]) * pass.data()[i];
        }
        // A progress line every few seconds, and at the end.
        r.seconds = timer.seconds();
        if (p + 1 < passes && r.seconds < last_line + 5) continue;
        last_line = r.seconds;
        char line[160];
        std::snprintf(line, sizeof line,
                      "bench accuracy: reference: %d of %d spp, %.1f s, about %.0f s to go\n",
                      (p + 1) * pass_spp, r.spp, r.seconds, r.seconds / (p + 1) * (passes - p - 1));
        log << line << std::flush;
    }
    r.image = Image(scene.film_width, scene.film_height);
    double relative_error = 0;
    for (size_t i = 0; i < n; ++i) {
        const double mean = sum[i] / passes;
        r.image.data()[i] = float(mean);
        if (passes > 1) {
            const double pass_variance =
                std::max(0.0, (sum_squares[i] - passes * mean * mean) / (passes - 1));
            relative_error += pass_variance / passes / (mean * mean + kRelMseEpsilon);
        }
    }
    r.own_relmse = passes > 1 ? relative_error / double(n) : -1;
    return r;
}

}  // namespace

Reference converged_reference(const Scene& scene, const RenderSettings& base, int spp, int threads,
                              const std::string& cache_dir, std::ostream& log) {
    RenderSettings settings = base;
    settings.direct = DirectStrategy::mis;
    settings.adaptive = false;
    // The sampler of the smallest error (docs/sampling.md): its passes are
    // independent randomisations, so their spread still measures its error.
    settings.sampler = SamplerKind::zsobol;
    const IntegratorKind kind =
        choose_integrator(scene, analyze_effects(scene, settings), settings, nullptr);
    const std::string words = settings_in_words(settings, kind);
    if (cache_dir.empty()) {
        Reference r = render_reference(scene, settings, kind, spp, threads, log);
        r.source = "rendered";
        r.settings = words;
        return r;
    }

    // The fingerprint (file comment).
    std::ostringstream key;
    key << kAccuracyCacheVersion << "|" << fs::weakly_canonical(scene.path).string() << "|"
        << scene.film_width << "x" << scene.film_height << "|" << words << "|" << spp;
    const std::string scene_bytes = read_bytes(scene.path);
    uint64_t h = fnv1a(key.str().data(), key.str().size());
    h = fnv1a(scene_bytes.data(), scene_bytes.size(), h);
    h = fnv1a(scene.positions.data(), scene.positions.size() * sizeof(Vec3), h);
    char name[32];
    std::snprintf(name, sizeof name, "-%016llx", (unsigned long long)h);
    std::error_code ec;
    fs::create_directories(cache_dir, ec);
    if (!fs::is_directory(cache_dir))
        throw InputError("accuracy: --cache: cannot create the folder " + cache_dir);
    const std::string base_path = cache_dir + "/" + scene.name + name;

    const Image witness = render_pass(scene, settings, kind, 2, kWitnessSeed, threads);
    std::optional<Image> cached_witness = try_read_pfm(base_path + "-witness.pfm");
    std::optional<Image> cached = try_read_pfm(base_path + ".pfm");
    if (cached && cached_witness && cached_witness->data() == witness.data() &&
        cached->width() == scene.film_width && cached->height() == scene.film_height) {
        Reference r = read_reference(base_path + ".pfm", scene.film_width, scene.film_height);
        r.source = "cache";
        r.settings = words;
        log << "bench accuracy: reference: " << r.spp << " spp from the cache, " << r.path << "\n";
        return r;
    }
    if (cached) log << "bench accuracy: reference: the cached one is out of date; rendering anew\n";

    Reference r = render_reference(scene, settings, kind, spp, threads, log);
    r.source = "rendered";
    r.settings = words;
    r.path = base_path + ".pfm";
    nlohmann::json sidecar = {{"version", kAccuracyCacheVersion},
                              {"scene", scene.path},
                              {"width", scene.film_width},
                              {"height", scene.film_height},
                              {"spp", r.spp},
                              {"seconds", r.seconds},
                              {"threads", threads},
                              {"own_relmse", r.own_relmse},
                              {"settings", words}};
    // The witness last: a reader that finds it current finds the rest current too.
    // Each write is atomic (core/atomic_file.h): a reader never sees half a file.
    write_pfm(r.image, base_path + ".pfm");
    write_file_atomically(base_path + ".json", sidecar.dump(2) + "\n");
    write_pfm(witness, base_path + "-witness.pfm");
    return r;
}

Reference read_reference(const std::string& path, int width, int height) {
    Reference r;
    r.image = read_pfm(path);  // InputError naming the file when it cannot be read
    if (r.image.width() != width || r.image.height() != height)
        throw InputError("accuracy: --reference: " + path + " is " +
                         std::to_string(r.image.width()) + "x" + std::to_string(r.image.height()) +
                         ", expected " + std::to_string(width) + "x" + std::to_string(height) +
                         " (the size of the renders, -r)");
    r.source = "file";
    r.path = path;
    std::string sidecar_path = path.substr(0, path.size() - file_extension(path).size()) + ".json";
    std::ifstream in(sidecar_path);
    if (in) {
        nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        if (j.is_object()) {
            r.spp = j.value("spp", 0);
            r.seconds = j.value("seconds", 0.0);
            r.own_relmse = j.value("own_relmse", -1.0);
            r.settings = j.value("settings", std::string());
        }
    }
    return r;
}

}  // namespace pt::bench
