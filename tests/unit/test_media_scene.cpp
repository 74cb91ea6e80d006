// The media keys of the scene format (docs/scenes.md, issue 20): a
// material's "interior" medium, the null boundary, the scene-level
// "medium", the density grid file; and every misuse is one error naming
// the JSON path (or the grid file and line): negative coefficients, |g| >=
// 1, an interior on an opaque material, an open mesh as a medium boundary.
#include <doctest/doctest.h>

#include <string>

#include "core/error.h"
#include "scene/density_grid.h"
#include "scene/medium_boundary.h"
#include "scene/scene_loader.h"
#include "test_util.h"

using namespace pt;

namespace {

std::string scene_with(const std::string& materials, const std::string& objects, const std::string& extra = "") {
    return R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "materials": {)" + materials +
           R"(}, "objects": [)" + objects + "]" + extra + "}";
}

const std::string kSphere = R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"})";

std::string error_of(const std::string& json, const std::string& path = "s.json") {
    try {
        parse_json_scene(json, path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("media: interiors, the null boundary and the scene's medium are read as written") {
    Scene s = parse_json_scene(
        scene_with(R"("m": {"type": "glass", "ior": 1.33, "interior": {"sigma_a": [0.1, 0.2, 0.3], "sigma_s": [4, 5, 6], "g": 0.7}},
                      "n": {"type": "null", "interior": {"sigma_s": [1, 1, 1]}}, "t": {"type": "transparent"})",
                   kSphere + R"(, {"type": "sphere", "center": [3, 0, 0], "radius": 1, "material": "n"})",
                   R"(, "medium": {"sigma_a": [0, 0, 0], "sigma_s": [0.01, 0.01, 0.01], "g": -0.2})"),
        "s.json");
    REQUIRE(s.media.size() == 3);
    REQUIRE(s.materials[0].interior == 0);
    CHECK(s.materials[0].type == MaterialType::glass);
    CHECK(s.media[0].sigma_t() == Color(4.1, 5.2, 6.3));
    CHECK(s.media[0].g == 0.7);
    CHECK(s.media[0].homogeneous());
    CHECK(s.materials[1].type == MaterialType::null);
    CHECK(s.materials[1].interior == 1);
    CHECK(s.media[1].sigma_a == Color(0));
    CHECK(s.materials[2].type == MaterialType::null);  // "transparent" is the same boundary
    CHECK(s.materials[2].interior == -1);
    CHECK(s.outside_medium == 2);
    CHECK(s.media[2].g == -0.2);
    CHECK(s.has_media());
    CHECK_FALSE(parse_json_scene(scene_with(R"("m": {"type": "diffuse"})", kSphere), "s.json").has_media());
}

TEST_CASE("media: bad coefficients, g and boundaries are one error each") {
    struct Case {
        std::string material, expected;
    } cases[] = {
        {R"({"type": "null", "interior": {"sigma_a": [-1, 0, 0]}})", "s.json: materials.m.interior.sigma_a: expected components >= 0, got -1"},
        {R"({"type": "null", "interior": {"sigma_s": [1, 1, -0.5]}})", "materials.m.interior.sigma_s: expected components >= 0"},
        {R"({"type": "null", "interior": {"sigma_s": [1, 1, 1], "g": 1}})", "materials.m.interior.g: expected the Henyey-Greenstein g in (-1, 1), got 1"},
        {R"({"type": "null", "interior": {"sigma_s": [1, 1, 1], "g": -1.5}})", "g in (-1, 1), got -1.5"},
        {R"({"type": "null", "interior": {"g": 0.5}})", "materials.m.interior: a medium needs \"sigma_a\" and/or \"sigma_s\""},
        {R"({"type": "null", "interior": {"sigma_s": [1, 1, 1], "sigmas": 1}})", "sigmas"},
        {R"({"type": "diffuse", "interior": {"sigma_s": [1, 1, 1]}})", "materials.m.interior: a medium needs a boundary that light can cross"},
        {R"({"type": "null", "albedo": [1, 1, 1]})", "albedo"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.material);
        std::string error = error_of(scene_with(R"("m": )" + c.material, kSphere));
        CHECK(error.find(c.expected) != std::string::npos);
    }
    CHECK(error_of(scene_with(R"("m": {"type": "diffuse"})", kSphere, R"(, "medium": {"sigma_a": [0, -2, 0]})"))
              .find("s.json: medium.sigma_a: expected components >= 0, got -2") != std::string::npos);
}

TEST_CASE("media: an open mesh cannot hold a medium; a mesh wound inwards is turned round") {
    // A quad is open: its edges belong to one triangle each.
    std::string quad = R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "material": "m"})";
    std::string error = error_of(scene_with(R"("m": {"type": "null", "interior": {"sigma_s": [1, 1, 1]}})", quad));
    CHECK(error.find("s.json: objects[0]: the material \"m\" has an \"interior\" medium, so its mesh must be closed") !=
          std::string::npos);
    CHECK(error.find("belongs to one triangle only") != std::string::npos);
    // The same quad without a medium is fine.
    CHECK(error_of(scene_with(R"("m": {"type": "null"})", quad)).empty());

    // The cube of assets/meshes is closed and wound outwards; reversed, it is turned back.
    std::string dir = test::scratch_dir("media_scene");
    std::string cube = test::read_file(test::source_path("assets/meshes/cube.obj"));
    Scene s = parse_json_scene(scene_with(R"("m": {"type": "null", "interior": {"sigma_s": [1, 1, 1]}})",
                                          R"({"type": "mesh", "file": ")" + test::source_path("assets/meshes/cube.obj") +
                                              R"(", "material": "m"})"),
                               dir + "/s.json");
    REQUIRE(s.triangles.size() == 12);
    MeshData inward;
    for (const TriangleRecord& t : s.triangles) inward.faces.push_back({t.v[0], t.v[2], t.v[1]});
    inward.positions = s.positions;
    std::vector<Material> materials = s.materials;
    CHECK(orient_medium_boundaries(inward, materials).empty());
    for (size_t f = 0; f < inward.faces.size(); ++f) {
        CHECK(inward.faces[f][1] == s.triangles[f].v[1]);
        CHECK(inward.faces[f][2] == s.triangles[f].v[2]);
    }
    // One face wound the wrong way: an edge is then used twice in one direction.
    inward.faces = {};
    for (const TriangleRecord& t : s.triangles) inward.faces.push_back({t.v[0], t.v[1], t.v[2]});
    std::swap(inward.faces[3][1], inward.faces[3][2]);
    CHECK(orient_medium_boundaries(inward, materials).find("wound alike") != std::string::npos);
}

