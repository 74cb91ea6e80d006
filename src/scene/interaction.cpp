#include "scene/interaction.h"

#include <cmath>

#include "core/math.h"

namespace pt {

Vec3 offset_ray_origin(const Vec3& p, const Vec3& p_error, const Vec3& ng, const Vec3& w) {
    double d = dot(abs(ng), p_error);
    Vec3 offset = d * ng;
    if (dot(w, ng) < 0) offset = -offset;
    Vec3 po = p + offset;
    // Round away from p so the addition above cannot land back inside the error box.
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0) po[i] = next_double_up(po[i]);
        else if (offset[i] < 0) po[i] = next_double_down(po[i]);
    }
    return po;
}

Ray SurfaceInteraction::spawn_ray(const Vec3& w) const {
    return Ray(offset_ray_origin(p, p_error, ng, w), w, kSpawnTMin, kInfinity, depth + 1);
}

Ray SurfaceInteraction::spawn_ray_to(const Vec3& target) const {
    Vec3 origin = offset_ray_origin(p, p_error, ng, target - p);
    return Ray(origin, target - origin, kSpawnTMin, 1.0 - kShadowEpsilon, depth + 1);
}

}  // namespace pt
