// The thin-lens part of the generate_ray check (params.thin_lens, for a
// later part's manifest): the reference passes, a camera that ignores the
// lens or focuses at the wrong distance fails.
#include <doctest/doctest.h>

#include "grading_helpers.h"
#include "stages/camera.h"

using namespace pt;
using namespace pt::testing;

namespace {

TaskResult grade_thin_lens(const Stages& student) {
    TaskSpec spec;
    spec.part = 4;
    spec.id = "thin_lens";
    spec.name = "thin lens";
    spec.check = "generate_ray";
    spec.points = 1;
    spec.params = {{"thin_lens", true}, {"cameras", 20}, {"points_per_camera", 50}};
    spec.manifest = "test";
    return grade_task(spec, environment(student, 1));
}

}  // namespace

TEST_CASE("thin lens: the reference passes") {
    TaskResult r = grade_thin_lens(reference_stages());
    INFO(r.message);
    CHECK(r.status == TaskStatus::pass);
}

TEST_CASE("thin lens: ignoring the lens or misplacing the focus fails") {
    Stages pinhole = reference_stages();
    pinhole.camera.generate_ray = [](const Camera& c, double x, double y, Vec2 lens) {
        Camera p = c;
        p.lens_radius = 0;
        return reference::generate_ray(p, x, y, lens);
    };
    TaskResult r = grade_thin_lens(pinhole);
    INFO(r.message);
    CHECK(r.status == TaskStatus::fail);
    CHECK(r.message.find("lens_sample is ignored") != std::string::npos);

    Stages defocused = reference_stages();
    defocused.camera.generate_ray = [](const Camera& c, double x, double y, Vec2 lens) {
        Camera p = c;
        p.focal_distance *= 1.1;
        return reference::generate_ray(p, x, y, lens);
    };
    r = grade_thin_lens(defocused);
    INFO(r.message);
    CHECK(r.status == TaskStatus::fail);
    CHECK(r.message.find("misses the point in focus") != std::string::npos);
}
