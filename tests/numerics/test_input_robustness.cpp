// Input a student or grader may hand in: huge and tiny scene scales, a
// camera inside an object or looking straight along its up vector, meshes
// with NaN vertices or out-of-range indices. Each gives a clear error
// (exit 2) or a correct image, never a crash, and never NaN in the image.
#include <doctest/doctest.h>

#include <string>

#include "test_util.h"

using namespace pt::test;

namespace {

struct Render {
    int exit_code;
    std::string stats;
    std::string err;
};

Render render(const std::string& scene_json, const std::string& name, const std::string& flags = "") {
    std::string dir = scratch_dir("input_" + name);
    write_file(dir + "/scene.json", scene_json);
    CommandResult r = run("'" + bin_path("pathtracer") + "' -q -t 2 -r 24 24 -s 2 " + flags + " -f " + dir +
                              "/out.png --stats " + dir + "/stats.json " + dir + "/scene.json",
                          dir);
    return {r.exit_code, read_file(dir + "/stats.json"), r.err};
}

std::string cbox_scaled(double scale) {
    std::string s = std::to_string(scale);
    auto p = [&](double x, double y, double z) {
        return "[" + std::to_string(x * scale) + ", " + std::to_string(y * scale) + ", " + std::to_string(z * scale) + "]";
    };
    std::string meshes = source_path("assets/meshes/");
    return R"({"camera": {"position": )" + p(278, 273, -800) + R"(, "look_at": )" + p(278, 273, 0) +
           R"(, "vfov": 39.3}, "objects": [
        {"type": "mesh", "file": ")" + meshes + R"(cbox.obj", "transform": {"scale": )" + s + R"(}},
        {"type": "mesh", "file": ")" + meshes + R"(cbox_blocks.obj", "transform": {"scale": )" + s + R"(}}]})";
}

}  // namespace

TEST_CASE("the Cornell box at scales from 1e-6 to 1e6 renders without NaN") {
    for (double scale : {1e-6, 1e-3, 1e3, 1e6}) {
        CAPTURE(scale);
        Render r = render(cbox_scaled(scale), "scale");
        CHECK(r.exit_code == 0);
        CHECK(r.stats.find("\"nonfinite_samples\": 0") != std::string::npos);
    }
}

TEST_CASE("a camera inside a sphere, inside a closed mesh, and looking along its up vector") {
    const std::string inside_sphere = R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, -1]},
        "materials": {"white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 5, "material": "white"}],
        "lights": [{"type": "point", "position": [1, 1, 1], "intensity": [10, 10, 10]}]})";
    Render r = render(inside_sphere, "inside_sphere");
    CHECK(r.exit_code == 0);
    CHECK(r.stats.find("\"nonfinite_samples\": 0") != std::string::npos);

    const std::string inside_block = R"({"camera": {"position": [185, 80, 170], "look_at": [185, 80, 600]},
        "objects": [{"type": "mesh", "file": ")" + source_path("assets/meshes/cbox.obj") + R"("},
                    {"type": "mesh", "file": ")" + source_path("assets/meshes/cbox_blocks.obj") + R"("}]})";
    r = render(inside_block, "inside_mesh", "-m 1");
    CHECK(r.exit_code == 0);
    CHECK(r.stats.find("\"nonfinite_samples\": 0") != std::string::npos);

    for (const char* look : {"[0, 10, 0]", "[0, -10, 0]"}) {
        CAPTURE(look);
        const std::string straight_up = R"({"camera": {"position": [0, 0, 0], "look_at": )" + std::string(look) +
                                        R"(, "up": [0, 1, 0]},
            "materials": {"white": {"type": "diffuse"}},
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 50, "material": "white"}],
            "lights": [{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]}]})";
        r = render(straight_up, "straight_up");
        CHECK(r.exit_code == 0);
    }
}

TEST_CASE("meshes with NaN vertices or out-of-range indices are clear errors") {
    std::string dir = scratch_dir("input_bad_mesh");
    write_file(dir + "/nan.obj", "v 0 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\n");
    write_file(dir + "/range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    write_file(dir + "/negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9\n");
    for (const char* mesh : {"nan", "range", "negative"}) {
        CAPTURE(mesh);
        CommandResult r = run("'" + bin_path("pathtracer") + "' -q -r 8 8 -f " + dir + "/x.png " + dir + "/" + mesh + ".obj", dir);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(std::string(mesh) + ".obj") != std::string::npos);
    }
}
