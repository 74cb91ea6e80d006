// Frame: an orthonormal basis (s, t, n) around a unit normal n, for moving
// directions between world space and the local shading space in which the
// normal is +z (so cos(theta) = w.z).
//
// The basis is built with the branchless method of Duff et al., "Building an
// Orthonormal Basis, Revisited" (JCGT 2017), which stays accurate for normals
// near (0, 0, -1) where the older Frisvad method breaks down.
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace pt {

struct Frame {
    Vec3 s;  ///< first tangent, unit
    Vec3 t;  ///< second tangent, unit
    Vec3 n;  ///< normal, unit; local +z

    Frame() : s(1, 0, 0), t(0, 1, 0), n(0, 0, 1) {}
    explicit Frame(const Vec3& normal) : n(normal) {
        double sign = std::copysign(1.0, n.z);
        double a = -1.0 / (sign + n.z);
        double b = n.x * n.y * a;
        s = Vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        t = Vec3(b, sign + n.y * n.y * a, -n.y);
    }

    /// The frame about `normal` whose first tangent s is `tangent` made
    /// perpendicular to it (Gram-Schmidt); the normal-only frame when the
    /// tangent is parallel to the normal or zero.
    static Frame with_tangent(const Vec3& normal, const Vec3& tangent) {
        Vec3 s = tangent - normal * dot(normal, tangent);
        double len = s.norm();
        if (!(len > 1e-12 * tangent.norm()) || !std::isfinite(len)) return Frame(normal);
        Frame f;
        f.n = normal;
        f.s = s / len;
        f.t = cross(normal, f.s);
        return f;
    }

    Vec3 to_local(const Vec3& w) const { return {dot(w, s), dot(w, t), dot(w, n)}; }
    Vec3 to_world(const Vec3& w) const { return s * w.x + t * w.y + n * w.z; }
};

}  // namespace pt
