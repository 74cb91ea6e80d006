// direct_compare: what accuracy costs, for docs/direct.md. Not a test.
//
//   direct_compare SCENE.json REFERENCE.pfm OUT_PREFIX [--size N] [--budget SECONDS] [--threads T]
//                  [--crop X Y SIZE] [--sequence-pngs 0|1]
//
// PNGs are crops (--crop, default the whole image) at the rendered
// resolution, so they show the true per-pixel noise; relMSE is always over
// the whole image.
//
// 1. Equal time: for each strategy (hemisphere, light, mis), renders passes
//    of -s 2 -l 1 with seeds 1, 2, 3, ... and averages them until the time
//    budget is spent; prints relMSE against REFERENCE.pfm (a converged
//    render of the same scene, size and -m 1) and writes
//    OUT_PREFIX_equal_time_<strategy>.png. (-s 2, not 1: with -s 1 every
//    camera ray goes through the pixel centre, so averaging passes converges
//    to a point-sampled image, not to the pixel averages of the reference.)
// 2. Equal samples: each strategy at -s 2 -l 8, relMSE and time.
// 3. The course sequence: light sampling at -s 1 -l 1, 4, 16, 64 (one render
//    each, seed 1): time, rays and relMSE; writes OUT_PREFIX_l<N>.png.
// Output is a Markdown table per part.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "apps/number_flags.h"
#include "core/error.h"
#include "core/timer.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"

using namespace pt;

namespace {

struct Setup {
    Scene scene;
    Stages stages = make_stages(StageSet::none());
    std::unique_ptr<Accelerator> accelerator;
    std::unique_ptr<Integrator> integrator = make_integrator(IntegratorKind::direct);
    int threads = 2;
};

struct Outcome {
    Image image;
    double seconds = 0;
    uint64_t rays = 0;
    int passes = 0;
};

/// Averages passes of (spp, light_samples) with seeds 1, 2, ... until `budget`
/// seconds are spent (at least one pass), or exactly `passes` passes if > 0.
Outcome render_passes(const Setup& s, DirectStrategy strategy, int spp, int light_samples,
                      double budget, int passes = 0) {
    RenderSettings settings;
    settings.direct = strategy;
    settings.spp = spp;
    settings.light_samples = light_samples;
    settings.max_depth = 1;
    RenderOptions options;
    options.threads = s.threads;
    Outcome out;
    out.image = Image(s.scene.film_width, s.scene.film_height);
    Timer timer;
    while (passes > 0 ? out.passes < passes : (out.passes == 0 || timer.seconds() < budget)) {
        settings.seed = uint64_t(out.passes + 1);
        RenderContext context{s.scene, *s.accelerator, s.stages, settings, *s.integrator};
        RenderResult r = render_image(context, options);
        for (size_t i = 0; i < r.image.data().size(); ++i)
            out.image.data()[i] += r.image.data()[i];
        out.rays += r.counters.rays();
        ++out.passes;
    }
    out.seconds = timer.seconds();
    for (float& v : out.image.data())
        v /= float(out.passes);
    return out;
}

/// The square [x, x + size) x [y, y + size) of `image`.
Image crop(const Image& image, int x, int y, int size) {
    Image out(size, size);
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i)
            out.set(i, j, image.at(x + i, y + j));
    return out;
}

const char* kUsage =
    "usage: direct_compare SCENE.json REFERENCE.pfm OUT_PREFIX [--size N] [--budget SECONDS]\n"
    "                      [--threads T] [--crop X Y SIZE] [--sequence-pngs 0|1]\n"
    "Equal-time and equal-sample comparison of the direct-light strategies against a\n"
    "converged REFERENCE.pfm of the same scene, size and -m 1 (docs/direct.md).\n"
    "Defaults: --size 256 --budget 4 --threads 2, the whole image, --sequence-pngs 1.\n"
    "exit codes: 0 ok, 1 failure, 2 bad input\n";

