// Textures (scene/texture.h): bilinear filtering, wrapping, sRGB decoding,
// the checkerboard, loading from JSON and from OBJ/MTL (vt, map_Kd), and a
// rendered texture against the exact point-light formula.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/math.h"
#include "image/exr_io.h"
#include "image/image_io.h"
#include "image/tonemap.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"
#include "test_util.h"

using namespace pt;

namespace {

void check_color(const Color& got, const Color& want, double tolerance = 1e-6) {
    CHECK(got.r == doctest::Approx(want.r).epsilon(tolerance));
    CHECK(got.g == doctest::Approx(want.g).epsilon(tolerance));
    CHECK(got.b == doctest::Approx(want.b).epsilon(tolerance));
}

std::string load_error(const std::string& path) {
    try {
        load_scene(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("image texture: texel centres exact, bilinear between them, repeating") {
    Image image(3, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) image.set(x, y, Color(x, y, 10 * x + y));
    ImageTexture texture(image);
    // Texel (i, j)'s centre is at u = (i + 0.5) / 3, v = 1 - (j + 0.5) / 2 (rows run down).
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) check_color(texture.evaluate(Vec2((x + 0.5) / 3, 1 - (y + 0.5) / 2)), image.at(x, y));
    // Halfway between texels (0, 0) and (1, 0), and among four.
    check_color(texture.evaluate(Vec2(1.0 / 3, 0.75)), Color(0.5, 0, 5));
    check_color(texture.evaluate(Vec2(1.0 / 3, 0.5)), Color(0.5, 0.5, 5.5));
    // Repeating: u + 1 and v - 2 are the same point; u = 0 blends the first
    // and the last column.
    check_color(texture.evaluate(Vec2(0.3 + 1, 0.2 - 2)), texture.evaluate(Vec2(0.3, 0.2)), 1e-9);
    check_color(texture.evaluate(Vec2(0, 0.75)), Color(1, 0, 10));
    // A scale of 2 tiles the image twice.
    ImageTexture tiled(image, Vec2(2, 2));
    check_color(tiled.evaluate(Vec2(0.1, 0.3)), texture.evaluate(Vec2(0.2, 0.6)), 1e-9);
}

TEST_CASE("checkerboard: squares of 1 / scale, even where floor(u s) + floor(v s) is even") {
    CheckerboardTexture board(Color(1), Color(0.25), Vec2(4, 2));
    CHECK(board.evaluate(Vec2(0.1, 0.1)) == Color(1));      // (0, 0)
    CHECK(board.evaluate(Vec2(0.3, 0.1)) == Color(0.25));   // (1, 0)
    CHECK(board.evaluate(Vec2(0.3, 0.6)) == Color(1));      // (1, 1)
    CHECK(board.evaluate(Vec2(-0.1, 0.1)) == Color(0.25));  // (-1, 0)
    CHECK(board.evaluate(Vec2(-0.1, -0.1)) == Color(1));    // (-1, -1)
}

TEST_CASE("albedo textures decode sRGB PNGs to linear and refuse texels above 1") {
    std::string dir = test::scratch_dir("textures_load");
    Image image(2, 1);
    image.set(0, 0, Color(0.5, 0.2, 0.0));
    image.set(1, 0, Color(1.0, 0.01, 0.7));
    write_png(image, dir + "/t.png");
    auto texture = load_albedo_texture(dir + "/t.png", "test");
    // The PNG holds 8-bit sRGB codes; the texture holds what they encode.
    check_color(texture->evaluate(Vec2(0.25, 0.5)),
                Color(from_srgb8(to_srgb8(0.5)), from_srgb8(to_srgb8(0.2)), 0.0));
    CHECK(std::fabs(texture->evaluate(Vec2(0.25, 0.5)).r - 0.5) < 0.003);  // not 0.5^2.2 or 0.5^(1/2.2)
    image.set(1, 0, Color(1.5, 0, 0));
    write_exr(image, dir + "/bright.exr");
    try {
        load_albedo_texture(dir + "/bright.exr", "scene.json: materials.m.albedo.texture");
        FAIL("expected an InputError");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()) == "scene.json: materials.m.albedo.texture: " + dir +
                                           "/bright.exr: texel (1, 0) is not a reflectance in [0, 1]");
    }
}

TEST_CASE("textures from JSON and from OBJ (vt) with MTL map_Kd") {
    std::string dir = test::scratch_dir("textures_scene");
    Image image(4, 4);
    for (int i = 0; i < 16; ++i) image.set(i % 4, i / 4, Color(0.05 * i));
    write_png(image, dir + "/wood.png");
    test::write_file(dir + "/square.mtl", "newmtl wood\nKd 1 1 1\nmap_Kd -s 2 3 1 wood.png\n");
    test::write_file(dir + "/square.obj",
                     "mtllib square.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                     "usemtl wood\nf 1/2 2/3 3/4\nf 1 3 4\n");
    Scene scene = load_scene(dir + "/square.obj");
    const Material& wood = scene.materials.back();
    REQUIRE(wood.albedo_texture);
    auto expected = ImageTexture(read_image(dir + "/wood.png"), Vec2(2, 3));
    check_color(wood.albedo_at(Vec2(0.3, 0.7)), expected.evaluate(Vec2(0.3, 0.7)));
    // The first face has vt: (u, v) interpolates them; the second has none.
    CHECK(scene.uv_at(0, 0.0, 0.0, Vec3()).x == 1);
    Vec2 uv = scene.uv_at(0, 0.25, 0.5, Vec3());  // b0 = 0.25: 0.25 (1,0) + 0.25 (1,1) + 0.5 (0,1)
    CHECK(uv.x == doctest::Approx(0.5));
    CHECK(uv.y == doctest::Approx(0.75));
    Vec2 fallback = scene.uv_at(1, 0.25, 0.5, Vec3());
    CHECK(fallback.x == doctest::Approx(0.75));  // (b1 + b2, b2)
    CHECK(fallback.y == doctest::Approx(0.5));

    auto scene_with = [&](const std::string& albedo) {
        std::string path = dir + "/s.json";
        test::write_file(path, R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
            "materials": {"m": {"type": "diffuse", "albedo": )" + albedo + R"(}},
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
        return path;
    };
    Scene s = load_scene(scene_with(R"({"texture": "wood.png", "scale": [2, 3]})"));
    check_color(s.materials[0].albedo_at(Vec2(0.3, 0.7)), expected.evaluate(Vec2(0.3, 0.7)));
    s = load_scene(scene_with(R"({"checkerboard": {"even": [1, 1, 1], "odd": [0, 0.5, 0]}, "scale": 2})"));
    CHECK(s.materials[0].albedo_at(Vec2(0.6, 0.1)) == Color(0, 0.5, 0));
    // A sphere's (u, v): longitude from +z about +y, v = 1 at the top.
    uint32_t sphere = s.primitive_count() - 1;
    CHECK(s.uv_at(sphere, 0, 0, Vec3(0, 1, 0)).y == doctest::Approx(1.0));
    CHECK(s.uv_at(sphere, 0, 0, Vec3(1, 0, 0)).x == doctest::Approx(0.25));
    CHECK(s.uv_at(sphere, 0, 0, Vec3(0, 0, 1)).y == doctest::Approx(0.5));

    CHECK(load_error(scene_with(R"({"texture": "nope.png"})")).find("materials.m.albedo.texture: cannot read") !=
          std::string::npos);
    CHECK(load_error(scene_with(R"({"texture": "wood.png", "checkerboard": {}})")).find("either") != std::string::npos);
    CHECK(load_error(scene_with(R"({"texure": "wood.png"})")).find("texure") != std::string::npos);
    CHECK(load_error(scene_with(R"({"checkerboard": {"even": [1, 1, 1]}})")).find("\"odd\"") != std::string::npos);
    CHECK(load_error(scene_with(R"({"texture": "wood.png", "scale": 0})")).find("albedo.scale") != std::string::npos);
    test::write_file(dir + "/bad.obj", "mtllib square.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nusemtl wood\nf 1/1 2/2 3/1\n");
    CHECK(load_error(dir + "/bad.obj").find("texture coordinate 2 but the file has 1") != std::string::npos);
}

TEST_CASE("a rendered texture is the point-light formula times the texture, pixel by pixel") {
    // An orthographic camera looks straight down on a 2 x 2 quad in y = 0
    // under a point light of intensity I at height h: each pixel centre sees
    // the point (x, 0, z) with radiance albedo(u, v) I h / (pi r^3) exactly.
    std::string dir = test::scratch_dir("textures_render");
    Image image(4, 4);
    for (int i = 0; i < 16; ++i) image.set(i % 4, i / 4, Color(0.06 * i, 0.9 - 0.05 * i, 0.5));
    write_png(image, dir + "/t.png");
    for (std::string albedo : {R"({"texture": "t.png"})", R"({"checkerboard": {"even": [1, 1, 1], "odd": [0.25, 0.5, 0.1]}, "scale": 4})"}) {
        CAPTURE(albedo);
        test::write_file(dir + "/s.json", R"({
            "camera": {"type": "orthographic", "position": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "height": 2},
            "film": {"width": 16, "height": 16},
            "materials": {"m": {"type": "diffuse", "albedo": )" + albedo + R"(}},
            "objects": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "m"}],
            "lights": [{"type": "point", "position": [0, 1.5, 0], "intensity": [3, 3, 3]}]})");
        test::CommandResult r =
            test::run("'" + test::bin_path("pathtracer") + "' -q -t 2 --hdr " + dir + "/out.pfm -f " + dir + "/out.png " + dir + "/s.json", dir);
        REQUIRE(r.exit_code == 0);
        Scene scene = load_scene(dir + "/s.json");
        Image out = read_image(dir + "/out.pfm");
        for (int py = 0; py < 16; ++py)
            for (int px = 0; px < 16; ++px) {
                // The film point of the pixel centre; world x = film x, world z = -film y.
                double x = ((px + 0.5) / 16 * 2 - 1), z = -((1 - (py + 0.5) / 16) * 2 - 1);
                Vec2 uv((x + 1) / 2, (1 - z) / 2);  // corner + u edge1 + v edge2
                double h = 1.5, r2 = x * x + z * z + h * h;
                Color want = scene.materials[0].albedo_at(uv) * (3.0 * h / (kPi * r2 * std::sqrt(r2)));
                check_color(out.at(px, py), want, 1e-5);
            }
    }
}
