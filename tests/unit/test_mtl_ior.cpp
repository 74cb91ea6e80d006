// Ni in MTL files (issue 22): glass without Ni is 1.5, Ni as given
// otherwise; a negative Ni is an error (tests/cli/test_unsafe_inputs.cpp),
// Ni 0 on a material that does not refract is ignored, as exporters write it.
#include <doctest/doctest.h>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "test_util.h"

using namespace pt;
using namespace pt::test;

TEST_CASE("glass takes Ni, or 1.5 without it; Ni 0 is harmless on diffuse materials") {
    std::string dir = scratch_dir("mtl_ior");
    write_file(dir + "/m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                               "usemtl water\nf 1 2 3\nusemtl plain_glass\nf 1 2 4\nusemtl wall\nf 1 3 4\n");
    write_file(dir + "/m.mtl", "newmtl water\nillum 7\nNi 1.33\n"
                               "newmtl plain_glass\nillum 4\n"
                               "newmtl wall\nKd 0.5 0.5 0.5\nNi 0.000000\n");
    Scene s = load_scene(dir + "/m.obj");
    REQUIRE(s.triangles.size() == 3);
    CHECK(s.material_of(0).type == MaterialType::glass);
    CHECK(s.material_of(0).ior == doctest::Approx(1.33).epsilon(1e-6));
    CHECK(s.material_of(1).type == MaterialType::glass);
    CHECK(s.material_of(1).ior == 1.5);
    CHECK(s.material_of(2).type == MaterialType::diffuse);

    write_file(dir + "/m.mtl", "newmtl water\nillum 7\nNi nan\n");
    CHECK_THROWS_WITH_AS(load_scene(dir + "/m.obj"), doctest::Contains("line 3: Ni (index of refraction of 'water')"),
                         InputError);
}
