// The switch for stage `global`: `--student global` puts the student's two
// functions in the table, the handout's stubs stop with "Part 4, task N",
// the reference functions graded as a student's give the reference image,
// and a solution written from the TODO comments of assignments/part4 alone
// (global/handout_steps.h, as a student would write it) renders the reference's image: the
// same paths from the same random numbers, equal up to the rounding of a
// different summation order.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "global/global_render.h"
#include "global/handout_steps.h"
#include "test_util.h"

using namespace pt;
using namespace pt::global_test;

namespace {

Scene cbox_with(const std::string& scene) {
    return load_scene(test::source_path("assets/scenes/" + scene));
}

}  // namespace

TEST_CASE("student global stage: the stubs report the task, in task order") {
    Stages student = make_stages(StageSet::parse("global"));
    CHECK((student.global.at_least_one_bounce_radiance == &student::at_least_one_bounce_radiance));
    CHECK((make_stages(StageSet::none()).global.est_radiance_global_illumination ==
           &reference::est_radiance_global_illumination));
    Scene scene = cbox_with("cbox.json");
    scene.film_width = scene.film_height = 4;
    RenderSettings settings = path_settings(2, 1);
    try {
        render(scene, settings, IntegratorKind::automatic, student);
        FAIL("the stubs rendered an image");
    } catch (const NotImplemented& e) {
        CHECK(std::string(e.what()) ==
              "Part 4, task 1: at_least_one_bounce_radiance is not implemented yet");
        CHECK(e.part() == 4);
    }
    // -m 0 needs only task 2.
    settings.max_depth = 0;
    try {
        render(scene, settings, IntegratorKind::automatic, student);
        FAIL("the stubs rendered an image");
    } catch (const NotImplemented& e) {
        CHECK(std::string(e.what()) ==
              "Part 4, task 2: est_radiance_global_illumination is not implemented yet");
    }
}

TEST_CASE("the reference graded as a student gives the reference image, byte for byte") {
    Scene scene = cbox_with("cbox_spheres.json");
    scene.film_width = scene.film_height = 24;
    RenderSettings settings = path_settings(5, 2, 4);
    Stages as_student = make_stages(StageSet::parse("global"));
    as_student.global = {reference::at_least_one_bounce_radiance,
                         reference::est_radiance_global_illumination};
    RenderResult reference = render(scene, settings, IntegratorKind::path);
    RenderResult graded = render(scene, settings, IntegratorKind::path, as_student);
    CHECK(same_pixels(reference.image, graded.image));
}

TEST_CASE("a solution written from the TODO comments renders the reference's image") {
    Stages todo = make_stages(StageSet::parse("global"));
    todo.global = {handout_steps::bounce<handout_steps::Bug::none>,
                   handout_steps::camera_ray<handout_steps::CameraBug::none>};
    // cbox has no glass (whose eta^2 the reference keeps out of roulette and
    // the handout does not); cbox_spheres' mirror exercises delta bounces.
    for (const char* name : {"cbox.json", "cbox_spheres.json"}) {
        for (bool accumulate : {true, false}) {
            Scene scene = cbox_with(name);
            scene.film_width = scene.film_height = 20;
            if (std::string(name) == "cbox_spheres.json") {
                // Keep the mirror sphere, make the glass sphere a mirror too.
                for (Material& m : scene.materials)
                    if (m.type == MaterialType::glass) m.type = MaterialType::mirror;
            }
            CAPTURE(std::string(name));
            CAPTURE(accumulate);
            RenderSettings settings = path_settings(6, 2, 8);
            settings.accumulate_bounces = accumulate;
            settings.rr_depth = 2;
            RenderResult reference = render(scene, settings, IntegratorKind::path);
            RenderResult mine = render(scene, settings, IntegratorKind::path, todo);
            double worst = 0;
            for (size_t i = 0; i < reference.image.data().size(); ++i) {
                double a = reference.image.data()[i], b = mine.image.data()[i];
                worst = std::max(worst, std::fabs(a - b) / std::max(1e-3, std::fabs(a)));
            }
            CAPTURE(worst);
            CHECK(worst < 1e-5);
        }
    }
}
