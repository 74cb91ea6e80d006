// The spatial subdivisions (--accel grid, --accel kdtree) against the linear
// scan: the same closest hit (same primitive, t, b1, b2 and normal, to the
// last bit) and the same any-hit answer, on the BVH tests' hard rays
// (vertices, shared edges, axis-aligned rays on grid planes with +-0.0
// components, shortened intervals); plus the --accel plumbing.
#include <doctest/doctest.h>

#include "bvh_check.h"
#include "core/error.h"
#include "stages/embree_accel.h"
#include "stages/kd_tree.h"
#include "stages/uniform_grid.h"

using namespace pt;
using namespace pt::test;

namespace {

void check_scene(const Scene& scene, int ray_count) {
    std::vector<Ray> rays = test::test_rays(scene, ray_count, 777);
    Expected expected = linear_answers(scene, rays);
    {
        INFO("uniform grid");
        check_agrees(*make_uniform_grid(scene, kReference), rays, expected);
    }
    {
        INFO("SAH kd-tree");
        check_agrees(*make_kd_tree(scene, kReference), rays, expected);
    }
}

}  // namespace

TEST_CASE("grid and kd-tree equal the linear scan: torus knot") {
    check_scene(test::knot_scene(), 20000);
}

TEST_CASE("grid and kd-tree equal the linear scan: lattice of unit cubes (coincident faces, grid planes)") {
    check_scene(test::cubes_scene(), 20000);
}

TEST_CASE("grid and kd-tree equal the linear scan: knot and spheres") {
    check_scene(test::knot_and_spheres_scene(), 20000);
}

TEST_CASE("grid and kd-tree equal the linear scan: Cornell box") {
    check_scene(test::cbox_scene(), 20000);
}

TEST_CASE("grid and kd-tree: no primitives, one primitive, a flat scene") {
    Scene empty = test::empty_scene();
    empty.finalize();
    Ray ray(Vec3(0, 0, -1), Vec3(0, 0, 1));
    CHECK_FALSE(make_uniform_grid(empty, kReference)->intersect(ray));
    CHECK_FALSE(make_kd_tree(empty, kReference)->occluded(ray));

    Scene flat = test::empty_scene();  // 200 triangles in the plane z = 0
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            test::add_triangle(flat, Vec3(i, j, 0), Vec3(i + 1, j, 0), Vec3(i, j + 1, 0));
            test::add_triangle(flat, Vec3(i + 1, j, 0), Vec3(i + 1, j + 1, 0), Vec3(i, j + 1, 0));
        }
    flat.finalize();
    check_scene(flat, 4000);
}

TEST_CASE("--accel names every structure; embree only where built in") {
    for (const char* name : {"none", "grid", "kdtree", "bvh", "embree"})
        CHECK(std::string(to_string(parse_accel_kind(name))) == name);
    CHECK_THROWS_WITH_AS(parse_accel_kind("kd"), "--accel: expected one of none, grid, kdtree, bvh, embree, got 'kd'",
                         InputError);
    Scene scene = test::knot_scene(20, 4);
    Stages stages = make_stages(StageSet{});
    for (AccelKind kind : {AccelKind::none, AccelKind::grid, AccelKind::kdtree, AccelKind::bvh}) {
        AcceleratorSettings settings;
        settings.kind = kind;
        CHECK(build_accelerator(scene, stages, settings) != nullptr);
    }
    AcceleratorSettings embree;
    embree.kind = AccelKind::embree;
    if (!embree_available()) CHECK_THROWS_AS(build_accelerator(scene, stages, embree), InputError);
}
