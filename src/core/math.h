// Constants and small numeric helpers shared by every module.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace pt {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInvPi = 1.0 / kPi;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kInvTwoPi = 1.0 / kTwoPi;
constexpr double kInvFourPi = 1.0 / (4.0 * kPi);

constexpr double kMachineEpsilon = std::numeric_limits<double>::epsilon() * 0.5;

/// gamma(n) = n*eps / (1 - n*eps): the bound on the relative error of n
/// successive floating-point operations (Higham 2002; pbrt-v3 section 3.9.2).
constexpr double gamma(int n) { return (n * kMachineEpsilon) / (1 - n * kMachineEpsilon); }

inline double radians(double degrees) { return degrees * (kPi / 180.0); }
inline double degrees(double radians) { return radians * (180.0 / kPi); }
inline double clamp(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }
inline double lerp(double t, double a, double b) { return (1 - t) * a + t * b; }
inline double sqr(double v) { return v * v; }
/// sqrt that returns 0 for tiny negative arguments produced by rounding.
inline double safe_sqrt(double v) { return std::sqrt(v > 0 ? v : 0.0); }

/// The next representable double towards +infinity / -infinity: what
/// std::nextafter(v, +-infinity) returns, by stepping the bit pattern
/// (pbrt-v3 section 3.9.1) inline, since nextafter is a library call on
/// every spawned ray.
inline double next_double_up(double v) {
    if (!(v < std::numeric_limits<double>::infinity())) return v;  // +inf, NaN
    if (v == 0.0) v = 0.0;  // -0 steps up like +0
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof v);
    bits = v >= 0 ? bits + 1 : bits - 1;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}
inline double next_double_down(double v) {
    if (!(v > -std::numeric_limits<double>::infinity())) return v;  // -inf, NaN
    if (v == 0.0) v = -0.0;  // +0 steps down like -0
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof v);
    bits = v > 0 ? bits - 1 : bits + 1;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

}  // namespace pt
