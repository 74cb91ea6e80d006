// The slab test (reference::bbox_intersect) on its hard cases: zero and
// -0.0 direction components, origins on the box's faces, boxes behind the
// ray, infinite intervals; and the student stubs' behaviour.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include "bvh_check.h"
#include "core/error.h"
#include "render/integrators.h"
#include "stages/render_context.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "stages/bvh_wide.h"
#include "stages/bvh_wide_slab.h"

using namespace pt;
using namespace pt::test;

namespace {

const BBox kUnit(Vec3(0, 0, 0), Vec3(1, 1, 1));

bool hits(const Ray& ray, double* t0_out = nullptr, double* t1_out = nullptr) {
    double t0 = ray.t_min, t1 = ray.t_max;
    bool hit = reference::bbox_intersect(kUnit, ray, t0, t1);
    if (hit) {
        CHECK_FALSE(std::isnan(t0));
        CHECK_FALSE(std::isnan(t1));
        CHECK(t0 <= t1);
    }
    if (t0_out) *t0_out = t0;
    if (t1_out) *t1_out = t1;
    return hit;
}

}  // namespace

TEST_CASE("slab test: entry and exit distances") {
    double t0, t1;
    REQUIRE(hits(Ray(Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0)), &t0, &t1));
    CHECK(t0 == 1.0);
    CHECK(t1 == doctest::Approx(2.0).epsilon(1e-14));
    REQUIRE(hits(Ray(Vec3(0.5, 0.5, 0.5), Vec3(0, 0, -1)), &t0, &t1));
    CHECK(t0 == 0.0);  // inside: the interval starts at t_min
    CHECK(t1 == doctest::Approx(0.5).epsilon(1e-14));
    CHECK_FALSE(hits(Ray(Vec3(2, 0.5, 0.5), Vec3(1, 0, 0))));           // box behind
    CHECK_FALSE(hits(Ray(Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0), 0, 0.5)));  // t_max before the box
    CHECK_FALSE(hits(Ray(Vec3(-1, 0.5, 0.5), Vec3(1, 0, 0), 2.5)));     // t_min after it
}

TEST_CASE("slab test: zero and -0.0 direction components") {
    for (double zero : {0.0, -0.0}) {
        CAPTURE(zero);
        // Parallel to the x slabs, inside them, outside them, on their planes.
        CHECK(hits(Ray(Vec3(0.5, -1, 0.5), Vec3(zero, 1, zero))));
        CHECK_FALSE(hits(Ray(Vec3(1.5, -1, 0.5), Vec3(zero, 1, zero))));
        CHECK_FALSE(hits(Ray(Vec3(-0.5, -1, 0.5), Vec3(zero, 1, zero))));
        CHECK(hits(Ray(Vec3(0.0, -1, 0.5), Vec3(zero, 1, zero))));  // on the plane x = 0: 0 * inf
        CHECK(hits(Ray(Vec3(1.0, -1, 1.0), Vec3(zero, 1, zero))));  // along an edge
        CHECK(hits(Ray(Vec3(-0.0, -1, 0.0), Vec3(zero, 1, -zero))));
        // Two zero components: a ray along a coordinate axis.
        CHECK(hits(Ray(Vec3(0.5, 0.5, 5), Vec3(zero, -zero, -1))));
        CHECK_FALSE(hits(Ray(Vec3(0.5, 1.5, 5), Vec3(zero, -zero, -1))));
        // A zero direction (a degenerate ray): inside the box or not.
        CHECK(hits(Ray(Vec3(0.5, 0.5, 0.5), Vec3(zero, zero, zero))));
        CHECK_FALSE(hits(Ray(Vec3(0.5, 0.5, 1.5), Vec3(zero, zero, zero))));
    }
}

