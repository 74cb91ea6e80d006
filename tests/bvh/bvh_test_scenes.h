// Scenes and rays for the BVH tests: small meshes chosen for their hard
// cases (shared edges, coincident faces, axis-aligned planes), and ray sets
// aimed at them.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "scene/mesh.h"
#include "scene/scene.h"
#include "scene/scene_loader.h"

namespace pt::test {

/// A scene with one grey material and no camera work: only geometry.
inline Scene empty_scene() {
    Scene scene;
    scene.name = "test";
    Material grey;
    grey.name = "grey";
    scene.materials.push_back(grey);
    return scene;
}

inline void add_triangle(Scene& scene, const Vec3& a, const Vec3& b, const Vec3& c) {
    uint32_t base = uint32_t(scene.positions.size());
    scene.positions.insert(scene.positions.end(), {a, b, c});
    TriangleRecord r{{base, base + 1, base + 2}, {kNoIndex, kNoIndex, kNoIndex}, 0};
    scene.triangles.push_back(r);
}

inline void add_sphere(Scene& scene, const Vec3& center, double radius) {
    scene.spheres.push_back({{center, radius}, 0});
}

/// A (2,3) torus knot of 2 * segments * sides triangles with smooth normals.
inline Scene knot_scene(int segments = 100, int sides = 8) {
    Scene scene = empty_scene();
    add_mesh(scene, make_torus_knot(2, 3, 1.0, 0.25, segments, sides), Transform());
    scene.finalize();
    return scene;
}

/// Unit cubes on an integer lattice, in a checkerboard-free 3x3x3 block
/// with holes: every triangle is axis-aligned, neighbouring cubes have
/// coincident faces (exact ties), and all vertices lie on grid planes.
inline Scene cubes_scene() {
    Scene scene = empty_scene();
    MeshData cube;
    for (int i = 0; i < 8; ++i)
        cube.positions.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    const uint32_t faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                   {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                   {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& f : faces)
        cube.faces.push_back({f[0], f[1], f[2]});
    for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 3; ++y)
            for (int z = 0; z < 3; ++z) {
                if ((x + 2 * y + z) % 4 == 3) continue;  // some holes
                Transform t;
                t.translate = Vec3(x, y, z);
                add_mesh(scene, cube, t);
            }
    scene.finalize();
    return scene;
}

/// The knot with spheres around and inside it (mixed primitive types).
inline Scene knot_and_spheres_scene() {
    Scene scene = empty_scene();
    add_mesh(scene, make_torus_knot(2, 3, 1.0, 0.25, 60, 6), Transform());
    Rng rng(7);
    for (int i = 0; i < 40; ++i) {
        Vec3 c(rng.next_1d() * 3 - 1.5, rng.next_1d() * 3 - 1.5, rng.next_1d() * 2 - 1);
        add_sphere(scene, c, 0.02 + 0.2 * rng.next_1d());
    }
    scene.finalize();
    return scene;
}

/// Triangles whose normal cannot be normalised among ordinary ones, in the
/// same leaves: the ogre's case (its degenerate triangles are tested through
/// the stage's routine, not the leaf blocks). Around the origin, at scale
/// 1e-70, ordinary triangles with edges of about 1e-70 and `tiny` ones with
/// edges of about 1e-83, whose normal's squared length underflows to 0 (so
/// n / |n| is not finite) while the ray's determinant (about 1e-166) does
/// not; all with vertex normals, so that the reference routine reports hits
/// on the tiny ones too. Around them, the knot. `tiny` receives their ids.
inline Scene tiny_triangles_scene(std::vector<uint32_t>& tiny) {
    Scene scene = empty_scene();
    add_mesh(scene, make_torus_knot(2, 3, 1.0, 0.25, 30, 6), Transform());
    Rng rng(11);
    auto random_vec = [&](double scale) {
        return scale * Vec3(rng.next_1d() * 2 - 1, rng.next_1d() * 2 - 1, rng.next_1d() * 2 - 1);
    };
    for (int i = 0; i < 400; ++i) {
        const bool is_tiny = i % 5 == 0;
        const double edge = is_tiny ? 1e-83 : 1e-70;
        Vec3 c = random_vec(1e-69);
        uint32_t base = uint32_t(scene.positions.size()), nbase = uint32_t(scene.normals.size());
        scene.positions.insert(scene.positions.end(), {c + random_vec(edge), c + random_vec(edge), c + random_vec(edge)});
        for (int k = 0; k < 3; ++k)
            scene.normals.push_back(sample_uniform_sphere(rng.next_2d()));
        if (is_tiny) tiny.push_back(uint32_t(scene.triangles.size()));
        scene.triangles.push_back({{base, base + 1, base + 2}, {nbase, nbase + 1, nbase + 2}, 0});
    }
    scene.finalize();
    return scene;
}

/// The Cornell box of assets/ (walls, light and two blocks).
inline Scene cbox_scene() {
    return load_scene(std::string(PT_SOURCE_DIR) + "/assets/scenes/cbox.json");
}

/// Points on the scene's surfaces that rays should be aimed at: vertices,
/// points on edges (shared by two triangles) and triangle centres.
inline std::vector<Vec3> targets(const Scene& scene, Rng& rng) {
    std::vector<Vec3> out;
    for (uint32_t i = 0; i < scene.triangles.size(); ++i) {
        Triangle t = scene.triangle(i);
        out.push_back(t.p0);
        out.push_back(t.p0 + 0.5 * (t.p1 - t.p0));            // edge midpoint
        out.push_back(t.p1 + rng.next_1d() * (t.p2 - t.p1));  // anywhere on an edge
        out.push_back((t.p0 + t.p1 + t.p2) / 3.0);
    }
    for (const SphereRecord& s : scene.spheres)
        out.push_back(s.sphere.center + Vec3(s.sphere.radius, 0, 0));
    return out;
}

/// A zero of random sign: +0.0 or -0.0.
inline double signed_zero(Rng& rng) {
    return rng.next_1d() < 0.5 ? 0.0 : -0.0;
}

/// `count` rays of all kinds: random lines through the scene's box, rays
/// aimed at vertices and edges, axis-aligned rays starting on grid planes
/// and box faces (with +0.0 and -0.0 in the zero components), and some with
/// shortened intervals.
inline std::vector<Ray> test_rays(const Scene& scene, int count, uint64_t seed) {
    Rng rng(seed);
    std::vector<Vec3> aims = targets(scene, rng);
    const BBox& b = scene.bounds;
    Vec3 lo = b.min - 0.25 * b.extent(), size = 1.5 * b.extent();
    auto random_point = [&] {
        return lo + Vec3(rng.next_1d(), rng.next_1d(), rng.next_1d()) * size;
    };
    // Grid coordinates: the box's faces and, for lattice scenes, the integers.
    auto grid_coordinate = [&](int axis) {
        double choices[4] = {b.min[axis], b.max[axis],
                             std::floor(b.min[axis] + rng.next_1d() * b.extent()[axis]),
                             b.min[axis] + rng.next_1d() * b.extent()[axis]};
        return choices[rng.next_index(4)];
    };
    std::vector<Ray> rays;
    rays.reserve(size_t(count));
    for (int i = 0; i < count; ++i) {
        Ray ray;
        switch (i % 4) {
            case 0: {  // random line
                ray.o = random_point();
                ray.d = sample_uniform_sphere(rng.next_2d());
                break;
            }
            case 1: {  // aimed at a vertex, an edge or a centre
                Vec3 target = aims[rng.next_index(uint32_t(aims.size()))];
                ray.o = random_point();
                ray.d = target - ray.o;
                if (rng.next_1d() < 0.5) ray.d = ray.d.unit();
                break;
            }
            case 2: {  // axis-aligned, starting on grid planes and box faces
                int axis = int(rng.next_index(3));
                for (int a = 0; a < 3; ++a) {
                    ray.o[a] = a == axis ? lo[a] + rng.next_1d() * size[a] : grid_coordinate(a);
                    ray.d[a] = signed_zero(rng);
                }
                ray.d[axis] = rng.next_1d() < 0.5 ? 1.0 : -1.0;
                break;
            }
            default: {  // along a box face or grid plane: one zero component
                int axis = int(rng.next_index(3));
                ray.o = random_point();
                ray.o[axis] = grid_coordinate(axis);
                ray.d = sample_uniform_sphere(rng.next_2d());
                ray.d[axis] = signed_zero(rng);
                break;
            }
        }
        if (rng.next_1d() < 0.1) {  // shortened interval, as for shadow rays
            ray.t_min = rng.next_1d() * 0.1;
            ray.t_max = rng.next_1d() * 2.0 * b.extent().norm();
        }
        rays.push_back(ray);
    }
    return rays;
}

}  // namespace pt::test
