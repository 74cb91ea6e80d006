// The intersect_triangle check (Part 1, task 3). See function_checks.h.
#include <algorithm>
#include <cmath>

#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/hit_compare.h"
#include "grade/params.h"
#include "grade/random_inputs.h"
#include "stages/intersect.h"

namespace pt {
namespace {

using Real = long double;  // 64-bit mantissa on x86-64: the "exact" margins of a case

struct LVec {
    Real x, y, z;
};
LVec lv(const Vec3& v) {
    return {v.x, v.y, v.z};
}
LVec sub(LVec a, LVec b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Real ldot(LVec a, LVec b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
LVec lcross(LVec a, LVec b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Real lnorm(LVec a) {
    return std::sqrt(ldot(a, a));
}

/// Whether a one-ulp difference could flip this case's verdict: Möller-
/// Trumbore in long double gives the margins of the verdict; the band is
/// `band` times the condition number |e1| |e2| |d| / |det| of the system.
/// Exactly parallel rays and degenerate triangles (det = 0) are never in
/// the band: the contract says they miss.
bool in_edge_band(const Triangle& tri, const Ray& ray, double band) {
    LVec e1 = sub(lv(tri.p1), lv(tri.p0)), e2 = sub(lv(tri.p2), lv(tri.p0)), d = lv(ray.d);
    LVec pvec = lcross(d, e2);
    Real det = ldot(e1, pvec);
    if (det == 0) return false;
    Real kappa = std::max<Real>(1, lnorm(e1) * lnorm(e2) * lnorm(d) / std::fabs(det));
    Real eps = Real(band) * kappa;
    LVec s = sub(lv(ray.o), lv(tri.p0));
    Real b1 = ldot(s, pvec) / det;
    Real b2 = ldot(d, lcross(s, e1)) / det;
    Real t = ldot(e2, lcross(s, e1)) / det;
    bool inside = b1 >= -eps && b2 >= -eps && b1 + b2 <= 1 + eps;
    if (!inside) return false;
    if (std::fabs(b1) <= eps || std::fabs(b2) <= eps || std::fabs(1 - b1 - b2) <= eps) return true;
    Real t_eps = eps * std::max<Real>(1, std::fabs(t));
    return std::fabs(t - ray.t_min) <= t_eps ||
           (std::isfinite(ray.t_max) && std::fabs(t - ray.t_max) <= t_eps);
}

std::string describe(const Triangle& tri, const Ray& ray) {
    std::string s =
        "triangle " + format_vec(tri.p0) + " " + format_vec(tri.p1) + " " + format_vec(tri.p2);
    if (tri.has_normals)
        s += " with vertex normals " + format_vec(tri.n0) + " " + format_vec(tri.n1) + " " +
             format_vec(tri.n2);
    return s + ", ray o = " + format_vec(ray.o) + " d = " + format_vec(ray.d) + " t in [" +
           format_num(ray.t_min) + ", " + format_num(ray.t_max) + "]";
}

struct TriangleCheck {
    const GradeEnvironment& env;
    HitTolerance tol;
    double band;
    CaseLog log;

    void run(const Triangle& tri, const Ray& ray) {
        std::optional<Hit> r = env.reference.intersect.intersect_triangle(tri, ray);
        std::optional<Hit> s = env.student.intersect.intersect_triangle(tri, ray);
        std::string diff = compare_hits(s, r, tol);
        if (diff.empty())
            log.agreed();
        else if (in_edge_band(tri, ray, band))
            log.allowed();
        else
            log.mismatch(describe(tri, ray) + ": " + diff);
    }
};

Triangle random_triangle(Rng& rng, double* size) {
    Triangle t;
    double scale = log_uniform(rng, 0.01, 100);
    Vec3 centre = random_in_cube(rng) * log_uniform(rng, 0.1, 1000);
    t.p0 = centre + random_in_cube(rng) * scale;
    t.p1 = centre + random_in_cube(rng) * scale;
    t.p2 = centre + random_in_cube(rng) * scale;
    if (rng.next_1d() < 0.3) {
        t.has_normals = true;
        Vec3 ng = cross(t.p1 - t.p0, t.p2 - t.p0).unit();
        // Vertex normals near the geometric normal, as a smooth mesh has them.
        t.n0 = (ng + random_unit(rng) * 0.5).unit();
        t.n1 = (ng + random_unit(rng) * 0.5).unit();
        t.n2 = (ng + random_unit(rng) * 0.5).unit();
    }
    *size = scale;
    return t;
}

Vec3 point_at(const Triangle& t, double b1, double b2) {
    return t.p0 * (1 - b1 - b2) + t.p1 * b1 + t.p2 * b2;
}

/// A ray towards `target` from `distance` away along -dir, direction scaled
/// by `length` (shadow rays are not unit length).
Ray ray_towards(const Vec3& target, const Vec3& dir, double distance, double length) {
    return Ray(target - dir * distance, dir * length, 0.0, kInfinity);
}

double random_length(Rng& rng) {
    return rng.next_1d() < 0.25 ? log_uniform(rng, 0.1, 10) : 1.0;
}

}  // namespace

TaskResult check_intersect_triangle(const TaskSpec& spec, const GradeEnvironment& env) {
    TriangleCheck c{env, {}, param(spec, "edge_band", 1e-9), {}};
    c.tol.rel_tol = param(spec, "rel_tol", 1e-6);
    const int n = param(spec, "cases", 3000);
    Rng rng = check_rng(env.seed, "intersect_triangle");
    double size = 1;

    c.log.category("random rays");
    for (int i = 0; i < n; ++i) {
        Triangle tri = random_triangle(rng, &size);
        Vec3 target = point_at(tri, uniform(rng, -0.2, 1.2), uniform(rng, -0.2, 1.2));
        Ray ray = ray_towards(target, random_unit(rng), size * log_uniform(rng, 0.1, 100),
                              random_length(rng));
        if (rng.next_1d() < 0.2) ray.t_max = uniform(rng, 0.1, 2) * size;
        c.run(tri, ray);
    }

    c.log.category("near edges and vertices");
    for (int i = 0; i < n / 3; ++i) {
        Triangle tri = random_triangle(rng, &size);
        // A point on an edge or at a vertex, then nudged across the edge.
        double along = rng.next_1d() < 0.2 ? 0.0 : rng.next_1d();
        const double nudges[] = {0.0, 1e-13, -1e-13, 1e-7, -1e-7, 1e-4, -1e-4};
        double nudge = nudges[rng.next_index(7)];
        double b1, b2;
        switch (rng.next_index(3)) {
            case 0:
                b1 = nudge, b2 = along;
                break;  // edge p0 p2
            case 1:
                b1 = along, b2 = nudge;
                break;  // edge p0 p1
            default:
                b1 = along - nudge / 2, b2 = 1 - along - nudge / 2;  // edge p1 p2
        }
        Ray ray = ray_towards(point_at(tri, b1, b2), random_unit(rng), size * uniform(rng, 1, 10),
                              random_length(rng));
        c.run(tri, ray);
    }

    c.log.category("grazing rays");
    for (int i = 0; i < n / 6; ++i) {
        Triangle tri = random_triangle(rng, &size);
        Vec3 ng = cross(tri.p1 - tri.p0, tri.p2 - tri.p0).unit();
        Vec3 in_plane = any_perpendicular(ng);
        double sine = log_uniform(rng, 1e-6, 1e-2) * (rng.next_1d() < 0.5 ? -1 : 1);
        Vec3 dir = (in_plane * std::sqrt(1 - sine * sine) + ng * sine).unit();
        Vec3 target = point_at(tri, uniform(rng, 0, 0.6), uniform(rng, 0, 0.4));
        c.run(tri, ray_towards(target, dir, size * uniform(rng, 0.5, 5), 1.0));
    }

    c.log.category("parallel rays");
    for (int i = 0; i < n / 30; ++i) {
        // Integer coordinates in a plane z = const and directions with d.z = 0:
        // det is exactly zero, so every correct implementation misses.
        auto ri = [&](int lo, int hi) {
            return double(lo + int(rng.next_index(uint32_t(hi - lo + 1))));
        };
        double z = ri(-50, 50);
        Triangle tri;
        tri.p0 = {ri(-50, 0), ri(-50, 0), z};
        tri.p1 = {ri(1, 50), ri(-50, 0), z};
        tri.p2 = {ri(-50, 50), ri(1, 50), z};
        double dz = rng.next_1d() < 0.5 ? 0.0 : ri(-5, 5);  // in the plane, or beside it
        Vec3 o(ri(-100, 100), ri(-100, 100), z + dz);
        Vec3 d(ri(1, 8) / 8, ri(-8, 8) / 8, 0.0);
        c.run(tri, Ray(o, d));
    }

    c.log.category("hits behind the origin and t_min, t_max boundaries");
    for (int i = 0; i < n / 3; ++i) {
        Triangle tri = random_triangle(rng, &size);
        Vec3 dir = random_unit(rng);
        Ray ray = ray_towards(point_at(tri, uniform(rng, 0.05, 0.6), uniform(rng, 0.05, 0.3)), dir,
                              size * uniform(rng, 1, 10), random_length(rng));
        std::optional<Hit> hit = env.reference.intersect.intersect_triangle(tri, ray);
        if (!hit) continue;  // the ray grazes the triangle; the random cases cover that
        double t = hit->t;
        const double bounds[][2] = {
            {t * (1 + 1e-5), kInfinity},       // the hit is before t_min
            {0, t * (1 - 1e-5)},               // the hit is after t_max
            {t * (1 - 1e-5), t * (1 + 1e-5)},  // a narrow interval around the hit
            {2 * t, 3 * t},                    // well beyond the hit
            {0.5 * t, 2 * t},                  // around the hit
            {t, t},                            // exactly at the hit (edge band)
        };
        const auto& b = bounds[rng.next_index(6)];
        ray.t_min = b[0];
        ray.t_max = b[1];
        c.run(tri, ray);
        // The same ray turned round: the triangle is behind its origin.
        Ray back(ray.o, -ray.d, 0.0, kInfinity);
        c.run(tri, back);
    }

    c.log.category("degenerate triangles");
    for (int i = 0; i < n / 30; ++i) {
        // Zero area exactly (integer coordinates): a repeated vertex, three
        // collinear vertices, or a single point. det is zero: a miss.
        auto ri = [&](int lo, int hi) {
            return double(lo + int(rng.next_index(uint32_t(hi - lo + 1))));
        };
        Triangle tri;
        tri.p0 = {ri(-20, 20), ri(-20, 20), ri(-20, 20)};
        tri.p1 = {ri(-20, 20), ri(-20, 20), ri(-20, 20)};
        switch (rng.next_index(3)) {
            case 0:
                tri.p2 = tri.p0;
                break;
            case 1:
                tri.p2 = tri.p0 + (tri.p1 - tri.p0) * 2.0;
                break;
            default:
                tri.p1 = tri.p2 = tri.p0;
        }
        Vec3 target = tri.p0 + (tri.p1 - tri.p0) * 0.5;
        Vec3 o(ri(-60, 60), ri(-60, 60), ri(-60, 60));
        c.run(tri, Ray(o, target - o));
    }
    return c.log.finish(spec, param(spec, "max_mismatches", 0));
}

}  // namespace pt
