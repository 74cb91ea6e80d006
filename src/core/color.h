// Color: linear RGB radiometric quantities (radiance, reflectance, power).
// Components are linear, never sRGB-encoded; encoding happens only when an
// image is written as PNG (image/tonemap.h).
#pragma once

#include <cmath>

namespace pt {

struct Color {
    double r = 0, g = 0, b = 0;

    constexpr Color() = default;
    constexpr Color(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit Color(double v) : r(v), g(v), b(v) {}

    constexpr Color operator+(const Color& c) const { return {r + c.r, g + c.g, b + c.b}; }
    constexpr Color operator-(const Color& c) const { return {r - c.r, g - c.g, b - c.b}; }
    constexpr Color operator*(const Color& c) const { return {r * c.r, g * c.g, b * c.b}; }
    constexpr Color operator/(const Color& c) const { return {r / c.r, g / c.g, b / c.b}; }
    constexpr Color operator*(double s) const { return {r * s, g * s, b * s}; }
    constexpr Color operator/(double s) const { return {r / s, g / s, b / s}; }
    Color& operator+=(const Color& c) { return *this = *this + c; }
    Color& operator*=(const Color& c) { return *this = *this * c; }
    Color& operator*=(double s) { return *this = *this * s; }
    Color& operator/=(double s) { return *this = *this / s; }
    constexpr bool operator==(const Color& c) const { return r == c.r && g == c.g && b == c.b; }
    constexpr bool operator!=(const Color& c) const { return !(*this == c); }
    double operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }

    /// Relative luminance Y of linear sRGB/Rec. 709 primaries (ITU-R BT.709).
    constexpr double luminance() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
    constexpr double max_component() const {
        return r > g ? (r > b ? r : b) : (g > b ? g : b);
    }
    constexpr double average() const { return (r + g + b) / 3.0; }
    constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
    bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

constexpr Color operator*(double s, const Color& c) { return c * s; }

}  // namespace pt