TEST_CASE("density grid: trilinear between points, 0 outside, malformed files named with their line") {
    std::string dir = test::scratch_dir("density_grid");
    // 2 x 2 x 2 points over [0, 1]^3: density x + 2 y + 4 z at the corners.
    std::string good = "ptgrid 1\n# a comment\n2 2 2\n0 0 0 1 1 1\n0 1 2 3\n4 5 6 7\n";
    test::write_file(dir + "/good.grid", good);
    DensityGrid g = load_density_grid(dir + "/good.grid", "s.json: m");
    CHECK(g.max_density() == 7);
    CHECK(g.density(Vec3(0.5, 0.5, 0.5)) == doctest::Approx(3.5));
    CHECK(g.density(Vec3(0.25, 0.75, 1.0)) == doctest::Approx(0.25 + 1.5 + 4));
    CHECK(g.density(Vec3(1.01, 0.5, 0.5)) == 0);
    CHECK(g.density(Vec3(1, 1, 1)) == doctest::Approx(7));

    struct Case {
        std::string text, expected;
    } cases[] = {
        {"grid 1\n2 2 2\n", "bad.grid: line 1: expected the magic word \"ptgrid\""},
        {"ptgrid 2\n", "line 1: expected format version 1"},
        {"ptgrid 1\n1 2 2\n", "line 2: expected NX NY NZ, each an integer in [2, 512]"},
        {"ptgrid 1\n2 2 2\n0 0 0 1 -1 1\n", "line 3: expected XMAX > XMIN"},
        {"ptgrid 1\n2 2 2\n0 0 0 1 1 1\n0 1 2 3\n4 -5 6 7\n", "line 5: expected densities >= 0, got -5"},
        {"ptgrid 1\n2 2 2\n0 0 0 1 1 1\n0 1 2 3\n4 nan 6 7\n", "line 5: expected density 6 of 8, got \"nan\""},
        {"ptgrid 1\n2 2 2\n0 0 0 1 1 1\n0 1 2 3\n", "at the end: expected density 5 of 8"},
        {"ptgrid 1\n2 2 2\n0 0 0 1 1 1\n0 1 2 3 4 5 6 7\n8\n", "line 5: more values than NX*NY*NZ = 8"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.text);
        test::write_file(dir + "/bad.grid", c.text);
        std::string error;
        try {
            load_density_grid(dir + "/bad.grid", "s.json: m");
        } catch (const InputError& e) {
            error = e.what();
        }
        CHECK(error.find(c.expected) != std::string::npos);
        CHECK(error.find("s.json: m: ") == 0);
    }
    // Through the scene: the path of the key and the grid's problem.
    test::write_file(dir + "/s.json", scene_with(R"("m": {"type": "null", "interior": {"sigma_s": [1, 1, 1], "density": "missing.grid"}})", kSphere));
    std::string error;
    try {
        load_scene(dir + "/s.json");
    } catch (const InputError& e) {
        error = e.what();
    }
    CHECK(error.find("s.json: materials.m.interior.density") != std::string::npos);
    CHECK(error.find("missing.grid") != std::string::npos);
}

TEST_CASE("density grid: the shipped cloud loads, is bounded by 1 and has an inside") {
    DensityGrid cloud = load_density_grid(test::source_path("assets/media/cloud.grid"), "cloud");
    CHECK(cloud.max_density() <= 1.0);
    CHECK(cloud.max_density() > 0.9);
    CHECK(cloud.density(Vec3(0, 0.7, 0)) > 0.5);
    CHECK(cloud.density(Vec3(1.45, 1.45, 0.95)) == 0);
}
