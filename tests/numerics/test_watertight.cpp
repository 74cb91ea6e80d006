// Watertightness: rays from inside a closed mesh, aimed exactly at its
// shared edges and vertices, must hit it. Plain Moller-Trumbore can leak
// there; the watertight test (Woop et al. 2013) never does.
#include <doctest/doctest.h>

#include <cmath>

#include "closed_meshes.h"
#include "stages/accelerator.h"
#include "stages/bvh.h"
#include "stages/stages.h"
#include "stages/intersect.h"

using namespace pt;

namespace {

struct LeakCount {
    int edge_rays = 0, edge_misses = 0;
    int vertex_rays = 0, vertex_misses = 0;
};

/// Rays from `origin` (inside the mesh) towards points on random shared
/// edges (s in (0, 1)) and exactly at vertices; counts the rays that hit
/// nothing. Traced with the reference BVH (bit-identical to the linear scan,
/// tests/bvh), so a million rays take a second.
LeakCount count_leaks(const Scene& scene, IntersectTriangleFn triangle_test, const Vec3& origin, int rays,
                      uint64_t seed) {
    IntersectStage stage{triangle_test, reference::intersect_sphere};
    std::unique_ptr<Accelerator> scan = make_reference_bvh(scene, stage, AcceleratorSettings());
    Rng rng(seed);
    LeakCount count;
    for (int i = 0; i < rays; ++i) {
        const TriangleRecord& tri = scene.triangles[rng.next_index(uint32_t(scene.triangles.size()))];
        int k = int(rng.next_index(3));
        Vec3 a = scene.positions[tri.v[k]], b = scene.positions[tri.v[(k + 1) % 3]];
        // Every fourth ray aims exactly at a vertex, the others at an edge.
        bool at_vertex = i % 4 == 0;
        Vec3 target = at_vertex ? a : a + (b - a) * rng.next_1d();
        bool miss = !scan->intersect(Ray(origin, target - origin));
        (at_vertex ? count.vertex_rays : count.edge_rays)++;
        (at_vertex ? count.vertex_misses : count.edge_misses) += miss;
    }
    return count;
}

}  // namespace

TEST_CASE("watertight triangle test agrees with Moller-Trumbore away from edges") {
    Triangle tri;
    tri.p0 = Vec3(0, 0, 0);
    tri.p1 = Vec3(2, 0, 0.5);
    tri.p2 = Vec3(0, 1, 1);
    Rng rng(9);
    int compared = 0;
    for (int i = 0; i < 10000; ++i) {
        // Rays from above aimed at uniformly chosen points of the triangle.
        Vec3 o(rng.next_1d() * 4 - 1, rng.next_1d() * 4 - 1, 3 + rng.next_1d());
        double r1 = rng.next_1d(), r2 = rng.next_1d();
        if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
        Vec3 d = (tri.p0 + r1 * (tri.p1 - tri.p0) + r2 * (tri.p2 - tri.p0) - o).unit();
        std::optional<Hit> m = reference::intersect_triangle(tri, Ray(o, d));
        std::optional<Hit> w = reference::intersect_triangle_watertight(tri, Ray(o, d));
        if (m && w) {
            ++compared;
            CHECK(w->t == doctest::Approx(m->t).epsilon(1e-12));
            CHECK(w->b1 == doctest::Approx(m->b1).epsilon(1e-9).scale(1));
            CHECK(w->b2 == doctest::Approx(m->b2).epsilon(1e-9).scale(1));
            CHECK(w->n == m->n);
        } else if (m || w) {
            // Verdicts may differ only within rounding of an edge.
            const Hit& h = m ? *m : *w;
            CHECK(std::min({h.b1, h.b2, 1 - h.b1 - h.b2}) < 1e-12);
        }
    }
    CHECK(compared > 9900);
}

TEST_CASE("watertight test: degenerate and edge-on triangles never hit and never give NaN") {
    Triangle line;
    line.p1 = Vec3(1, 1, 0);
    line.p2 = Vec3(2, 2, 0);
    CHECK_FALSE(reference::intersect_triangle_watertight(line, Ray(Vec3(1, 1, 1), Vec3(0, 0, -1))));
    Triangle flat;
    flat.p1 = Vec3(1, 0, 0);
    flat.p2 = Vec3(0, 1, 0);
    CHECK_FALSE(reference::intersect_triangle_watertight(flat, Ray(Vec3(-1, 0.2, 0), Vec3(1, 0, 0))));  // in plane
    CHECK_FALSE(reference::intersect_triangle_watertight(flat, Ray(Vec3(0.2, 0.2, 1), Vec3(0, 0, 0))));  // zero direction
}

TEST_CASE("rays through shared edges and vertices of closed meshes: leaks counted, none for the watertight test") {
    struct Case {
        const char* name;
        double scale;
        Vec3 center;
    };
    const Case cases[] = {{"unit sphere", 1.0, Vec3(0, 0, 0)},
                          {"sphere scaled by 1000", 1000.0, Vec3(0, 0, 0)},
                          {"sphere scaled by 1000 and moved to 10^5", 1000.0, Vec3(1e5, -3e4, 2e4)}};
    for (const Case& c : cases) {
        Scene mesh = test::make_jittered_sphere(24, 48, 0.05, c.scale, c.center, 17);
        Vec3 inside = c.center + Vec3(0.1, -0.05, 0.02) * c.scale;
        LeakCount moller = count_leaks(mesh, reference::intersect_triangle, inside, 1000000, 5);
        LeakCount watertight = count_leaks(mesh, reference::intersect_triangle_watertight, inside, 1000000, 5);
        MESSAGE(std::string(c.name) << ", " << mesh.triangles.size() << " triangles: misses of "
                                    << moller.edge_rays << " rays at shared edges / " << moller.vertex_rays
                                    << " at vertices: Moller-Trumbore " << moller.edge_misses << " / "
                                    << moller.vertex_misses << ", watertight " << watertight.edge_misses << " / "
                                    << watertight.vertex_misses);
        CAPTURE(std::string(c.name));
        CHECK(watertight.edge_misses == 0);
        CHECK(watertight.vertex_misses == 0);
    }
}
