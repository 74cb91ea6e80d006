// Attacks on the converged references (issue 14's table, rows 4 and 6):
// a cache entry rewritten with zeros is detected by its content hash and
// rendered again, bit for bit as before; a render copied from the
// converged reference instead of rendered at the case's spp is flagged as
// suspicious in the task's message and details (flagged, not failed: the
// grader cannot prove how an image was made). The sandbox keeps a runner
// from reaching the cache at all (docs/grading.md, "The sandbox"); these
// tests cover what is left when something else writes to it.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "grade/image_case.h"
#include "grade/reference_renders.h"
#include "grading_helpers.h"
#include "image/image_io.h"
#include "stages/render_context.h"

using namespace pt;
using namespace pt::testing;
namespace fs = std::filesystem;

namespace {

const TaskSpec& task(int part, const std::string& id) {
    for (const TaskSpec& t : manifest(part).tasks)
        if (t.id == id) return t;
    throw std::runtime_error("no task " + id);
}

/// part1.2's case 3: normals of the Cornell box with spheres, 64x64, 8 spp
/// against a converged reference of 1024 spp.
ImageCase eight_spp_case() {
    const TaskSpec& spec = task(1, "part1.2");
    ImageCase c = parse_image_case(spec.params.at("cases").at(2), "part1.2 case 3");
    REQUIRE(c.settings.spp == 8);
    REQUIRE(c.converged_spp == 1024);
    return c;
}

bool same_bits(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() && a.data() == b.data();
}

Image g_converged;  // what the copying raytrace_pixel returns

/// A raytrace_pixel that returns the converged reference's pixel on the
/// 8-spp case (as one that reads the grader's cache would) and renders
/// honestly on the others.
PixelResult copied_pixel(const RenderContext& context, int x, int y) {
    if (context.settings.spp == 8 && context.scene.film_width == g_converged.width() &&
        context.scene.film_height == g_converged.height())
        return {g_converged.at(x, y), context.settings.spp};
    return reference::raytrace_pixel(context, x, y);
}

}  // namespace

TEST_CASE("attack: a cached converged reference rewritten with zeros is detected and rendered again") {
    const ImageCase c = eight_spp_case();
    GradeEnvironment env = environment(reference_stages(), 1);
    env.cache_dir = output_dir() + "/tampered_cache";
    fs::remove_all(env.cache_dir);
    const Scene scene = load_case_scene(c, env.assets_dir);

    forget_converged_in_memory();
    const ReferenceRenders first = reference_renders(scene, c, 0, env);
    CHECK_FALSE(first.from_cache);
    forget_converged_in_memory();
    CHECK(reference_renders(scene, c, 0, env).from_cache);  // an honest entry is used

    // The attack: every converged image of the cache replaced by zeros.
    int rewritten = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(env.cache_dir)) {
        const std::string name = e.path().filename().string();
        if (name.size() > 4 && name.substr(name.size() - 4) == ".pfm" && name.find("-witness") == std::string::npos &&
            name.find("-variance") == std::string::npos) {
            write_pfm(Image(c.width, c.height), e.path().string());
            ++rewritten;
        }
    }
    REQUIRE(rewritten == 1);
    forget_converged_in_memory();
    const ReferenceRenders again = reference_renders(scene, c, 0, env);
    CHECK_FALSE(again.from_cache);  // the hash no longer matches: rendered anew
    CHECK(same_bits(again.converged, first.converged));
    CHECK(same_bits(again.sample_variance, first.sample_variance));
    forget_converged_in_memory();
    const ReferenceRenders repaired = reference_renders(scene, c, 0, env);
    CHECK(repaired.from_cache);  // and the entry written again is whole
    CHECK(same_bits(repaired.converged, first.converged));
    forget_converged_in_memory();
}

TEST_CASE("attack: an image copied from the converged reference is flagged as suspicious") {
    const ImageCase c = eight_spp_case();
    const GradeEnvironment honest_env = environment(reference_stages(), 1);
    g_converged = reference_renders(load_case_scene(c, honest_env.assets_dir), c, 0, honest_env).converged;
    REQUIRE(g_converged.width() == 64);

    Stages s = reference_stages();
    s.camera.raytrace_pixel = copied_pixel;
    const TaskResult copied = grade_task(task(1, "part1.2"), environment(s, 1));
    INFO(copied.message);
    CHECK(copied.status == TaskStatus::pass);  // flagged, not failed
    CHECK(copied.message.rfind("case 3 SUSPICIOUS: relMSE ", 0) == 0);
    CHECK(copied.message.find("was this image rendered at 8 spp?") != std::string::npos);
    size_t flagged = 0;
    for (const std::string& d : copied.details) {
        if (d.rfind("case 3 SUSPICIOUS", 0) == 0) ++flagged;
        if (d.rfind("case 1 ", 0) == 0 || d.rfind("case 2 ", 0) == 0)
            CHECK(d.find("SUSPICIOUS") == std::string::npos);  // the copied case only
    }
    CHECK(flagged == 1);

    // The honest reference at 8 spp is not flagged on any seed of three.
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        const TaskResult honest = grade_task(task(1, "part1.2"), environment(reference_stages(), seed));
        INFO("seed " << seed << ": " << honest.message);
        CHECK(honest.status == TaskStatus::pass);
        CHECK(honest.message.find("SUSPICIOUS") == std::string::npos);
        for (const std::string& d : honest.details)
            CHECK(d.find("SUSPICIOUS") == std::string::npos);
    }
}
