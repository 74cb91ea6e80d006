// Vec3 and Vec2: small value types for points, directions and normals.
//
// Everything geometric is double precision, as in CS184's Vector3D: a unit
// sphere a million units from the origin still has 10 significant digits of
// room, so the numerics stay simple for students. Only the BVH stores float
// boxes (rounded outward, see stages/bvh.h) to keep its nodes 32 bytes.
#pragma once

#include <algorithm>
#include <cmath>

namespace pt {

struct Vec3 {
    double x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3(double v) : x(v), y(v), z(v) {}

    constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator+(const Vec3& b) const { return {x + b.x, y + b.y, z + b.z}; }
    constexpr Vec3 operator-(const Vec3& b) const { return {x - b.x, y - b.y, z - b.z}; }
    constexpr Vec3 operator*(const Vec3& b) const { return {x * b.x, y * b.y, z * b.z}; }
    constexpr Vec3 operator/(const Vec3& b) const { return {x / b.x, y / b.y, z / b.z}; }
    constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
    Vec3& operator+=(const Vec3& b) { return *this = *this + b; }
    Vec3& operator-=(const Vec3& b) { return *this = *this - b; }
    Vec3& operator*=(double s) { return *this = *this * s; }
    Vec3& operator/=(double s) { return *this = *this / s; }
    constexpr bool operator==(const Vec3& b) const { return x == b.x && y == b.y && z == b.z; }
    constexpr bool operator!=(const Vec3& b) const { return !(*this == b); }

    double norm2() const { return x * x + y * y + z * z; }
    double norm() const { return std::sqrt(norm2()); }
    Vec3 unit() const { return *this / norm(); }
    bool is_finite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
};

constexpr Vec3 operator*(double s, const Vec3& v) { return v * s; }
constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3 abs(const Vec3& v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }
inline Vec3 min(const Vec3& a, const Vec3& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline double max_component(const Vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }
/// Index (0, 1, 2) of the largest component.
inline int max_dimension(const Vec3& v) {
    return (v.x > v.y) ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2);
}
inline Vec3 normalize(const Vec3& v) { return v.unit(); }
/// Mirror direction of `w` about the unit normal `n` (both pointing away from the surface).
inline Vec3 reflect(const Vec3& w, const Vec3& n) { return 2.0 * dot(w, n) * n - w; }

struct Vec2 {
    double x = 0, y = 0;
    constexpr Vec2() = default;
    constexpr Vec2(double x_, double y_) : x(x_), y(y_) {}
    constexpr Vec2 operator+(const Vec2& b) const { return {x + b.x, y + b.y}; }
    constexpr Vec2 operator-(const Vec2& b) const { return {x - b.x, y - b.y}; }
    constexpr Vec2 operator*(double s) const { return {x * s, y * s}; }
};

}  // namespace pt
