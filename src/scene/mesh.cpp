#include "scene/mesh.h"

#include <cmath>

#include "core/math.h"
#include "scene/scene.h"

namespace pt {

void add_mesh(Scene& scene, const MeshData& mesh, const Transform& transform) {
    uint32_t position_base = uint32_t(scene.positions.size());
    uint32_t normal_base = uint32_t(scene.normals.size());
    for (const Vec3& p : mesh.positions) scene.positions.push_back(transform.point(p));
    for (const Vec3& n : mesh.normals) scene.normals.push_back(transform.normal(n));
    bool smooth = !mesh.face_normals.empty();
    // Texture coordinates are kept only once some mesh has them.
    const uint32_t uv_base = uint32_t(scene.uvs.size());
    const bool keep_uvs = !mesh.face_uvs.empty() || !scene.triangle_uvs.empty();
    if (keep_uvs) scene.triangle_uvs.resize(scene.triangles.size(), {kNoIndex, kNoIndex, kNoIndex});
    scene.uvs.insert(scene.uvs.end(), mesh.uvs.begin(), mesh.uvs.end());
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
        TriangleRecord r;
        for (int k = 0; k < 3; ++k) {
            r.v[k] = position_base + mesh.faces[f][k];
            r.n[k] = smooth ? normal_base + mesh.face_normals[f][k] : kNoIndex;
        }
        r.material = mesh.face_materials.empty() ? mesh.material : mesh.face_materials[f];
        scene.triangles.push_back(r);
        if (keep_uvs) {
            std::array<uint32_t, 3> uv = {kNoIndex, kNoIndex, kNoIndex};
            if (!mesh.face_uvs.empty() && mesh.face_uvs[f][0] != kNoIndex)
                for (int k = 0; k < 3; ++k) uv[k] = uv_base + mesh.face_uvs[f][k];
            scene.triangle_uvs.push_back(uv);
        }
    }
}

MeshData make_torus_knot(int p, int q, double radius, double tube_radius, int segments, int sides) {
    // The knot's centre line: the curve ((2 + cos(q t)) cos(p t), (2 + cos(q t)) sin(p t),
    // sin(q t)) scaled to `radius`, a standard torus-knot parametrisation.
    auto curve = [&](double t) {
        double r = radius * (2.0 + std::cos(q * t)) / 3.0;
        return Vec3(r * std::cos(p * t), r * std::sin(p * t), radius * std::sin(q * t) / 3.0);
    };
    MeshData mesh;
    for (int i = 0; i < segments; ++i) {
        double t = kTwoPi * i / segments;
        Vec3 c = curve(t);
        // A frame that turns smoothly along the curve: the tangent T (central
        // differences), N = the radial direction made perpendicular to T (the
        // radial part of T is never all of it, since r >= radius / 3), B = T x N.
        Vec3 tangent = (curve(t + 1e-4) - curve(t - 1e-4)).unit();
        Vec3 radial(std::cos(p * t), std::sin(p * t), 0);
        Vec3 normal = (radial - tangent * dot(radial, tangent)).unit();
        Vec3 binormal = cross(tangent, normal);
        for (int j = 0; j < sides; ++j) {
            double a = kTwoPi * j / sides;
            Vec3 n = normal * std::cos(a) + binormal * std::sin(a);
            mesh.positions.push_back(c + n * tube_radius);
            mesh.normals.push_back(n);
        }
    }
    auto index = [&](int i, int j) { return uint32_t((i % segments) * sides + (j % sides)); };
    for (int i = 0; i < segments; ++i) {
        for (int j = 0; j < sides; ++j) {
            uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
            // Wound so that the geometric normal points out of the tube.
            mesh.faces.push_back({a, c, b});
            mesh.faces.push_back({a, d, c});
        }
    }
    mesh.face_normals = mesh.faces;
    return mesh;
}

}  // namespace pt
