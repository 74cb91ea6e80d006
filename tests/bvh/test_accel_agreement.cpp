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

namespace {
int g_grid_calls = 0;
std::optional<Hit> counting_grid_intersect(const GridCells& grid, const Ray& ray) {
    ++g_grid_calls;
    return reference::grid_intersect(grid, ray);
}
}  // namespace

TEST_CASE("--accel grid walks with the bvh stage's grid_intersect (Part 2's optional task 6)") {
    Scene scene = test::knot_scene(20, 4);
    Stages stages = make_stages(StageSet{});
    CHECK((stages.bvh.grid_intersect == &reference::grid_intersect));
    CHECK((make_stages(StageSet::of_part(2)).bvh.grid_intersect == &student::grid_intersect));
    stages.bvh.grid_intersect = counting_grid_intersect;
    AcceleratorSettings settings;
    settings.kind = AccelKind::grid;
    std::unique_ptr<Accelerator> grid = build_accelerator(scene, stages, settings);
    std::vector<Ray> rays = test::test_rays(scene, 200, 5);
    Expected expected = linear_answers(scene, rays);
    check_agrees(*grid, rays, expected);
    CHECK(g_grid_calls >= 200);

    // What the student's walk reads: every primitive listed in some cell,
    // nothing outside the cells.
    GridCells cells(scene, kReference);
    std::vector<bool> listed(cells.primitive_count(), false);
    for (int z = 0; z < cells.res[2]; ++z)
        for (int y = 0; y < cells.res[1]; ++y)
            for (int x = 0; x < cells.res[0]; ++x) {
                size_t n = 0;
                const uint32_t* p = cells.cell_primitives(x, y, z, n);
                for (size_t i = 0; i < n; ++i)
                    listed.at(p[i]) = true;
            }
    CHECK(std::count(listed.begin(), listed.end(), false) == 0);
    size_t n = 7;
    CHECK(cells.cell_primitives(cells.res[0], 0, 0, n) == nullptr);
    CHECK(n == 0);
}

TEST_CASE("student stubs: grid_intersect says it is not implemented") {
    Scene scene = test::knot_scene(20, 4);
    GridCells cells(scene, kReference);
    CHECK_THROWS_AS(student::grid_intersect(cells, Ray(Vec3(0, 0, -10), Vec3(0, 0, 1))), NotImplemented);
}