int run(const std::vector<std::string>& args) {
    std::vector<std::string> positional;
    Setup s;
    int size = 256, crop_x = 0, crop_y = 0, crop_size = 0;
    double budget = 4.0;
    bool sequence_pngs = true;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size()) throw InputError(a + ": expected a value after it");
            return args[++i];
        };
        if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            return kExitOk;
        } else if (a == "--size") {
            size = int(parse_whole_number(a, value(), 1, 1 << 14));
        } else if (a == "--budget") {
            budget = parse_real_number(a, value(), 0, 1e6, true);
        } else if (a == "--threads") {
            s.threads = int(parse_whole_number(a, value(), 1, 4096));
        } else if (a == "--sequence-pngs") {
            sequence_pngs = parse_whole_number(a, value(), 0, 1) == 1;
        } else if (a == "--crop") {
            crop_x = int(parse_whole_number(a + " (x)", value(), 0, 1 << 14));
            crop_y = int(parse_whole_number(a + " (y)", value(), 0, 1 << 14));
            crop_size = int(parse_whole_number(a + " (size)", value(), 1, 1 << 14));
        } else if (a.size() > 1 && a[0] == '-') {
            throw InputError(a + ": unknown option (direct_compare --help)");
        } else {
            positional.push_back(a);
        }
    }
    if (positional.size() != 3)
        throw InputError("expected SCENE.json REFERENCE.pfm OUT_PREFIX, got " + std::to_string(positional.size()) +
                         " arguments (direct_compare --help)");
    s.scene = load_scene(positional[0]);
    Image reference = read_pfm(positional[1]);
    std::string prefix = positional[2];
    if (crop_size == 0) crop_size = size;
    auto save = [&](const Image& image, const std::string& path) {
        write_png(crop(image, crop_x, crop_y, crop_size), path);
    };
    s.scene.film_width = s.scene.film_height = size;
    s.scene.camera.aspect = 1.0;
    s.scene.camera.finalize();
    if (reference.width() != size || reference.height() != size)
        throw InputError(positional[1] + ": the reference is " + std::to_string(reference.width()) + "x" +
                         std::to_string(reference.height()) + ", not " + std::to_string(size) + "x" +
                         std::to_string(size));
    if (crop_x + crop_size > size || crop_y + crop_size > size)
        throw InputError("--crop: the crop does not fit in the " + std::to_string(size) + "x" + std::to_string(size) +
                         " image");
    s.accelerator = build_accelerator(s.scene, s.stages, AcceleratorSettings{});
    const DirectStrategy strategies[] = {DirectStrategy::hemisphere, DirectStrategy::light,
                                         DirectStrategy::mis};

    std::printf("\nEqual time (%.1f s each, passes of -s 2 -l 1, %d threads, %dx%d):\n\n", budget,
                s.threads, size, size);
    std::printf(
        "| strategy | spp | seconds | Mrays | relMSE | relMSE x time "
        "|\n|---|---|---|---|---|---|\n");
    for (DirectStrategy d : strategies) {
        Outcome o = render_passes(s, d, 2, 1, budget);
        double e = relmse(o.image, reference);
        std::printf("| %s | %d | %.2f | %.1f | %.4g | %.4g |\n", to_string(d), 2 * o.passes,
                    o.seconds, o.rays * 1e-6, e, e * o.seconds);
        save(o.image, prefix + "_equal_time_" + to_string(d) + ".png");
    }

    std::printf("\nEqual samples (-s 2 -l 8, one pass):\n\n");
    std::printf("| strategy | seconds | Mrays | relMSE | relMSE x time |\n|---|---|---|---|---|\n");
    for (DirectStrategy d : strategies) {
        Outcome o = render_passes(s, d, 2, 8, 0, 1);
        double e = relmse(o.image, reference);
        std::printf("| %s | %.2f | %.1f | %.4g | %.4g |\n", to_string(d), o.seconds, o.rays * 1e-6,
                    e, e * o.seconds);
    }

    std::printf("\nLight sampling, -s 1 -l N:\n\n");
    std::printf("| -l | seconds | Mrays | relMSE |\n|---|---|---|---|\n");
    for (int l : {1, 4, 16, 64}) {
        Outcome o = render_passes(s, DirectStrategy::light, 1, l, 0, 1);
        std::printf("| %d | %.2f | %.1f | %.4g |\n", l, o.seconds, o.rays * 1e-6,
                    relmse(o.image, reference));
        if (sequence_pngs) save(o.image, prefix + "_l" + std::to_string(l) + ".png");
    }
    return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const InputError& e) {
        std::fprintf(stderr, "direct_compare: error: %s\n", e.what());
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "direct_compare: internal error: %s\n", e.what());
        return kExitFailure;
    }
}
