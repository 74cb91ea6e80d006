// The scene keys of issue 21 (docs/scenes.md): camera types, microfacet
// distributions, anisotropic roughness and rough_dielectric are read as
// written, and each misuse is one error naming the JSON path.
#include <doctest/doctest.h>

#include <string>

#include "core/error.h"
#include "scene/scene_loader.h"

using namespace pt;

namespace {

std::string scene_with(const std::string& camera, const std::string& material) {
    return R"({"camera": )" + camera + R"(, "materials": {"m": )" + material + R"(},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
}

const std::string kCamera = R"({"position": [0, 0, 5], "look_at": [0, 0, 0]})";
const std::string kMaterial = R"({"type": "diffuse"})";

std::string error_of(const std::string& json) {
    try {
        parse_json_scene(json, "s.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("camera types: their keys, and the keys of other types refused") {
    Scene s = parse_json_scene(
        scene_with(R"({"type": "orthographic", "position": [0, 0, 5], "look_at": [0, 0, 0], "height": 3})", kMaterial), "s.json");
    CHECK(s.camera.type == CameraType::orthographic);
    CHECK(s.camera.height == 3);
    s = parse_json_scene(scene_with(R"({"type": "fisheye", "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 360})", kMaterial),
                         "s.json");
    CHECK(s.camera.type == CameraType::fisheye);
    CHECK(s.camera.fov == 360);
    CHECK(parse_json_scene(scene_with(kCamera, kMaterial), "s.json").camera.type == CameraType::perspective);

    struct Case {
        std::string camera, expected;
    } cases[] = {
        {R"({"type": "orthographic", "position": [0, 0, 5], "look_at": [0, 0, 0]})", "s.json: camera.height: an orthographic camera needs"},
        {R"({"type": "orthographic", "position": [0, 0, 5], "look_at": [0, 0, 0], "height": 2, "vfov": 30})", "vfov"},
        {R"({"type": "orthographic", "position": [0, 0, 5], "look_at": [0, 0, 0], "height": -2})", "camera.height"},
        {R"({"type": "fisheye", "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 361})", "camera.fov"},
        {R"({"type": "fisheye", "position": [0, 0, 5], "look_at": [0, 0, 0], "lens_radius": 0.1})", "lens_radius"},
        {R"({"type": "pinhole", "position": [0, 0, 5], "look_at": [0, 0, 0]})", "unknown camera type \"pinhole\""},
        {R"({"position": [0, 0, 5], "look_at": [0, 0, 0], "height": 2})", "height"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.camera);
        CHECK(error_of(scene_with(c.camera, kMaterial)).find(c.expected) != std::string::npos);
    }
    // A thin lens from the command line on an orthographic camera.
    Camera ortho = s.camera;
    ortho.type = CameraType::orthographic;
    ortho.lens_radius = 0.1;
    CHECK_THROWS_WITH_AS(ortho.finalize("s.json: camera"),
                         "s.json: camera: a thin lens (lens_radius, -b) needs a perspective camera, not orthographic",
                         InputError);
}

TEST_CASE("glossy materials: distributions, anisotropy, rough_dielectric") {
    Scene s = parse_json_scene(
        scene_with(kCamera, R"({"type": "microfacet", "distribution": "beckmann", "roughness": [0.1, 0.4], "reflectance": [0.9, 0.9, 0.9]})"),
        "s.json");
    CHECK(s.materials[0].distribution == MicrofacetModel::beckmann);
    CHECK(s.materials[0].roughness == 0.1);
    CHECK(s.materials[0].roughness_y == 0.4);
    s = parse_json_scene(scene_with(kCamera, R"({"type": "microfacet", "distribution": "blinn_phong", "exponent": 64, "reflectance": [0.9, 0.9, 0.9]})"),
                         "s.json");
    CHECK(s.materials[0].distribution == MicrofacetModel::blinn_phong);
    CHECK(s.materials[0].exponent == 64);
    s = parse_json_scene(scene_with(kCamera, R"({"type": "rough_dielectric", "ior": 1.33, "roughness": 0.2})"), "s.json");
    CHECK(s.materials[0].type == MaterialType::rough_dielectric);
    CHECK(s.materials[0].ior == 1.33);
    CHECK(s.materials[0].roughness == 0.2);
    CHECK(s.materials[0].distribution == MicrofacetModel::ggx);

    struct Case {
        std::string material, expected;
    } cases[] = {
        {R"({"type": "microfacet", "distribution": "phong", "reflectance": [1, 1, 1]})", "materials.m.distribution: unknown distribution \"phong\""},
        {R"({"type": "microfacet", "distribution": "blinn_phong", "roughness": 0.2, "reflectance": [1, 1, 1]})", "takes \"exponent\", not \"roughness\""},
        {R"({"type": "microfacet", "exponent": 20, "reflectance": [1, 1, 1]})", "materials.m.exponent: only the blinn_phong"},
        {R"({"type": "microfacet", "roughness": [0.1, 2], "reflectance": [1, 1, 1]})", "materials.m.roughness: expected alpha or [alpha_x, alpha_y]"},
        {R"({"type": "microfacet", "roughness": [0.1], "reflectance": [1, 1, 1]})", "materials.m.roughness"},
        {R"({"type": "rough_dielectric", "ior": -1})", "materials.m.ior"},
        {R"({"type": "rough_dielectric", "eta": [1, 1, 1]})", "eta"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.material);
        CHECK(error_of(scene_with(kCamera, c.material)).find(c.expected) != std::string::npos);
    }
}
