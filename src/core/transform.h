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
    /// The inverse map (instancing: world rays into object space),
    /// S^-1 R^T (p - T); R is orthonormal, so R^-1 = R^T.
    Vec3 inverse_rotate(const Vec3& v) const { return rows[0] * v.x + rows[1] * v.y + rows[2] * v.z; }
    Vec3 inverse_point(const Vec3& p) const { return inverse_rotate(p - translate) / scale; }
    Vec3 inverse_vector(const Vec3& v) const { return inverse_rotate(v) / scale; }
    /// A bound on the absolute error of point(p) per component when p itself
    /// is off by up to p_error (pbrt-v3 section 3.9.4, "transforming points"):
    /// the map's |entries| carry the input error, and the products and sums
    /// add gamma(3) of |M||p| + |T| (with M = R S).
    Vec3 point_error(const Vec3& p, const Vec3& p_error) const {
        Vec3 ap = abs(p * scale), ae = p_error * abs(scale);
        Vec3 carried(dot(abs(rows[0]), ae), dot(abs(rows[1]), ae), dot(abs(rows[2]), ae));
        Vec3 rounding(dot(abs(rows[0]), ap), dot(abs(rows[1]), ap), dot(abs(rows[2]), ap));
        return (1 + gamma(3)) * carried + gamma(4) * (rounding + abs(translate));
    }
    bool is_uniform_scale() const { return scale.x == scale.y && scale.y == scale.z; }
};

}  // namespace pt