TEST_CASE("flat BVH: rays in the plane of a flat box and along its faces") {
    // A 10 x 10 grid in z = 0: every box is flat in z.
    Scene grid = empty_scene();
    for (int x = 0; x < 10; ++x)
        for (int y = 0; y < 10; ++y) {
            add_triangle(grid, Vec3(x, y, 0), Vec3(x + 1, y, 0), Vec3(x + 1, y + 1, 0));
            add_triangle(grid, Vec3(x, y, 0), Vec3(x + 1, y + 1, 0), Vec3(x, y + 1, 0));
        }
    grid.finalize();
    auto bvh = make_reference_bvh(grid, kReference, AcceleratorSettings());
    for (double zero : {0.0, -0.0}) {
        // Straight down onto a grid vertex, an edge and a face, from z = 1.
        for (Vec3 p : {Vec3(3, 4, 1), Vec3(3.5, 4, 1), Vec3(3.25, 4.5, 1)}) {
            std::optional<Hit> hit = bvh->intersect(Ray(p, Vec3(zero, -zero, -1)));
            REQUIRE(hit.has_value());
            CHECK(hit->t == 1.0);
            CHECK(bvh->occluded(Ray(p, Vec3(zero, zero, -1))));
        }
        // In the plane of the grid: parallel to every triangle, so no hit.
        CHECK_FALSE(bvh->intersect(Ray(Vec3(-1, 4.5, 0), Vec3(1, zero, zero))).has_value());
        CHECK_FALSE(bvh->intersect(Ray(Vec3(-1, 4.5, zero), Vec3(1, 0.5, zero))).has_value());
        // Beside the grid, parallel to it, with an infinite interval.
        CHECK_FALSE(bvh->intersect(Ray(Vec3(-1, 4.5, 1), Vec3(1, zero, zero))).has_value());
        CHECK_FALSE(bvh->occluded(Ray(Vec3(-1, 4.5, -1), Vec3(1, zero, zero))));
    }
}

TEST_CASE("student stubs: bbox_intersect says it is not implemented") {
    double t0 = 0, t1 = 1;
    CHECK_THROWS_AS(student::bbox_intersect(kUnit, Ray(Vec3(0, 0, 0), Vec3(1, 0, 0)), t0, t1),
                    NotImplemented);
}

TEST_CASE("student stubs: the linear-scan fallback gives the reference image") {
    Scene scene = load_scene(std::string(PT_SOURCE_DIR) + "/assets/scenes/cbox_knot.json");
    scene.film_width = 48;
    scene.film_height = 36;
    scene.camera.aspect = 48.0 / 36.0;
    scene.camera.finalize();
    RenderSettings settings;
    auto integrator = make_normals_integrator();
    auto render_with = [&](StageSet student) {
        Stages stages = make_stages(student);
        auto accel = build_accelerator(scene, stages, AcceleratorSettings());
        RenderContext context{scene, *accel, stages, settings, *integrator};
        RenderOptions options;
        options.threads = 2;
        return render_image(context, options).image;
    };
    Image reference = render_with(StageSet::none());
    Image student = render_with(StageSet::none().with(Stage::bvh));
    CHECK(reference.data() == student.data());
}

TEST_CASE("flat BVH: rays and scenes at the edges of float range") {
    // Tiny direction components (1/d overflows float), origins far away
    // (visited without culling), and a scene beyond 1e30 (likewise).
    Scene knot = knot_scene(40, 6);
    std::vector<Ray> rays = test_rays(knot, 3000, 5);
    Rng rng(11);
    for (Ray& r : rays) {
        double u = rng.next_1d();
        if (u < 0.25)
            r.d.x = std::copysign(1e-40, r.d.x);
        else if (u < 0.5)
            r.d.y = 1e-300;
        else if (u < 0.6)
            r.o = r.o + 1e35 * r.d.unit() * -1.0;  // far behind, same line
    }
    Expected expected = linear_answers(knot, rays);
    auto hits = [](const Expected& e) {
        return std::count_if(e.hits.begin(), e.hits.end(), [](auto& h) { return h.has_value(); });
    };
    CHECK(hits(expected) > 500);
    check_agrees(*make_reference_bvh(knot, kReference, AcceleratorSettings()), rays, expected);

    Scene far = empty_scene();
    Transform shift;
    shift.translate = Vec3(1e31, -3e31, 0);
    add_mesh(far, make_torus_knot(2, 3, 1e29, 2e28, 40, 6), shift);
    far.finalize();
    rays = test_rays(far, 3000, 6);
    expected = linear_answers(far, rays);
    CHECK(hits(expected) > 500);
    check_agrees(*make_reference_bvh(far, kReference, AcceleratorSettings()), rays, expected);
}

