// The intersect_sphere check (Part 1, task 4). See function_checks.h.
//
// Tolerances follow the first-order error of the textbook solution of the
// quadratic (b' = -f.d, disc = b'^2 - a c with f = o - center): its
// discriminant carries an absolute error of about 16 eps |f|^2 |d|^2, so a
// unit sphere 10^6 units away is located to about 10^-3 by a correct
// textbook implementation, and the reference's more accurate answer
// (Ray Tracing Gems ch. 7) must not fail it. For ordinary scenes the extra
// tolerance is below 10^-12 and rel_tol alone applies.
#include <algorithm>
#include <cmath>
#include <limits>

#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/hit_compare.h"
#include "grade/params.h"
#include "grade/random_inputs.h"
#include "stages/intersect.h"

namespace pt {
namespace {

using Real = long double;

struct SphereAnalysis {
    Real disc_rel = 0;      ///< (r^2 - distance^2 of the line from the centre) / r^2: < 0 misses
    Real t0 = 0, t1 = 0;    ///< the roots, t0 <= t1 (when disc_rel >= 0)
    double ill = 0;         ///< relative error of the textbook discriminant, 16 eps (|f| / r)^2
    double t_abs = 0;       ///< tolerance on t that the textbook error needs
    double normal_abs = 0;  ///< tolerance on the normal that the textbook error needs
};

SphereAnalysis analyse(const Sphere& sphere, const Ray& ray) {
    SphereAnalysis s;
    Real fx = Real(ray.o.x) - sphere.center.x, fy = Real(ray.o.y) - sphere.center.y,
         fz = Real(ray.o.z) - sphere.center.z;
    Real dx = ray.d.x, dy = ray.d.y, dz = ray.d.z;
    Real a = dx * dx + dy * dy + dz * dz;
    Real b = -(fx * dx + fy * dy + fz * dz);
    Real px = fx + b / a * dx, py = fy + b / a * dy, pz = fz + b / a * dz;
    Real r2 = Real(sphere.radius) * sphere.radius;
    s.disc_rel = (r2 - (px * px + py * py + pz * pz)) / r2;
    Real f2 = fx * fx + fy * fy + fz * fz;
    s.ill = double(16 * std::numeric_limits<double>::epsilon() / 2 * f2 / r2);
    double root_rel = std::sqrt(std::max(double(std::fabs(s.disc_rel)), s.ill));
    double d_len = std::sqrt(double(a));
    s.t_abs = s.ill * sphere.radius / (d_len * root_rel);
    s.normal_abs = s.t_abs * d_len / sphere.radius;
    if (s.disc_rel >= 0) {
        Real root = std::sqrt(a * r2 * s.disc_rel);
        Real q = b + std::copysign(root, b);
        Real c = f2 - r2;
        s.t0 = q != 0 ? c / q : 0;
        s.t1 = q / a;
        if (s.t0 > s.t1) std::swap(s.t0, s.t1);
    }
    return s;
}

/// Whether a one-ulp (or textbook-error) difference could flip the verdict
/// or the choice of root: a nearly tangent ray, or a root at t_min or t_max.
bool in_edge_band(const SphereAnalysis& s, const Ray& ray, double band) {
    if (std::fabs(double(s.disc_rel)) <= band + s.ill) return true;
    if (s.disc_rel < 0) return false;
    for (Real t : {s.t0, s.t1}) {
        double eps = band * std::max(1.0, double(std::fabs(t))) + s.t_abs;
        if (std::fabs(double(t) - ray.t_min) <= eps) return true;
        if (std::isfinite(ray.t_max) && std::fabs(double(t) - ray.t_max) <= eps) return true;
    }
    return false;
}

std::string describe(const Sphere& sphere, const Ray& ray) {
    return "sphere center " + format_vec(sphere.center) + " radius " + format_num(sphere.radius) +
           ", ray o = " + format_vec(ray.o) + " d = " + format_vec(ray.d) + " t in [" +
           format_num(ray.t_min) + ", " + format_num(ray.t_max) + "]";
}

struct SphereCheck {
    const GradeEnvironment& env;
    double rel_tol;
    double band;
    CaseLog log;

