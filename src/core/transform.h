// Transform: the affine map of the scene format, applied in this order:
// scale (uniform or per axis), then rotate (axis-angle, degrees), then
// translate. p' = R (S p) + T.
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/vec3.h"

namespace pt {

struct Transform {
    Vec3 scale{1, 1, 1};
    Vec3 rows[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  ///< the rotation R, row by row
    Vec3 translate{0, 0, 0};

    /// Rotation by `angle_degrees` about the unit `axis` (Rodrigues' formula).
    void set_rotation(const Vec3& axis, double angle_degrees) {
        Vec3 a = axis.unit();
        double c = std::cos(radians(angle_degrees)), s = std::sin(radians(angle_degrees));
        double k = 1 - c;
        rows[0] = {c + a.x * a.x * k, a.x * a.y * k - a.z * s, a.x * a.z * k + a.y * s};
        rows[1] = {a.y * a.x * k + a.z * s, c + a.y * a.y * k, a.y * a.z * k - a.x * s};
        rows[2] = {a.z * a.x * k - a.y * s, a.z * a.y * k + a.x * s, c + a.z * a.z * k};
    }
    Vec3 rotate(const Vec3& v) const { return {dot(rows[0], v), dot(rows[1], v), dot(rows[2], v)}; }
    Vec3 point(const Vec3& p) const { return rotate(p * scale) + translate; }
    Vec3 vector(const Vec3& v) const { return rotate(v * scale); }
    /// Normals transform by the inverse transpose: R S^-1 n, renormalised.
    Vec3 normal(const Vec3& n) const { return rotate(n / scale).unit(); }
    bool is_uniform_scale() const { return scale.x == scale.y && scale.y == scale.z; }
};

}  // namespace pt
