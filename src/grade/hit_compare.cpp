#include "grade/hit_compare.h"

#include <algorithm>
#include <cmath>

#include "grade/case_log.h"

namespace pt {

bool same_closest_t(double got, double want, double rel_tol) {
    return std::fabs(got - want) <= rel_tol * std::max(1.0, std::fabs(want));
}

std::string compare_hits(const std::optional<Hit>& s, const std::optional<Hit>& r,
                         const HitTolerance& tol) {
    if (!s && !r) return "";
    if (s && !r) return "a hit at t = " + format_num(s->t) + " where the reference misses";
    if (!s && r) return "a miss where the reference hits at t = " + format_num(r->t);
    if (std::isnan(s->t) || !s->n.is_finite() || std::isnan(s->b1) || std::isnan(s->b2))
        return "a hit with NaN or infinite values: t = " + format_num(s->t) +
               ", n = " + format_vec(s->n);
    if (!(std::fabs(s->t - r->t) <= tol.rel_tol * std::max(1.0, std::fabs(r->t)) + tol.t_abs))
        return "t = " + format_num(s->t) + " instead of " + format_num(r->t);
    if (tol.barycentrics &&
        !(std::fabs(s->b1 - r->b1) <= tol.rel_tol && std::fabs(s->b2 - r->b2) <= tol.rel_tol))
        return "barycentrics (b1, b2) = (" + format_num(s->b1) + ", " + format_num(s->b2) +
               ") instead of (" + format_num(r->b1) + ", " + format_num(r->b2) + ")";
    if (!(std::fabs(s->n.norm() - 1.0) <= tol.rel_tol + tol.normal_abs))
        return "the normal " + format_vec(s->n) +
               " is not unit length (|n| = " + format_num(s->n.norm()) + ")";
    Vec3 dn = s->n - r->n;
    double limit = tol.rel_tol + tol.normal_abs;
    if (!(std::fabs(dn.x) <= limit && std::fabs(dn.y) <= limit && std::fabs(dn.z) <= limit))
        return "normal " + format_vec(s->n) + " instead of " + format_vec(r->n);
    return "";
}

}  // namespace pt
