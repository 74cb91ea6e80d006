// Ray: origin, direction and the parameter interval [t_min, t_max] in which
// hits count. A hit at parameter t lies at o + t * d.
#pragma once

#include <limits>

#include "core/vec3.h"

namespace pt {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Ray {
    Vec3 o;                  ///< origin, scene units
    Vec3 d;                  ///< direction; unit length for camera and bounce rays
    double t_min = 0.0;      ///< hits with t < t_min are ignored
    double t_max = kInfinity;  ///< hits with t > t_max are ignored (shortened for shadow rays)
    int depth = 0;           ///< number of bounces before this ray (camera rays: 0)

    Ray() = default;
    Ray(const Vec3& origin, const Vec3& direction, double tmin = 0.0, double tmax = kInfinity,
        int depth_ = 0)
        : o(origin), d(direction), t_min(tmin), t_max(tmax), depth(depth_) {}

    Vec3 at(double t) const { return o + t * d; }
};

}  // namespace pt
