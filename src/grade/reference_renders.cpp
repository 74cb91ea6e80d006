#include "grade/reference_renders.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>

#include <nettle/sha2.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/image_io.h"

namespace pt {
namespace {

// Renders made in this process, by (fingerprint, spp, seed): the reference
// code cannot change while the process runs.
std::mutex memo_mutex;
std::map<std::string, Image>& memo() {
    static std::map<std::string, Image> m;
    return m;
}

Image render_reference(const Scene& scene, const ImageCase& c, const GradeEnvironment& env,
                       const std::string& fingerprint, int spp, uint64_t seed) {
    std::string key = fingerprint + "/" + std::to_string(spp) + "/" + std::to_string(seed);
    {
        std::lock_guard<std::mutex> lock(memo_mutex);
        auto it = memo().find(key);
        if (it != memo().end()) return it->second;
    }
    Image image = render_case(scene, c, env.reference, spp, seed, env.threads).image;
    std::lock_guard<std::mutex> lock(memo_mutex);
    memo()[key] = image;
    return image;
}

constexpr int kBatches = 64;

struct Converged {
    Image mean, sample_variance;
    int spp = 0;
};

/// The converged image as the mean of batches, and the per-sample variance
/// from the spread of the batch means (reference_renders.h).
Converged render_converged(const Scene& scene, const ImageCase& case_in,
                           const GradeEnvironment& env) {
    // Without adaptive sampling: every batch takes all its samples, so the
    // mean is unbiased and the spread of the batch means is the per-sample variance.
    ImageCase c = case_in;
    c.settings.adaptive = false;
    const int batches = std::min(kBatches, c.converged_spp);
    const int batch_spp = c.converged_spp / batches;
    std::vector<Image> parts;
    for (int b = 0; b < batches; ++b)
        parts.push_back(render_case(scene, c, env.reference, batch_spp,
                                    kConvergedSeed + uint64_t(b), env.threads)
                            .image);
    Converged out;
    out.spp = batches * batch_spp;
    out.mean = Image(c.width, c.height);
    out.sample_variance = Image(c.width, c.height);
    std::vector<float>& mean = out.mean.data();
    std::vector<float>& var = out.sample_variance.data();
    for (size_t i = 0; i < mean.size(); ++i) {
        double sum = 0, sum2 = 0;
        for (const Image& p : parts)
            sum += p.data()[i];
        double m = sum / batches;
        for (const Image& p : parts)
            sum2 += (p.data()[i] - m) * (p.data()[i] - m);
        mean[i] = float(m);
        var[i] = batches > 1 ? float(sum2 / (batches - 1) * batch_spp) : 0.f;
    }
    return out;
}

bool identical(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() && a.data() == b.data();
}

std::optional<Image> try_read(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return std::nullopt;
    try {
        return read_pfm(path);
    } catch (const InputError&) {
        return std::nullopt;  // a damaged cache file is rendered again
    }
}

/// Writes through a temporary file and a rename, so that concurrent graders
/// (ctest -j) never read a half-written cache file.
void write_atomically(const Image& image, const std::string& path) {
    std::string tmp = path + ".tmp" + std::to_string(getpid());
    write_pfm(image, tmp);
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) std::filesystem::remove(tmp, ec);
}

/// SHA-256 (nettle) of the entry's three images, in hex: recorded when the
/// entry is made, checked whenever it is read, so that a damaged or
/// tampered entry is rendered again.
std::string content_hash(const Image& mean, const Image& variance, const Image& witness) {
    sha256_ctx ctx;
    sha256_init(&ctx);
    for (const Image* image : {&mean, &variance, &witness}) {
        const int32_t size[2] = {image->width(), image->height()};
        sha256_update(&ctx, sizeof size, reinterpret_cast<const uint8_t*>(size));
        sha256_update(&ctx, image->data().size() * sizeof(float),
                      reinterpret_cast<const uint8_t*>(image->data().data()));
    }
    uint8_t digest[SHA256_DIGEST_SIZE];
    sha256_digest(&ctx, sizeof digest, digest);
    std::string hex;
    char byte[3];
    for (uint8_t b : digest) {
        std::snprintf(byte, sizeof byte, "%02x", b);
        hex += byte;
    }
    return hex;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return text.substr(0, 64);
}

std::string stem_of(const std::string& path) {
    return std::filesystem::path(path).stem().string();
}

/// The converged image and its variance from the disk cache when the
/// witness proves them current, else rendered (and cached).
Converged converged_from_cache(const Scene& scene, const ImageCase& c, const GradeEnvironment& env,
                               const std::string& fingerprint, bool* from_cache) {
    std::error_code ec;
    std::filesystem::create_directories(env.cache_dir, ec);
    if (!std::filesystem::is_directory(env.cache_dir))
        throw InputError("--cache: cannot create the folder " + env.cache_dir);
    char name[64];
    std::snprintf(name, sizeof name, "-%s-c%d", case_fingerprint(c, env.assets_dir).c_str(),
                  c.converged_spp);
    std::string base = env.cache_dir + "/" + stem_of(c.scene) + name;
    Image witness = render_reference(scene, c, env, fingerprint, 2, kConvergedSeed - 1);
    std::optional<Image> cached_witness = try_read(base + "-witness.pfm");
    std::optional<Image> cached = try_read(base + ".pfm");
    std::optional<Image> cached_variance = try_read(base + "-variance.pfm");
    if (cached && cached_variance && cached_witness && identical(*cached_witness, witness) &&
        cached->width() == c.width && cached->height() == c.height &&
        cached_variance->width() == c.width && cached_variance->height() == c.height &&
        read_text(base + ".sha256") == content_hash(*cached, *cached_variance, *cached_witness)) {
        const int batches = std::min(kBatches, c.converged_spp);
        *from_cache = true;
        return Converged{*cached, *cached_variance, batches * (c.converged_spp / batches)};
    }
    Converged conv = render_converged(scene, c, env);
    // The witness last: a reader that finds it current finds the images current too.
    write_atomically(conv.mean, base + ".pfm");
    write_atomically(conv.sample_variance, base + "-variance.pfm");
    write_atomically(witness, base + "-witness.pfm");
    // The hash last: a reader that finds it matching finds the images complete.
    write_file_atomically(base + ".sha256", content_hash(conv.mean, conv.sample_variance, witness));
    return conv;
}

std::map<std::string, Converged>& converged_memo() {
    static std::map<std::string, Converged> m;
    return m;
}

}  // namespace