TEST_CASE("float_down and float_up round to the neighbouring floats") {
    Rng rng(3);
    int bad = 0;
    const double specials[] = {0.0,    -0.0,    1e-45, -1e-45, 1e-300, -1e-300,
                               3.5e38, -3.5e38, 1e39,  -1e39,  0.1,    1.0};
    for (int i = 0; i < 100000; ++i) {
        double x = i < 12 ? specials[i]
                          : std::ldexp(2 * rng.next_1d() - 1, int(rng.next_index(300)) - 150);
        float f = float(x);
        float down = double(f) > x ? std::nextafter(f, -INFINITY) : f;
        float up = double(f) < x ? std::nextafter(f, INFINITY) : f;
        bad += !(float_down(x) == down && float_up(x) == up && double(float_down(x)) <= x &&
                 double(float_up(x)) >= x);
    }
    CHECK(bad == 0);
}

namespace {
/// The AVX2 set-up called from a function compiled for AVX2 (as the traversal does).
[[gnu::target("avx2"), gnu::noinline]] bvh_kernels::SlabRay run_make_slab_ray_avx(const Ray& ray, bool float_scene) {
    return bvh_kernels::make_slab_ray_avx(ray, float_scene);
}
}  // namespace

TEST_CASE("8-wide BVH: the branch-free AVX2 ray set-up gives the scalar SlabRay bit for bit") {
    // make_slab_ray_avx (stages/bvh_wide_slab.h) against SlabRay's
    // constructor on random rays whose components are drawn from the hard
    // values (signed zeros, float underflow and overflow of 1/d, origins
    // exactly on floats, beyond 1e30 and beyond float range, infinities,
    // NaN) and random magnitudes; every field compared bit for bit.
    if (!wide_bvh_has_avx()) return;
    const double specials[] = {0.0,    -0.0,   1e-45,  -1e-45, 1e-40,    -1e-40,   1e-300,    -1e-300,
                               3.5e38, -3.5e38, 1e39,  -1e39,  1e31,     -1e31,    0.5,       -0.25,
                               1.0,    0.1,    -0.1,   1e-8,   INFINITY, -INFINITY, std::nan("")};
    const int n_specials = int(sizeof specials / sizeof specials[0]);
    Rng rng(17);
    auto component = [&]() {
        if (rng.next_1d() < 0.3) return specials[rng.next_index(uint32_t(n_specials))];
        return std::ldexp(2 * rng.next_1d() - 1, int(rng.next_index(80)) - 40);
    };
    int bad = 0;
    for (int i = 0; i < 200000; ++i) {
        Ray ray(Vec3(component(), component(), component()), Vec3(component(), component(), component()),
                rng.next_1d() < 0.5 ? 0.0 : std::fabs(component()));
        const bool float_scene = rng.next_1d() < 0.8;
        const bvh_kernels::SlabRay a(ray, float_scene);
        const bvh_kernels::SlabRay b = run_make_slab_ray_avx(ray, float_scene);
        bool same = std::memcmp(a.o_near, b.o_near, sizeof a.o_near) == 0 &&
                    std::memcmp(a.o_far, b.o_far, sizeof a.o_far) == 0 &&
                    std::memcmp(a.inv_near, b.inv_near, sizeof a.inv_near) == 0 &&
                    std::memcmp(a.inv_far, b.inv_far, sizeof a.inv_far) == 0 &&
                    std::memcmp(a.near_plane, b.near_plane, sizeof a.near_plane) == 0 &&
                    std::memcmp(a.far_plane, b.far_plane, sizeof a.far_plane) == 0 &&
                    std::memcmp(a.negative, b.negative, sizeof a.negative) == 0 &&
                    std::memcmp(&a.t_min, &b.t_min, sizeof a.t_min) == 0;
        if (!same && bad < 5) {
            MESSAGE("differs: o = " << ray.o.x << ", " << ray.o.y << ", " << ray.o.z << "  d = " << ray.d.x << ", "
                                    << ray.d.y << ", " << ray.d.z << "  float_scene " << float_scene);
        }
        bad += !same;
    }
    CHECK(bad == 0);
}
