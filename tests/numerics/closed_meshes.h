// Closed test meshes for the watertightness cases: a UV sphere whose
// vertices are jittered radially, so no two triangles are coplanar and
// shared edges run in every direction.
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/rng.h"
#include "scene/mesh.h"
#include "scene/scene.h"

namespace pt::test {

/// A closed UV sphere around `center` (rings x segments quads, fans at the
/// poles), radius 1 +- jitter, scaled by `scale`; every edge is shared by
/// exactly two triangles.
inline Scene make_jittered_sphere(int rings, int segments, double jitter, double scale, const Vec3& center,
                                  uint64_t seed) {
    Scene scene;
    Material grey;
    scene.materials.push_back(grey);
    MeshData mesh;
    Rng rng(seed);
    auto jittered = [&](Vec3 p) { return p * (1.0 + jitter * (2.0 * rng.next_1d() - 1.0)); };
    mesh.positions.push_back(jittered(Vec3(0, 0, 1)));  // north pole
    for (int i = 1; i < rings; ++i) {
        double theta = kPi * i / rings;
        for (int j = 0; j < segments; ++j) {
            double phi = kTwoPi * j / segments;
            mesh.positions.push_back(jittered(Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta))));
        }
    }
    mesh.positions.push_back(jittered(Vec3(0, 0, -1)));  // south pole
    const uint32_t south = uint32_t(mesh.positions.size() - 1);
    auto ring = [&](int i, int j) { return uint32_t(1 + (i - 1) * segments + (j % segments)); };
    for (int j = 0; j < segments; ++j) mesh.faces.push_back({0, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            mesh.faces.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            mesh.faces.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
    for (int j = 0; j < segments; ++j) mesh.faces.push_back({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
    Transform t;
    t.scale = Vec3(scale);
    t.translate = center;
    add_mesh(scene, mesh, t);
    scene.finalize();
    return scene;
}

}  // namespace pt::test
