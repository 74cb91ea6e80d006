#include "scene/scene.h"

#include <cmath>

#include "core/math.h"

namespace pt {

const char* to_string(MaterialType type) {
    switch (type) {
        case MaterialType::diffuse: return "diffuse";
        case MaterialType::mirror: return "mirror";
        case MaterialType::glass: return "glass";
        case MaterialType::microfacet: return "microfacet";
        case MaterialType::rough_dielectric: return "rough_dielectric";
        case MaterialType::null: return "null";
    }
    return "unknown";
}

Triangle Scene::triangle(uint32_t prim) const {
    const TriangleRecord& r = triangles[prim];
    Triangle t;
    t.p0 = positions[r.v[0]];
    t.p1 = positions[r.v[1]];
    t.p2 = positions[r.v[2]];
    if (r.n[0] != kNoIndex) {
        t.has_normals = true;
        t.n0 = normals[r.n[0]];
        t.n1 = normals[r.n[1]];
        t.n2 = normals[r.n[2]];
    }
    return t;
}

bool Scene::has_media() const {
    if (!media.empty()) return true;
    for (const Material& m : materials)
        if (m.type == MaterialType::null) return true;
    return false;
}

const Material& Scene::material_of(uint32_t prim) const {
    if (is_instance(prim)) return materials[instance(prim).material];
    return materials[is_sphere(prim) ? sphere_record(prim).material : triangles[prim].material];
}

Vec2 Scene::uv_at(uint32_t prim, double b1, double b2, const Vec3& p, uint32_t part) const {
    if (is_instance(prim))
        return shape_of(prim).uv_at(part, b1, b2, instance(prim).to_world.inverse_point(p));
    if (is_sphere(prim)) {
        const Sphere& s = sphere_record(prim).sphere;
        Vec3 d = (p - s.center) / s.radius;
        double phi = std::atan2(d.x, d.z);
        if (phi < 0) phi += kTwoPi;
        return {phi * kInvTwoPi, 1.0 - std::acos(clamp(d.y, -1.0, 1.0)) * kInvPi};
    }
    if (prim < triangle_uvs.size() && triangle_uvs[prim][0] != kNoIndex) {
        const std::array<uint32_t, 3>& t = triangle_uvs[prim];
        const double b0 = 1.0 - b1 - b2;
        return {b0 * uvs[t[0]].x + b1 * uvs[t[1]].x + b2 * uvs[t[2]].x,
                b0 * uvs[t[0]].y + b1 * uvs[t[1]].y + b2 * uvs[t[2]].y};
    }
    return {b1 + b2, b2};
}

Vec3 Scene::dpdu(uint32_t prim, const Vec3& p, uint32_t part) const {
    if (is_instance(prim)) {
        const Transform& m = instance(prim).to_world;
        return m.vector(shape_of(prim).dpdu(part, m.inverse_point(p)));
    }
    if (is_sphere(prim)) {
        // The direction of growing longitude (uv_at's u) about +y.
        Vec3 d = p - sphere_record(prim).sphere.center;
        return Vec3(d.z, 0, -d.x);
    }
    Triangle t = triangle(prim);
    Vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0;
    if (prim < triangle_uvs.size() && triangle_uvs[prim][0] != kNoIndex) {
        // Solve e1 = du1 dpdu + dv1 dpdv, e2 = du2 dpdu + dv2 dpdv for dpdu.
        const std::array<uint32_t, 3>& uv = triangle_uvs[prim];
        Vec2 d1(uvs[uv[1]].x - uvs[uv[0]].x, uvs[uv[1]].y - uvs[uv[0]].y);
        Vec2 d2(uvs[uv[2]].x - uvs[uv[0]].x, uvs[uv[2]].y - uvs[uv[0]].y);
        double det = d1.x * d2.y - d1.y * d2.x;
        if (std::fabs(det) > 1e-12) return (e1 * d2.y - e2 * d1.y) / det;
    }
    return e1;
}

BBox Scene::primitive_bounds(uint32_t prim) const {
    if (is_instance(prim)) return instance(prim).bounds;
    if (is_sphere(prim)) {
        const Sphere& s = sphere_record(prim).sphere;
        return BBox(s.center - Vec3(s.radius), s.center + Vec3(s.radius));
    }
    const TriangleRecord& r = triangles[prim];
    BBox b(positions[r.v[0]], positions[r.v[1]]);
    b.expand(positions[r.v[2]]);
    return b;
}

double Scene::primitive_area(uint32_t prim) const {
    if (is_sphere(prim)) {
        double r = sphere_record(prim).sphere.radius;
        return 4.0 * 3.14159265358979323846 * r * r;
    }
    Triangle t = triangle(prim);
    return 0.5 * cross(t.p1 - t.p0, t.p2 - t.p0).norm();
}

void Scene::finalize() {
    emitters.clear();
    bounds = BBox();
    for (uint32_t i = 0; i < primitive_count(); ++i) {
        bounds.expand(primitive_bounds(i));
        if (material_of(i).is_emissive() && primitive_area(i) > 0) emitters.push_back(i);
    }
    // Instances never emit (the loader refuses emissive instance materials).
    for (const InstanceRecord& instance : instances) bounds.expand(instance.bounds);
}

}  // namespace pt
