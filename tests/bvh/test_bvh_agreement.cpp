// Every BVH against the linear scan: the same closest hit (same primitive,
// same t, b1, b2 and normal, to the last bit) for 100,000 rays per mesh,
// and any hit agreeing with closest hit. The reference BVH is 8-wide by
// default (stages/bvh_wide.h); the binary one (--bvh-width 2), the 4-wide
// one, and the portable scalar box tests of both wide ones are checked on
// a fifth of the rays.
#include <doctest/doctest.h>

#include "bvh_check.h"
#include "stages/bvh_wide.h"

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

namespace {

/// The knot's corners rounded to floats (nudge = false: an OBJ mesh as
/// loaded), or moved one double step above those floats (nudge = true:
/// no corner is a float); `shift` moves it first.
MeshData float_grid_knot(bool nudge, const Vec3& shift = Vec3(0, 0, 0)) {
    MeshData knot = make_torus_knot(2, 3, 1.0, 0.25, 60, 8);
    for (Vec3& p : knot.positions) {
        for (int k = 0; k < 3; ++k) {
            const double f = double(float(p[k] + shift[k]));
            p[k] = nudge ? std::nextafter(f, INFINITY) : f;
        }
    }
    return knot;
}

/// A scene of the given meshes, untransformed.
Scene mesh_scene(const std::vector<MeshData>& meshes) {
    Scene scene = empty_scene();
    for (const MeshData& mesh : meshes)
        add_mesh(scene, mesh, Transform());
    scene.finalize();
    return scene;
}

/// Random rays and rows of camera-like rays (so that packets stay together).
std::vector<Ray> float_test_rays(const Scene& scene) {
    std::vector<Ray> rays = test::test_rays(scene, 20000, 4242);
    const BBox& b = scene.bounds;
    const Vec3 eye = b.centroid() + Vec3(-0.2, 0.3, 2.0) * b.extent().norm();
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            Vec3 target(b.min.x + (x + 0.5) / 64 * b.extent().x, b.min.y + (y + 0.5) / 64 * b.extent().y,
                        b.centroid().z);
            rays.push_back(Ray(eye, target - eye));
        }
    return rays;
}

}  // namespace

TEST_CASE("BVH equals the linear scan: corners stored as floats or as doubles") {
    // The 8-wide tree stores a leaf whose corners are all floats as floats
    // (FloatCornerBlock, bvh_leaf_block.h) and any other leaf as doubles;
    // both must give the linear scan's bits, on single rays and packets.
    // The float mesh's blocks take half the bytes: that is how the test
    // knows each path ran (the trees' nodes take the same bytes either way).
    const Scene floats = mesh_scene({float_grid_knot(false)}), doubles = mesh_scene({float_grid_knot(true)});
    AcceleratorSettings settings;  // the default: 8-wide, SIMD
    auto float_bvh = make_reference_bvh(floats, kReference, settings);
    auto double_bvh = make_reference_bvh(doubles, kReference, settings);
    const AcceleratorInfo f = float_bvh->info(), d = double_bvh->info();
    const double f_blocks = double(f.bytes - f.tree_bytes), d_blocks = double(d.bytes - d.tree_bytes);
    if (wide_bvh_has_avx()) {
        INFO("bytes beyond the tree: floats " << f_blocks << ", doubles " << d_blocks);
        CHECK(f_blocks < 0.6 * d_blocks);
    }
    {
        INFO("corners on the float grid");
        const std::vector<Ray> rays = float_test_rays(floats);
        check_agrees(*float_bvh, rays, linear_answers(floats, rays));
    }
    {
        INFO("corners one double step off the float grid");
        const std::vector<Ray> rays = float_test_rays(doubles);
        check_agrees(*double_bvh, rays, linear_answers(doubles, rays));
    }
    {
        // Both kinds of leaf in one tree: a float knot and a nudged one
        // beside it (then each leaf is checked on its own).
        INFO("float and double leaves in one tree");
        const Scene mixed = mesh_scene({float_grid_knot(false), float_grid_knot(true, Vec3(1.5, 0.5, 0.25))});
        auto mixed_bvh = make_reference_bvh(mixed, kReference, settings);
        if (wide_bvh_has_avx()) {  // about half the leaves of each kind
            const AcceleratorInfo m = mixed_bvh->info();
            const double m_blocks = double(m.bytes - m.tree_bytes);
            INFO("bytes beyond the tree: mixed " << m_blocks);
            CHECK(m_blocks > 1.2 * 2 * f_blocks);
            CHECK(m_blocks < 0.9 * 2 * d_blocks);
        }
        const std::vector<Ray> rays = float_test_rays(mixed);
        check_agrees(*mixed_bvh, rays, linear_answers(mixed, rays));
    }
}