ReferenceRenders reference_renders(const Scene& scene, const ImageCase& c, int runs,
                                   const GradeEnvironment& env) {
    std::string fingerprint = case_fingerprint(c, env.assets_dir) + "-" + kReferenceCacheVersion;
    ReferenceRenders r;
    for (int i = 0; i < runs; ++i)
        r.runs.push_back(
            render_reference(scene, c, env, fingerprint, c.settings.spp, kReferenceRunSeed + i));

    std::string key = fingerprint + "/converged/" + std::to_string(c.converged_spp);
    std::optional<Converged> conv;
    {
        std::lock_guard<std::mutex> lock(memo_mutex);
        auto it = converged_memo().find(key);
        if (it != converged_memo().end()) conv = it->second;
    }
    if (!conv) {
        conv = env.cache_dir.empty()
                   ? render_converged(scene, c, env)
                   : converged_from_cache(scene, c, env, fingerprint, &r.from_cache);
        std::lock_guard<std::mutex> lock(memo_mutex);
        converged_memo()[key] = *conv;
    }
    r.converged = conv->mean;
    r.sample_variance = conv->sample_variance;
    r.converged_spp = conv->spp;
    return r;
}

void forget_converged_in_memory() {
    std::lock_guard<std::mutex> lock(memo_mutex);
    converged_memo().clear();
}

}  // namespace pt
