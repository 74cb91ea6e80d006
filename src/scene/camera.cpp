#include "scene/camera.h"

#include <cmath>

#include "core/error.h"
#include "core/math.h"

namespace pt {

void Camera::finalize(const std::string& where) {
    Vec3 view = look_at - position;
    if (!(view.norm() > 0)) throw InputError(where + ": look_at must differ from position");
    if (!(vfov > 0 && vfov < 180))
        throw InputError(where + ".vfov: expected an angle in (0, 180) degrees");
    if (!(aspect > 0) || !std::isfinite(aspect)) throw InputError(where + ": film aspect ratio must be positive");
    backward = -view.unit();
    Vec3 r = cross(up, backward);
    // Looking straight along the up vector leaves "right" undefined; pick any
    // perpendicular instead of failing, since such a camera is legitimate.
    if (r.norm() < 1e-12 * up.norm()) r = cross(std::fabs(backward.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0), backward);
    right = r.unit();
    true_up = cross(backward, right);
    tan_half_vfov = std::tan(radians(vfov) * 0.5);
    tan_half_hfov = aspect * tan_half_vfov;
    if (focal_distance <= 0) focal_distance = view.norm();
}

}  // namespace pt
