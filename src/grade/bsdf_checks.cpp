// Part 3, diffuse_f and diffuse_sample_f: the Lambertian BSDF's value, and
// its sampling routine by the properties every correct one has (any
// cosine-weighted warp is right, so directions are not compared with the
// reference's): each sample is valid, unit, in the upper hemisphere, with
// pdf = cos(theta) / pi and f = albedo / pi, and the directions follow
// cos(theta) / pi by a chi-square test at the manifest's significance.
//
// A wrong diffuse_f is charged to diffuse_f alone: diffuse_sample_f's f may
// equal either albedo / pi or the student's own diffuse_f at the sampled
// direction (the handout has sample_f call diffuse_f).
#include <cmath>

#include "core/error.h"
#include "core/math.h"
#include "grade/case_log.h"
#include "grade/chi_square.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"

namespace pt {
namespace {

std::string format_color(const Color& c) {
    return format_vec(Vec3(c.r, c.g, c.b));
}

bool colors_close(const Color& a, const Color& b, double rel_tol) {
    for (int c = 0; c < 3; ++c)
        if (!(std::fabs(a[c] - b[c]) <= rel_tol * std::max(1.0, std::fabs(b[c])))) return false;
    return true;
}

Color random_albedo(Rng& rng) {
    switch (rng.next_index(8)) {
        case 0:
            return Color(0);
        case 1:
            return Color(1);
        case 2:
            return Color(0.725, 0.71, 0.68);
        default:
            return Color(rng.next_1d(), rng.next_1d(), rng.next_1d());
    }
}

/// Unit direction with z in [z_lo, z_hi].
Vec3 direction_with_z(Rng& rng, double z_lo, double z_hi) {
    double z = uniform(rng, z_lo, z_hi), phi = uniform(rng, 0, kTwoPi);
    double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 upper_direction(Rng& rng) {
    return direction_with_z(rng, 0, 1);
}

}  // namespace

TaskResult check_diffuse_f(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-6);
    const double band = param(spec, "edge_band", 1e-9);
    const int n = param(spec, "cases", 2000);
    Rng rng = check_rng(env.seed, "diffuse_f");
    CaseLog log;
    auto run = [&](const Color& albedo, const Vec3& wo, const Vec3& wi) {
        Color got = env.student.direct.diffuse_f(albedo, wo, wi);
        Color want = env.reference.direct.diffuse_f(albedo, wo, wi);
        if (colors_close(got, want, rel_tol)) {
            log.agreed();
        } else if (std::fabs(wi.z) <= band && got.is_finite()) {
            log.allowed();  // on the horizon cos = 0: either side's value is harmless
        } else {
            log.mismatch("albedo " + format_color(albedo) + ", wo = " + format_vec(wo) +
                         ", wi = " + format_vec(wi) + ": f = " + format_color(got) +
                         " instead of " + format_color(want));
        }
    };
    log.category("wi above the surface: albedo / pi");
    for (int i = 0; i < n; ++i)
        run(random_albedo(rng), upper_direction(rng), upper_direction(rng));
    log.category("wi below the surface: black");
    for (int i = 0; i < n / 2; ++i)
        run(random_albedo(rng), upper_direction(rng), direction_with_z(rng, -1, 0));
    log.category("wi on and near the horizon");
    const double zs[] = {0.0, -0.0, 1e-300, -1e-300, 1e-12, -1e-12, 1e-6, -1e-6, 1.0, -1.0};
    for (double z : zs)
        for (int i = 0; i < 5; ++i) {
            Vec3 w = direction_with_z(rng, 0, 0);
            double s = std::sqrt(std::max(0.0, 1 - z * z));
            run(random_albedo(rng), upper_direction(rng), Vec3(w.x * s, w.y * s, z));
        }
    return log.finish(spec, param(spec, "max_mismatches", 0));
}

TaskResult check_diffuse_sample_f(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-6);
    const int n = param(spec, "samples", 100000);
    const double significance = param(spec, "significance", 1e-5);
    const int nz = 10, nphi = 20;  // cells of equal probability under cos / pi
    Rng rng = check_rng(env.seed, "diffuse_sample_f");
    CaseLog log;
    bool own_f = true;  // whether the student's diffuse_f can be called
    std::vector<double> observed(size_t(nz * nphi), 0.0);

