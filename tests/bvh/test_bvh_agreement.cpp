// Every BVH against the linear scan: the same closest hit (same primitive,
// same t, b1, b2 and normal, to the last bit) for 100,000 rays per mesh,
// and any hit agreeing with closest hit. The reference BVH is 8-wide by
// default (stages/bvh_wide.h); the binary one (--bvh-width 2), the 4-wide
// one, and the portable scalar box tests of both wide ones are checked on
// a fifth of the rays.
#include <doctest/doctest.h>

#include "bvh_check.h"

using namespace pt;
using namespace pt::test;

namespace {

/// The 4- and 8-wide reference BVHs, with the SIMD and the scalar box
/// tests, against the linear scan's answers.
void check_wide_agree(const Scene& scene, const std::vector<Ray>& rays, const Expected& expected) {
    for (int width : {4, 8}) {
        for (bool simd : {true, false}) {
            INFO("reference BVH, --bvh-width " << width << (simd ? ", SIMD" : ", scalar") << " box tests");
            AcceleratorSettings wide;
            wide.width = width;
            wide.simd = simd;
            check_agrees(*make_reference_bvh(scene, kReference, wide), rays, expected);
        }
    }
}

void check_scene(const Scene& scene, int ray_count) {
    std::vector<Ray> rays = test::test_rays(scene, ray_count, 12345);
    Expected expected = linear_answers(scene, rays);
    AcceleratorSettings settings;
    {
        INFO("reference BVH, inlined triangle test");
        check_agrees(*make_reference_bvh(scene, kReference, settings), rays, expected);
    }
    {
        INFO("reference BVH, triangle test through the stage table");
        check_agrees(*make_reference_bvh(scene, kCalled, settings), rays, expected);
    }
    {
        INFO("CS184-style tree with the reference functions");
        check_agrees(*make_tree_bvh(scene, kReference, settings, reference::tree_functions()), rays,
                     expected);
    }
    // The other builds on a fifth of the rays: they share the traversal.
    rays.resize(rays.size() / 5);
    {
        INFO("binary reference BVH (--bvh-width 2), inlined and through the table");
        AcceleratorSettings binary = settings;
        binary.width = 2;
        check_agrees(*make_reference_bvh(scene, kReference, binary), rays, expected);
        check_agrees(*make_reference_bvh(scene, kCalled, binary), rays, expected);
    }
    check_wide_agree(scene, rays, expected);
    {
        INFO("reference BVH, inlined watertight triangle test (--triangle watertight)");
        check_agrees(*make_reference_bvh(scene, kWatertight, settings), rays, linear_answers(scene, rays, kWatertight));
    }
    for (const char* split : {"median", "middle"}) {
        for (int max_leaf : {1, 8}) {
            settings.split = split;
            settings.max_leaf = max_leaf;
            INFO("split " << split << ", max_leaf " << max_leaf);
            check_agrees(*make_reference_bvh(scene, kReference, settings), rays, expected);
        }
    }
}

}  // namespace

TEST_CASE("BVH equals the linear scan: torus knot") {
    check_scene(test::knot_scene(), 100000);
}

TEST_CASE("BVH equals the linear scan: lattice of unit cubes (coincident faces, grid planes)") {
    check_scene(test::cubes_scene(), 100000);
}

TEST_CASE("BVH equals the linear scan: knot and spheres") {
    check_scene(test::knot_and_spheres_scene(), 100000);
}

TEST_CASE("BVH equals the linear scan: Cornell box") {
    check_scene(test::cbox_scene(), 100000);
}

TEST_CASE("BVH equals the linear scan: degenerate triangles in the leaves of ordinary ones") {
    // The 8-wide tree tests a leaf's ordinary triangles in its blocks and
    // its degenerate ones through the reference routine (bvh_wide.cpp,
    // kGenericSlots). Besides the usual rays, rays that start 1e-84 from a
    // triangle's centre and run through it (so they can hit the tiny ones).
    std::vector<uint32_t> tiny;
    Scene scene = test::tiny_triangles_scene(tiny);
    std::vector<Ray> rays = test::test_rays(scene, 20000, 777);
    Rng rng(778);
    for (uint32_t prim = 0; prim < scene.triangles.size(); ++prim) {
        const Triangle t = scene.triangle(prim);
        const Vec3 c = (t.p0 + t.p1 + t.p2) / 3.0;
        const double offset = std::binary_search(tiny.begin(), tiny.end(), prim) ? 1e-84 : 1e-69;
        for (int k = 0; k < (c.norm() < 1e-60 ? 40 : 2); ++k) {
            Vec3 u = sample_uniform_sphere(rng.next_2d());
            rays.push_back(Ray(c + offset * u, -u));
        }
    }
    Expected expected = linear_answers(scene, rays);
    int tiny_hits = 0;
    for (const std::optional<Hit>& h : expected.hits)
        tiny_hits += h && std::binary_search(tiny.begin(), tiny.end(), h->primitive) ? 1 : 0;
    INFO("closest hits on the tiny triangles: " << tiny_hits);
    CHECK(tiny_hits >= 100);  // the rays reach the generic path
    check_wide_agree(scene, rays, expected);
}

TEST_CASE("BVH packets of coherent camera-like rays equal the linear scan") {
    // Rays from one point outside the knot through a 96x96 grid spanning its
    // box, in rows: each packet of intersect_packet is 8 neighbouring rays,
    // as camera rays are, so the shared traversal splits and culls rays.
    Scene scene = test::knot_scene();
    const BBox& b = scene.bounds;
    Vec3 eye = b.centroid() + Vec3(0.3, 0.2, 2.0) * b.extent().norm();
    std::vector<Ray> rays;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            Vec3 target(b.min.x + (x + 0.5) / 96 * b.extent().x, b.min.y + (y + 0.5) / 96 * b.extent().y,
                        b.centroid().z);
            rays.push_back(Ray(eye, target - eye));
        }
    Expected expected = linear_answers(scene, rays);
    check_wide_agree(scene, rays, expected);
}
