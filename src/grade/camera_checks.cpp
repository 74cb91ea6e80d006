// The generate_ray check (Part 1, task 1). See function_checks.h.
#include <cmath>

#include "core/rng.h"
#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"
#include "stages/camera.h"

namespace pt {
namespace {

bool close(double a, double r, double tol) {
    if (a == r) return true;  // also equal infinities
    return std::fabs(a - r) <= tol * std::max(1.0, std::fabs(r));
}

bool close(const Vec3& a, const Vec3& r, double tol) {
    return close(a.x, r.x, tol) && close(a.y, r.y, tol) && close(a.z, r.z, tol);
}

Camera random_camera(Rng& rng) {
    for (;;) {
        Camera c;
        double scale = log_uniform(rng, 0.1, 1000);  // scene units from decimetres to kilometres
        c.position = random_in_cube(rng) * scale;
        Vec3 view = random_unit(rng);
        c.look_at = c.position + view * (scale * uniform(rng, 0.1, 2));
        c.up = random_unit(rng) * uniform(rng, 0.5, 2);  // up need not be unit nor perpendicular
        if (cross(c.up.unit(), view).norm() < 0.2) continue;
        c.vfov = uniform(rng, 5, 150);
        c.aspect = log_uniform(rng, 0.25, 4);
        c.near_clip = rng.next_1d() < 0.5 ? 0.0 : uniform(rng, 0, 1) * scale;
        c.far_clip = rng.next_1d() < 0.5 ? 1e300 : uniform(rng, 10, 1000) * scale;
        c.finalize("random camera");
        return c;
    }
}

/// The Cornell box camera at 4:3: a camera students will recognise.
Camera cornell_camera() {
    Camera c;
    c.position = {278, 273, -800};
    c.look_at = {278, 273, 0};
    c.vfov = 39.3;
    c.aspect = 4.0 / 3.0;
    c.finalize("cornell camera");
    return c;
}

std::string describe(const Camera& c, double x, double y) {
    return "camera position " + format_vec(c.position) + " look_at " + format_vec(c.look_at) +
           " up " + format_vec(c.up) + " vfov " + format_num(c.vfov) + " aspect " +
           format_num(c.aspect) + ", x = " + format_num(x) + ", y = " + format_num(y);
}

/// What differs between the student's ray and the reference's, or "".
std::string compare_rays(const Ray& s, const Ray& r, double tol) {
    if (!s.o.is_finite() || !s.d.is_finite() || std::isnan(s.t_min) || std::isnan(s.t_max))
        return "the ray has NaN or infinite components: o = " + format_vec(s.o) +
               ", d = " + format_vec(s.d);
    if (!close(s.d.norm(), 1.0, tol))
        return "the direction is not unit length: |d| = " + format_num(s.d.norm()) +
               " for d = " + format_vec(s.d);
    if (!close(s.d, r.d, tol))
        return "direction " + format_vec(s.d) + " instead of " + format_vec(r.d);
    if (!close(s.o, r.o, tol))
        return "origin " + format_vec(s.o) + " instead of " + format_vec(r.o);
    if (!close(s.t_min, r.t_min, tol) || !close(s.t_max, r.t_max, tol))
        return "t in [" + format_num(s.t_min) + ", " + format_num(s.t_max) + "] instead of [" +
               format_num(r.t_min) + ", " + format_num(r.t_max) + "]";
    return "";
}

void check_pinhole(const Camera& camera, double x, double y, Rng& rng, const GradeEnvironment& env,
                   double tol, CaseLog& log) {
    Vec2 lens = rng.next_2d();  // ignored by a pinhole: a student who uses it anyway is caught
    Ray r = env.reference.camera.generate_ray(camera, x, y, lens);
    Ray s = env.student.camera.generate_ray(camera, x, y, lens);
    std::string diff = compare_rays(s, r, tol);
    if (diff.empty())
        log.agreed();
    else
        log.mismatch(describe(camera, x, y) + ": " + diff);
}

/// Thin lens: any area-preserving map from lens_sample to the disk is
/// correct, so the rays are checked by what makes them right: a unit
/// direction, an origin on the lens disk, and a path through the point
/// where the pinhole ray meets the plane of focus.
void check_thin_lens(const Camera& camera, double x, double y, Rng& rng,
                     const GradeEnvironment& env, double tol, CaseLog& log,
                     int* origins_at_centre) {
    Vec2 lens = rng.next_2d();
    Ray s = env.student.camera.generate_ray(camera, x, y, lens);
    Camera pinhole = camera;
    pinhole.lens_radius = 0;
    Ray p = env.reference.camera.generate_ray(pinhole, x, y, lens);
    std::string where = describe(camera, x, y) + " lens_radius " + format_num(camera.lens_radius) +
                        " focal_distance " + format_num(camera.focal_distance) + ": ";
    if (!s.o.is_finite() || !s.d.is_finite())
        return log.mismatch(where + "the ray has NaN or infinite components");
    if (!close(s.d.norm(), 1.0, tol))
        return log.mismatch(where +
                            "the direction is not unit length: |d| = " + format_num(s.d.norm()));
    Vec3 q = s.o - camera.position;
    double lx = dot(q, camera.right), ly = dot(q, camera.true_up), lz = dot(q, camera.backward);
    double r = camera.lens_radius;
    if (std::fabs(lz) > tol * r || lx * lx + ly * ly > r * r * (1 + tol))
        return log.mismatch(where + "the origin " + format_vec(s.o) + " is not on the lens disk");
    if (std::sqrt(lx * lx + ly * ly) < 1e-6 * r) ++*origins_at_centre;
    // The point in focus: the pinhole ray at depth focal_distance along the view axis.
    Vec3 focus = p.o + p.d * (camera.focal_distance / dot(p.d, -camera.backward));
    Vec3 to_focus = focus - s.o;
    double miss =
        cross(to_focus, s.d).norm();  // distance of the focus point from the student's line
    if (miss > tol * std::max(1.0, to_focus.norm()) || dot(to_focus, s.d) <= 0)
        return log.mismatch(where + "the ray misses the point in focus " + format_vec(focus) +
                            " by " + format_num(miss));
    log.agreed();
}

}  // namespace

TaskResult check_generate_ray(const TaskSpec& spec, const GradeEnvironment& env) {
    const double tol = param(spec, "rel_tol", 1e-6);
    const int cameras = param(spec, "cameras", 40);
    const int points = param(spec, "points_per_camera", 100);
    const bool thin_lens = param(spec, "thin_lens", false);
    Rng rng = check_rng(env.seed, "generate_ray");
    CaseLog log;

    const double special[][2] = {{0, 0},   {1, 0},   {0, 1},   {1, 1},  {0.5, 0.5},
                                 {0.5, 0}, {0, 0.5}, {1, 0.5}, {0.5, 1}};
    for (int i = 0; i <= cameras; ++i) {
        Camera camera = i == 0 ? cornell_camera() : random_camera(rng);
        log.category("corners, edge midpoints and centre");
        for (const auto& xy : special)
            check_pinhole(camera, xy[0], xy[1], rng, env, tol, log);
        log.category("random points");
        for (int k = 0; k < points; ++k) {
            double x = rng.next_1d(), y = rng.next_1d();
            check_pinhole(camera, x, y, rng, env, tol, log);
        }
    }
    if (thin_lens) {
        log.category("thin lens");
        int at_centre = 0, lens_cases = 0;
        for (int i = 0; i < cameras; ++i) {
            Camera camera = random_camera(rng);
            double scale = (camera.look_at - camera.position).norm();
            camera.lens_radius = scale * log_uniform(rng, 1e-3, 0.2);
            camera.focal_distance = scale * uniform(rng, 0.3, 3);
            for (int k = 0; k < points; ++k, ++lens_cases)
                check_thin_lens(camera, rng.next_1d(), rng.next_1d(), rng, env, tol, log,
                                &at_centre);
        }
        // A concentric or polar map puts an origin at the lens centre with probability 0.
        if (at_centre > lens_cases / 100)
            log.mismatch(std::to_string(at_centre) + " of " + std::to_string(lens_cases) +
                         " thin-lens rays start at the lens centre: lens_sample is ignored");
    }
    return log.finish(spec, param(spec, "max_mismatches", 0));
}

}  // namespace pt
