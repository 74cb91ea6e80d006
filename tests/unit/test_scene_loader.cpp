// The scene loader: the DESIGN.md format is read exactly, and every bad
// input is one InputError naming the file, the JSON path and what was expected.
#include <doctest/doctest.h>

#include <string>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "test_util.h"

using namespace pt;
using pt::test::scratch_dir;
using pt::test::write_file;

namespace {

const char* kMinimal = R"({
  "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov": 40},
  "film": {"width": 64, "height": 48},
  "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
                "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [4, 4, 4]}},
  "objects": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"},
    {"type": "quad", "corner": [-1, 3, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "lamp"}
  ],
  "lights": [{"type": "point", "position": [0, 5, 0], "intensity": [10, 10, 10]}]
})";

/// The message of the InputError that loading `text` throws ("" if none).
std::string load_error(const std::string& text, const std::string& name = "bad.json") {
    try {
        parse_json_scene(text, name);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

/// kMinimal with `from` replaced by `to`.
std::string edit(const std::string& from, const std::string& to) {
    std::string s = kMinimal;
    size_t at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("a well-formed scene loads with every part in place") {
    Scene s = parse_json_scene(kMinimal, "ok.json");
    CHECK(s.name == "ok");
    CHECK(s.film_width == 64);
    CHECK(s.film_height == 48);
    CHECK(s.spheres.size() == 1);
    CHECK(s.triangles.size() == 2);  // the quad
    CHECK(s.point_lights.size() == 1);
    CHECK(s.emitters.size() == 2);   // both halves of the emissive quad
    CHECK(s.camera.aspect == doctest::Approx(64.0 / 48));
    // The quad's triangles face edge1 x edge2 = (0, -4, 0): down.
    Triangle t = s.triangle(0);
    CHECK(cross(t.p1 - t.p0, t.p2 - t.p0).unit() == Vec3(0, -1, 0));
}

TEST_CASE("transforms scale, then rotate, then translate") {
    Scene s = parse_json_scene(edit(R"("center": [0, 0, 0], "radius": 1, "material": "white")",
                                    R"("center": [1, 0, 0], "radius": 1, "material": "white",
                                       "transform": {"scale": 2, "rotate": [0, 0, 1, 90], "translate": [0, 0, 3]})"),
                               "t.json");
    const Sphere& sp = s.spheres[0].sphere;
    CHECK(sp.radius == 2);
    CHECK(sp.center.x == doctest::Approx(0).scale(1));
    CHECK(sp.center.y == doctest::Approx(2));
    CHECK(sp.center.z == doctest::Approx(3));
}

TEST_CASE("bad JSON scenes: one message naming the file, the JSON path and what was expected") {
    struct Case {
        std::string text;
        std::string expected;  // a fragment the message must contain
    };
    const Case cases[] = {
        {"{ \"objects\": [ }", "malformed JSON"},
        {edit("\"film\"", "\"flim\""), "flim: unknown key"},
        {edit("\"radius\": 1", "\"radius\": 1, \"radus\": 2"), "objects[0].radus: unknown key"},
        {edit("\"type\": \"sphere\"", "\"type\": \"spere\""), "objects[0].type: unknown object type \"spere\""},
        {edit("\"type\": \"diffuse\", \"albedo\": [0.5", "\"type\": \"difuse\", \"albedo\": [0.5"),
         "materials.white.type: unknown material type"},
        {edit("\"type\": \"point\"", "\"type\": \"spot\""), "lights[0].type: unknown light type"},
        {edit("\"center\": [0, 0, 0]", "\"center\": [0, 0]"), "objects[0].center: expected an array of 3 numbers"},
        {edit("\"radius\": 1", "\"radius\": -1"), "objects[0].radius: expected a number > 0, got -1"},
        {edit("\"radius\": 1", "\"radius\": 0"), "objects[0].radius: expected a number > 0, got 0"},
        {edit("\"radius\": 1", "\"radius\": \"big\""), "objects[0].radius: expected a number"},
        {edit("\"radius\": 1", "\"radius\": 1e999"), "number overflow parsing '1e999'"},
        {edit("\"edge2\": [0, 0, 2]", "\"edge2\": [4, 0, 0]"), "objects[1]: zero-area quad"},
        {edit("\"material\": \"white\"", "\"material\": \"whte\""), "objects[0].material: no material named \"whte\""},
        {edit("\"albedo\": [0.5, 0.5, 0.5]", "\"albedo\": [0.5, 1.5, 0.5]"), "materials.white.albedo: expected components in [0, 1]"},
        {edit("\"emission\": [4, 4, 4]", "\"emission\": [4, -4, 4]"), "materials.lamp.emission: expected components >= 0"},
        {edit("\"vfov\": 40", "\"vfov\": 180"), "camera.vfov"},
        {edit("\"look_at\": [0, 0, 0]", "\"look_at\": [0, 0, 5]"), "look_at must differ from position"},
        {edit("\"width\": 64", "\"width\": 6.5"), "film.width: expected a whole number"},
        {R"({"objects": {"a": 1}})", "objects: expected an array"},
        {"[1, 2]", "top level: expected an object"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.expected);
        std::string message = load_error(c.text);
        CHECK(message.rfind("bad.json: ", 0) == 0);  // starts with the file name
        CHECK(message.find(c.expected) != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);  // one line
    }
}

TEST_CASE("mesh objects: OBJ with MTL, a material override, and bad OBJ files") {
    std::string dir = scratch_dir("loader_meshes");
    write_file(dir + "/quad.obj", "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl lamp\nf 1 2 3 4\n");
    write_file(dir + "/quad.mtl", "newmtl lamp\nKd 0.1 0.2 0.3\nKe 5 5 5\n");
    write_file(dir + "/mirror.obj", "mtllib mirror.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
    write_file(dir + "/mirror.mtl", "newmtl m\nKs 0.9 0.8 0.7\nillum 3\nnewmtl g\nNi 1.33\nillum 7\n");
    write_file(dir + "/nomtl.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write_file(dir + "/missing_mtl.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write_file(dir + "/empty.obj", "# nothing\nv 0 0 0\n");
    write_file(dir + "/badindex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    write_file(dir + "/garbage.obj", "\x01\x02 this is not an OBJ file\nf a b c\n");
    auto scene_with = [&](const std::string& object) {
        return R"({"camera": {"position": [0,0,5], "look_at": [0,0,0]}, "materials": {"white": {"type": "diffuse"}},
                   "objects": [)" + object + "]}";
    };
    std::string path = dir + "/scene.json";

    Scene s = parse_json_scene(scene_with(R"({"type": "mesh", "file": "quad.obj"})"), path);
    CHECK(s.triangles.size() == 2);  // the quad face is triangulated
    CHECK(s.emitters.size() == 2);
    CHECK(s.material_of(0).name == "quad.obj:lamp");
    CHECK(s.material_of(0).emission == Color(5, 5, 5));
    CHECK(s.material_of(0).albedo.g == doctest::Approx(0.2).epsilon(1e-7));  // tinyobjloader reads floats

    s = parse_json_scene(scene_with(R"({"type": "mesh", "file": "quad.obj", "material": "white"})"), path);
    CHECK(s.material_of(0).name == "white");
    CHECK(s.emitters.empty());

    s = parse_json_scene(scene_with(R"({"type": "mesh", "file": "mirror.obj"})"), path);
    CHECK(s.material_of(0).type == MaterialType::mirror);
    CHECK(s.material_of(0).reflectance.r == doctest::Approx(0.9).epsilon(1e-7));

    struct Case {
        std::string object, expected;
    };
    const Case cases[] = {
        {R"({"type": "mesh", "file": "absent.obj"})", "objects[0]: cannot read"},
        {R"({"type": "mesh", "file": "/dev/zero"})", "not a regular file"},
        {R"({"type": "mesh", "file": "nomtl.obj"})", "have no material"},
        {R"({"type": "mesh", "file": "missing_mtl.obj"})", "not found"},
        {R"({"type": "mesh", "file": "empty.obj", "material": "white"})", "the mesh has no faces"},
        {R"({"type": "mesh", "file": "badindex.obj", "material": "white"})", "uses vertex 7 but the file has 3"},
        {R"({"type": "mesh", "file": "garbage.obj", "material": "white"})", "garbage.obj"},
        {R"({"type": "mesh", "file": "quad.obj", "transform": {"scale": [1, 0, 1]}})", "objects[0].transform.scale"},
        {R"({"type": "mesh", "file": "quad.obj", "transform": {"rotate": [0, 0, 0, 90]}})", "non-zero axis"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.object);
        std::string message;
        try {
            parse_json_scene(scene_with(c.object), path);
        } catch (const InputError& e) {
            message = e.what();
        }
        CHECK(message.find(c.expected) != std::string::npos);
        CHECK(message.find("scene.json") != std::string::npos);
    }
}

TEST_CASE("a bare OBJ file is a scene framed by its camera, without added lights") {
    std::string dir = scratch_dir("loader_bare_obj");
    write_file(dir + "/tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
    Scene s = load_scene(dir + "/tri.obj");
    CHECK(s.triangles.size() == 1);
    CHECK_FALSE(s.has_lights());
    // The camera looks at the centre of the bounding box.
    CHECK((s.camera.look_at - s.bounds.centroid()).norm() < 1e-12);
    CHECK(s.camera.position.z > 1);

    CHECK_THROWS_AS(load_scene(dir + "/none.json"), InputError);
    CHECK_THROWS_AS(load_scene(dir + "/tri.ply"), InputError);
}

TEST_CASE("every asset scene loads") {
    for (const char* name : {"cbox", "cbox_empty", "cbox_spheres", "cbox_knot", "whitted"}) {
        CAPTURE(name);
        Scene s = load_scene(pt::test::source_path(std::string("assets/scenes/") + name + ".json"));
        CHECK(s.primitive_count() > 0);
        CHECK(s.has_lights());
    }
}
