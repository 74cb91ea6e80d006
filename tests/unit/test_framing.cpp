// Auto-framing (scene/framing.h): a bare OBJ of an open box or a room is
// seen from inside, a closed object from the default side (issue 22: the
// Cornell box's OBJ used to render the outside of its back wall, black).
#include <doctest/doctest.h>

#include "scene/framing.h"
#include "scene/mesh.h"
#include "scene/scene_loader.h"
#include "test_util.h"

using namespace pt;

namespace {

/// The 12 triangles of the unit cube [0,1]^3, normals outward (or inward),
/// without the faces listed in `missing` ("-z" is the face at z = 0).
Scene cube(bool inward, const std::string& missing = "") {
    Scene scene;
    scene.materials.push_back(Material{});
    MeshData mesh;
    mesh.material = 0;
    for (int i = 0; i < 8; ++i) mesh.positions.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    // Each face as four corners counter-clockwise seen from outside.
    struct Face {
        const char* name;
        uint32_t a, b, c, d;
    };
    const Face faces[] = {{"-x", 0, 4, 6, 2}, {"+x", 1, 3, 7, 5}, {"-y", 0, 1, 5, 4},
                          {"+y", 2, 6, 7, 3}, {"-z", 0, 2, 3, 1}, {"+z", 4, 5, 7, 6}};
    for (const Face& f : faces) {
        if (missing.find(f.name) != std::string::npos) continue;
        if (inward) {
            mesh.faces.push_back({f.a, f.c, f.b});
            mesh.faces.push_back({f.a, f.d, f.c});
        } else {
            mesh.faces.push_back({f.a, f.b, f.c});
            mesh.faces.push_back({f.a, f.c, f.d});
        }
    }
    add_mesh(scene, mesh, Transform());
    scene.finalize();
    return scene;
}

}  // namespace

TEST_CASE("a closed cube with outward normals is framed from the default side") {
    Framing f = choose_framing(cube(false));
    CHECK(std::string(f.reason) == "default view");
    CHECK_FALSE(f.inside);
    CHECK((f.from - default_view_direction()).norm() < 1e-12);
}

TEST_CASE("an open box with inward normals is seen through its open side") {
    // The Cornell box's way: inward normals, the -z wall missing.
    Framing f = choose_framing(cube(true, "-z"));
    CHECK(std::string(f.reason) == "open side");
    CHECK((f.from - Vec3(0, 0, -1)).norm() < 1e-12);
    Scene s = cube(true, "-z");
    s.camera.aspect = 4.0 / 3;
    frame_camera_on_scene(s.camera, s);
    CHECK(s.camera.position.z < 0);  // outside the open side, looking in
    // An open box lying on its back (open upwards) is seen from above and in front.
    f = choose_framing(cube(true, "+y"));
    CHECK(f.from.y > 0.8);
    CHECK(f.from.z > 0.3);
}

TEST_CASE("a closed room (inward normals) is seen from its centre") {
    Scene s = cube(true);
    Framing f = choose_framing(s);
    CHECK(std::string(f.reason) == "inside a closed room");
    s.camera.aspect = 1;
    frame_camera_on_scene(s.camera, s);
    CHECK((s.camera.position - Vec3(0.5)).norm() < 1e-12);
}

TEST_CASE("the Cornell box OBJ is framed through its open front") {
    Scene s = load_scene(pt::test::source_path("assets/meshes/cbox.obj"));
    CHECK(std::string(choose_framing(s).reason) == "open side");
    CHECK(s.camera.position.z < 0);  // the box spans z = 0 .. 559.2, open at z = 0
}