    void run(const Sphere& sphere, const Ray& ray) {
        SphereAnalysis a = analyse(sphere, ray);
        HitTolerance tol;
        tol.rel_tol = rel_tol;
        tol.t_abs = a.t_abs;
        tol.normal_abs = a.normal_abs;
        tol.barycentrics = false;  // 0 by contract, and unused for spheres
        std::optional<Hit> r = env.reference.intersect.intersect_sphere(sphere, ray);
        std::optional<Hit> s = env.student.intersect.intersect_sphere(sphere, ray);
        std::string diff = compare_hits(s, r, tol);
        if (diff.empty())
            log.agreed();
        else if (in_edge_band(a, ray, band))
            log.allowed();
        else
            log.mismatch(describe(sphere, ray) + ": " + diff);
    }
};

Sphere random_sphere(Rng& rng, double min_radius = 0.01, double max_radius = 100) {
    Sphere s;
    s.radius = log_uniform(rng, min_radius, max_radius);
    s.center = random_in_cube(rng) * log_uniform(rng, 0.1, 1000);
    return s;
}

double random_length(Rng& rng) {
    return rng.next_1d() < 0.25 ? log_uniform(rng, 0.1, 10) : 1.0;
}

/// A ray from outside, `distance` radii from the centre, aimed at the
/// point `offset` radii from the centre across the line of sight.
Ray ray_from_outside(Rng& rng, const Sphere& s, double distance, double offset) {
    Vec3 o = s.center + random_unit(rng) * (s.radius * distance);
    Vec3 w = (s.center - o).unit();
    // Rotate the offset about the line of sight so every side is tried.
    Vec3 p = any_perpendicular(w), q = cross(w, p);
    double phi = uniform(rng, 0, 2 * M_PI);
    Vec3 target = s.center + (p * std::cos(phi) + q * std::sin(phi)) * (s.radius * offset);
    return Ray(o, (target - o).unit() * random_length(rng));
}

}  // namespace

TaskResult check_intersect_sphere(const TaskSpec& spec, const GradeEnvironment& env) {
    SphereCheck c{env, param(spec, "rel_tol", 1e-6), param(spec, "edge_band", 1e-9), {}};
    const int n = param(spec, "cases", 3000);
    Rng rng = check_rng(env.seed, "intersect_sphere");

    c.log.category("rays from outside");
    for (int i = 0; i < n; ++i) {
        Sphere s = random_sphere(rng);
        c.run(s, ray_from_outside(rng, s, log_uniform(rng, 1.01, 100), uniform(rng, 0, 1.3)));
    }

    c.log.category("rays from inside");
    for (int i = 0; i < n / 3; ++i) {
        Sphere s = random_sphere(rng);
        Vec3 o = s.center + random_unit(rng) * (s.radius * uniform(rng, 0, 0.95));
        c.run(s, Ray(o, random_unit(rng) * random_length(rng)));
    }

    c.log.category("tangent rays");
    for (int i = 0; i < n / 6; ++i) {
        Sphere s = random_sphere(rng);
        const double offsets[] = {1.0,      1 + 1e-12, 1 - 1e-12, 1 + 1e-6,
                                  1 - 1e-6, 1 + 1e-3,  1 - 1e-3};
        c.run(s, ray_from_outside(rng, s, log_uniform(rng, 1.5, 50), offsets[rng.next_index(7)]));
    }

    c.log.category("spheres behind the origin");
    for (int i = 0; i < n / 6; ++i) {
        Sphere s = random_sphere(rng);
        Ray ray = ray_from_outside(rng, s, log_uniform(rng, 1.01, 100), uniform(rng, 0, 0.9));
        c.run(s, Ray(ray.o, -ray.d));
    }

    c.log.category("a unit sphere 10^6 away");
    for (int i = 0; i < n / 6; ++i) {
        Sphere s;
        s.radius = 1;
        s.center = random_unit(rng) * 1e6;
        Vec3 o = random_in_cube(rng) * 10;
        Vec3 w = (s.center - o).unit();
        Vec3 target = s.center + any_perpendicular(w) * uniform(rng, 0, 1.2);
        c.run(s, Ray(o, (target - o).unit()));
    }

    c.log.category("tiny and huge spheres");
    for (int i = 0; i < n / 6; ++i) {
        Sphere s =
            rng.next_1d() < 0.5 ? random_sphere(rng, 1e-4, 1e-3) : random_sphere(rng, 1e3, 1e4);
        c.run(s, ray_from_outside(rng, s, log_uniform(rng, 1.01, 20), uniform(rng, 0, 1.3)));
    }

    c.log.category("t_min and t_max around the roots");
    for (int i = 0; i < n / 3; ++i) {
        Sphere s = random_sphere(rng);
        Ray ray = ray_from_outside(rng, s, log_uniform(rng, 1.5, 20), uniform(rng, 0, 0.8));
        SphereAnalysis a = analyse(s, ray);
        double t0 = double(a.t0), t1 = double(a.t1), mid = 0.5 * (t0 + t1);
        const double bounds[][2] = {
            {0, t0 * (1 - 1e-5)},                // both roots after t_max: miss
            {t0 * (1 + 1e-5), kInfinity},        // t_min between the roots: the far root
            {mid, t1 * (1 - 1e-5)},              // between the roots: miss
            {t1 * (1 + 1e-5), kInfinity},        // both roots before t_min: miss
            {t0 * (1 - 1e-5), mid},              // the near root only
            {t0 * (1 + 1e-5), t1 * (1 + 1e-5)},  // the far root only
            {t0, t1},                            // exactly the roots (edge band)
        };
        const auto& b = bounds[rng.next_index(7)];
        ray.t_min = b[0];
        ray.t_max = b[1];
        c.run(s, ray);
    }
    return c.log.finish(spec, param(spec, "max_mismatches", 0));
}

}  // namespace pt
