// The Lambertian BSDF (values, reciprocity, energy), the shading frame that
// RenderContext::bsdf_at builds (two-sided), and the direct stage switch.
#include <doctest/doctest.h>

#include "core/error.h"
#include "core/math.h"
#include "core/rng.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "scene/bsdf.h"
#include "scene/material.h"
#include "scene/scene_loader.h"
#include "stages/stages.h"

using namespace pt;

TEST_CASE("diffuse BSDF: albedo / pi above, black below, reciprocal") {
    Color albedo(0.6, 0.3, 0.1);
    Vec3 up = Vec3(0.2, 0.3, 0.9).unit(), other = Vec3(-0.5, 0.1, 0.4).unit(), below(0, 0.6, -0.8);
    CHECK(reference::diffuse_f(albedo, up, other) == albedo * kInvPi);
    CHECK(reference::diffuse_f(albedo, other, up) == reference::diffuse_f(albedo, up, other));
    CHECK(reference::diffuse_f(albedo, up, below).is_black());
    CHECK(reference::diffuse_f(albedo, up, Vec3(1, 0, 0)).is_black());  // grazing: cos = 0
}

TEST_CASE("diffuse BSDF: f cos / pdf = albedo for every sample (energy conservation)") {
    Color albedo(0.6, 0.3, 0.1);
    Rng rng(5);
    for (int i = 0; i < 1000; ++i) {
        BSDFSample s = reference::diffuse_sample_f(albedo, Vec3(0, 0, 1), rng.next_2d());
        REQUIRE(s.valid());
        CHECK(s.wi.z > 0);
        CHECK_FALSE(s.is_delta);
        Color w = s.f * s.wi.z / s.pdf;
        CHECK(w.r == doctest::Approx(albedo.r));
        CHECK(w.b == doctest::Approx(albedo.b));
    }
    // The edge of the disk maps to the horizon: no sample, never a division by 0.
    BSDFSample edge = reference::diffuse_sample_f(albedo, Vec3(0, 0, 1), Vec2(0.0, 0.0));
    CHECK((edge.valid() ? std::isfinite(edge.f.r / edge.pdf) : true));
}

TEST_CASE("mirror and glass are deltas: no light sample reaches them, only sample_f") {
    for (MaterialType type : {MaterialType::mirror, MaterialType::glass}) {
        Material m;
        m.type = type;
        BSDF bsdf(m, Frame(), {reference::diffuse_f, reference::diffuse_sample_f});
        CHECK(bsdf.is_delta());
        CHECK(bsdf.f(Vec3(0, 0, 1), Vec3(0, 0, 1)).is_black());
        CHECK(bsdf.pdf(Vec3(0, 0, 1), Vec3(0, 0, 1)) == 0);
        BSDFSample s = bsdf.sample_f(Vec3(0.6, 0, 0.8), Vec2(0.01, 0.5));
        CHECK(s.valid());
        CHECK(s.is_delta);
    }
}

TEST_CASE("bsdf_at turns the frame to the side the ray came from (two-sided), except for glass") {
    Scene scene = parse_json_scene(R"({
        "camera": {"position": [0, 2, 0], "look_at": [0, 0, 0], "up": [0, 0, 1]},
        "materials": {"grey": {"type": "diffuse"}, "glass": {"type": "glass"}},
        "objects": [{"type": "quad", "corner": [-1, 0, -1], "edge1": [0, 0, 2], "edge2": [2, 0, 0], "material": "grey"},
                    {"type": "quad", "corner": [-1, 5, -1], "edge1": [0, 0, 2], "edge2": [2, 0, 0], "material": "glass"}]
    })",
                                   "frame.json");
    RenderSettings settings;
    Stages stages = make_stages(StageSet::none());
    std::unique_ptr<Integrator> integrator = make_integrator(IntegratorKind::normals);
    std::unique_ptr<Accelerator> accelerator =
        build_accelerator(scene, stages, AcceleratorSettings{});
    RenderContext context{scene, *accelerator, stages, settings, *integrator};
    for (double from : {1.0, -1.0}) {
        std::optional<SurfaceInteraction> hit =
            context.intersect(Ray(Vec3(0.1, from, 0.2), Vec3(0, -from, 0)));
        REQUIRE(hit);
        BSDF bsdf = context.bsdf_at(*hit);
        CHECK(bsdf.frame().n.y == doctest::Approx(from));  // faces the viewer from either side
        CHECK(bsdf.to_local(hit->wo).z == doctest::Approx(1.0));
    }
    // Seen from below, glass keeps its stored normal e1 x e2 = +y (it must know in from out).
    std::optional<SurfaceInteraction> glass =
        context.intersect(Ray(Vec3(0.1, 4, 0.2), Vec3(0, 1, 0)));
    REQUIRE(glass);
    CHECK(context.bsdf_at(*glass).frame().n.y == doctest::Approx(1.0));
}

TEST_CASE("the direct stage switch: student stubs throw NotImplemented, naming the task") {
    Stages student = make_stages(StageSet::parse("direct"));
    Stages reference = make_stages(StageSet::none());
    CHECK((reference.direct.diffuse_f == &reference::diffuse_f));
    CHECK((student.direct.diffuse_f == &student::diffuse_f));
    CHECK((student.direct.one_bounce_radiance == &student::one_bounce_radiance));
    try {
        student.direct.diffuse_f(Color(0.5), Vec3(0, 0, 1), Vec3(0, 0, 1));
        // A student who has done task 1 passes through; the stub does not.
    } catch (const NotImplemented& e) {
        CHECK(std::string(e.what()) == "Part 3, task 1: diffuse_f is not implemented yet");
        CHECK(e.part() == 3);
    }
}