    // "" when the sample has every property, else what is wrong.
    auto problems = [&](const Color& albedo, const Vec3& wo, const BSDFSample& s) -> std::string {
        if (!s.wi.is_finite() || !(std::fabs(s.wi.norm() - 1) <= rel_tol))
            return "wi = " + format_vec(s.wi) + " is not a unit vector";
        if (!(s.wi.z > 0)) return "wi = " + format_vec(s.wi) + " is not above the surface (z > 0)";
        double pdf = s.wi.z * kInvPi;
        if (!(std::fabs(s.pdf - pdf) <= rel_tol * pdf))
            return "pdf = " + format_num(s.pdf) + " for wi = " + format_vec(s.wi) +
                   ", but cos(theta) / pi = " + format_num(pdf);
        if (s.is_delta) return "is_delta is set: a diffuse sample is not a delta";
        Color f = albedo * kInvPi;
        bool f_ok = colors_close(s.f, f, rel_tol);
        if (!f_ok && own_f) {
            try {
                f_ok = colors_close(s.f, env.student.direct.diffuse_f(albedo, wo, s.wi), rel_tol);
            } catch (const NotImplemented&) {
                own_f = false;
            }
        }
        if (!f_ok)
            return "f = " + format_color(s.f) + " for albedo " + format_color(albedo) +
                   ", but albedo / pi = " + format_color(f);
        return "";
    };

    log.category("random samples: valid, unit, above the surface, pdf = cos / pi, f = albedo / pi");
    for (int i = 0; i < n; ++i) {
        Color albedo = random_albedo(rng);
        Vec3 wo = upper_direction(rng);
        Vec2 u = rng.next_2d();
        BSDFSample s = env.student.direct.diffuse_sample_f(albedo, wo, u);
        std::string where =
            "u = (" + format_num(u.x) + ", " + format_num(u.y) + "), wo = " + format_vec(wo) + ": ";
        if (!s.valid()) {
            log.mismatch(where + "no sample (pdf " + format_num(s.pdf) + ")");
            continue;
        }
        std::string p = problems(albedo, wo, s);
        if (!p.empty()) {
            log.mismatch(where + p);
            continue;
        }
        log.agreed();
        // The cell: z^2 in nz equal steps (equal probability under cos / pi), phi in nphi.
        int iz = std::min(nz - 1, int(s.wi.z * s.wi.z * nz));
        double phi = std::atan2(s.wi.y, s.wi.x);
        if (phi < 0) phi += kTwoPi;
        int ip = std::min(nphi - 1, int(phi / kTwoPi * nphi));
        observed[size_t(iz * nphi + ip)] += 1;
    }

    log.category("u at 0, 1/2 and just below 1 (no sample is accepted, pdf 0)");
    const double us[] = {0.0, 0x1p-32, 0.5, 1.0 - 0x1p-32};
    for (double ux : us)
        for (double uy : us) {
            Color albedo = random_albedo(rng);
            Vec3 wo = upper_direction(rng);
            BSDFSample s = env.student.direct.diffuse_sample_f(albedo, wo, Vec2(ux, uy));
            std::string p = s.valid() || s.pdf != 0 ? problems(albedo, wo, s) : "";
            if (p.empty())
                log.agreed();
            else
                log.mismatch("u = (" + format_num(ux) + ", " + format_num(uy) + "): " + p);
        }

    log.category("distribution of wi (chi-square against cos / pi)");
    double valid = 0;
    for (double o : observed)
        valid += o;
    ChiSquareResult chi;
    if (valid < 0.5 * n) {
        chi.message = "too few valid samples to test the distribution";
    } else {
        std::vector<double> expected(observed.size(), valid / double(observed.size()));
        chi = chi_square_test(observed, expected, significance);
    }
    if (chi.passed)
        log.agreed();
    else
        log.mismatch(std::to_string(int(valid)) + " directions in " + std::to_string(nz * nphi) +
                     " cells of equal probability under cos / pi: " + chi.message);
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0),
                              "the properties of a cosine-weighted sampler");
    r.details.insert(r.details.begin(), "chi-square test of " + std::to_string(int(valid)) +
                                            " directions in " + std::to_string(nz) + " x " +
                                            std::to_string(nphi) + " cells: " + chi.message);
    if (r.status == TaskStatus::pass)
        r.message = std::to_string(n) +
                    " samples valid, unit, above the surface, with pdf = cos / pi and f = "
                    "albedo / pi; their directions pass the chi-square test (" +
                    chi.message + ")";
    return r;
}

}  // namespace pt
