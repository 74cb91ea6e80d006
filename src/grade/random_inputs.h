// Random inputs for the function checks, drawn from an explicit Rng so
// that every check is reproducible from grade's --seed.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "core/rng.h"
#include "core/vec3.h"

namespace pt {

/// A generator for one check: the grade seed and the check's name pick the
/// stream, so adding a check never changes another check's inputs.
inline Rng check_rng(uint64_t seed, const std::string& check) {
    uint64_t h = 1469598103934665603ull;  // FNV-1a of the name
    for (char c : check)
        h = (h ^ uint8_t(c)) * 1099511628211ull;
    return Rng(seed, h, 0);
}

inline double uniform(Rng& rng, double lo, double hi) {
    return lo + (hi - lo) * rng.next_1d();
}

/// Log-uniform in [lo, hi], for scales spanning several decades.
inline double log_uniform(Rng& rng, double lo, double hi) {
    return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}

/// Uniform on the unit sphere.
inline Vec3 random_unit(Rng& rng) {
    double z = uniform(rng, -1, 1);
    double phi = uniform(rng, 0, 2 * M_PI);
    double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Uniform in the cube [-1, 1]^3.
inline Vec3 random_in_cube(Rng& rng) {
    return {uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
}

/// A unit vector perpendicular to unit vector n.
inline Vec3 any_perpendicular(const Vec3& n) {
    Vec3 a = std::fabs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    return cross(n, a).unit();
}

}  // namespace pt
