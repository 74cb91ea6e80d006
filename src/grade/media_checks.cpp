// Part 9, the media functions with closed forms (issue 20): transmittance,
// free-flight distances, the Henyey-Greenstein phase function and its
// sampling routine. in_scattered_radiance is graded by an image task.
//
//   homogeneous_transmittance  e^(-sigma_t d) per channel, within rel_tol;
//                              1 where sigma_t = 0 at any distance (never
//                              NaN from 0 * infinity), 0 for sigma_t > 0 at
//                              an infinite distance.
//   sample_distance            by properties, so that t = -ln(u) / sigma_t is
//                              as right as the contract's -ln(1 - u):
//                              a collision lies in [0, t_max) with pdf
//                              sigma_t e^(-sigma_t t), a pass is at t_max
//                              with probability e^(-sigma_t t_max), sigma_t
//                              = 0 always passes; and the distances follow
//                              the truncated exponential with its mass at
//                              t_max (chi-square at the manifest's
//                              significance, equal-probability bins).
//   hg_phase                   the closed form (media.h) for g in (-1, 1)
//                              and cos theta in [-1, 1]; it integrates to 1
//                              over the sphere (Simpson's rule, reported).
//   sample_hg                  unit directions whose cos theta = -dot(wo, wi)
//                              follows HG's cdf and whose azimuth about -wo
//                              is uniform (chi-square on 20 x 8 cells of
//                              equal probability), for g in {-0.9, -0.3, 0,
//                              0.5, 0.95} (issue 20's list) and random wo.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/frame.h"
#include "core/math.h"
#include "grade/case_log.h"
#include "grade/chi_square.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"

namespace pt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool close(double got, double want, double rel_tol) {
    if (std::isinf(want)) return got == want;
    return std::fabs(got - want) <= rel_tol * std::fabs(want) + 1e-300;
}

std::string format_color(const Color& c) { return format_vec(Vec3(c.r, c.g, c.b)); }

/// e^(-s d) with 0 * infinity = 0: the closed form of the contract.
double beer(double sigma, double d) { return sigma > 0 ? std::exp(-sigma * d) : 1.0; }

/// p_HG(cos theta), media.h, in long double.
double hg_closed_form(double mu, double g) {
    const long double gg = g, d = 1 + gg * gg - 2 * gg * mu;
    return double((1 - gg * gg) / (4 * 3.14159265358979323846264338327950288L * d * std::sqrt(d)));
}

/// P(cos theta <= mu) under HG (the integral of 2 pi p_HG from -1 to mu).
double hg_cdf(double mu, double g) {
    if (std::fabs(g) < 1e-4) return (mu + 1) / 2;
    return (1 - g * g) / (2 * g) * (1 / std::sqrt(1 + g * g - 2 * g * mu) - 1 / (1 + g));
}

}  // namespace

TaskResult check_homogeneous_transmittance(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-9);
    const int n = param(spec, "cases", 3000);
    Rng rng = check_rng(env.seed, "homogeneous_transmittance");
    CaseLog log;
    auto run = [&](const Color& sigma, double d) {
        const Color got = env.student.media.homogeneous_transmittance(sigma, d);
        const Color want(beer(sigma.r, d), beer(sigma.g, d), beer(sigma.b, d));
        bool ok = true;
        for (int c = 0; c < 3; ++c)
            ok = ok && close(got[c], want[c], rel_tol);
        if (ok)
            log.agreed();
        else
            log.mismatch("sigma_t = " + format_color(sigma) + ", distance " + format_num(d) + ": T = " +
                         format_color(got) + " instead of e^(-sigma_t d) = " + format_color(want));
    };
    log.category("random extinctions and distances: e^(-sigma_t d) per channel");
    for (int i = 0; i < n; ++i) {
        const Color sigma(log_uniform(rng, 1e-4, 1e2), log_uniform(rng, 1e-4, 1e2), log_uniform(rng, 1e-4, 1e2));
        run(sigma, log_uniform(rng, 1e-4, 1e3));
    }
    log.category("zero extinction in some channels: 1 at any distance, infinite included");
    for (double d : {0.0, 1.0, 1e300, kInf}) {
        run(Color(0, 0, 0), d);
        run(Color(0, 0.5, 2), d);
        run(Color(3, 0, 0), d);
    }
    log.category("distance 0 (1) and infinite distance (0)");
    for (int i = 0; i < 20; ++i) {
        const Color sigma(log_uniform(rng, 1e-4, 1e2), log_uniform(rng, 1e-4, 1e2), log_uniform(rng, 1e-4, 1e2));
        run(sigma, 0.0);
        run(sigma, kInf);
    }
    return log.finish(spec, param(spec, "max_mismatches", 0), "the closed form");
}

TaskResult check_sample_distance(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-9);
    const int samples = param(spec, "samples", 20000);
    const double significance = param(spec, "significance", 1e-5);
    Rng rng = check_rng(env.seed, "sample_distance");
    CaseLog log;
    // "" when the sample is consistent with the contract, else what is wrong.
    auto problems = [&](double sigma, double t_max, const DistanceSample& s) -> std::string {
        if (sigma == 0 || !(sigma > 0)) {
            if (s.scattered) return "a collision in a medium of zero extinction";
        }
        if (s.scattered) {
            if (!(s.t >= 0 && s.t < t_max))
                return "a collision at t = " + format_num(s.t) + ", outside [0, t_max) = [0, " + format_num(t_max) + ")";
            const double pdf = sigma * std::exp(-sigma * s.t);
            if (!close(s.pdf, pdf, rel_tol))
                return "a collision at t = " + format_num(s.t) + " with pdf " + format_num(s.pdf) +
                       ", but sigma_t e^(-sigma_t t) = " + format_num(pdf);
            return "";
        }
        if (std::isinf(t_max) && sigma > 0) return "passed through an infinite medium";
        if (!(s.t == t_max || close(s.t, t_max, rel_tol)))
            return "passed, but at t = " + format_num(s.t) + " instead of t_max = " + format_num(t_max);
        const double p = beer(sigma, t_max);
        if (!close(s.pdf, p, rel_tol))
            return "passed with probability " + format_num(s.pdf) + ", but e^(-sigma_t t_max) = " + format_num(p);
        return "";
    };
    auto one = [&](double sigma, double t_max, double u) {
        const DistanceSample s = env.student.media.sample_distance(sigma, t_max, u);
        const std::string p = problems(sigma, t_max, s);
        if (p.empty())
            log.agreed();
        else
            log.mismatch("sigma_t = " + format_num(sigma) + ", t_max = " + format_num(t_max) + ", u = " +
                         format_num(u) + ": " + p);
        return s;
    };
    log.category("random samples: collisions with pdf sigma_t e^(-sigma_t t), passes with e^(-sigma_t t_max)");
    for (int i = 0; i < 3000; ++i)
        one(log_uniform(rng, 1e-3, 1e2), log_uniform(rng, 1e-3, 1e2), rng.next_1d());
    log.category("sigma_t = 0: always passes, with probability 1");
    for (double t_max : {1e-3, 1.0, 1e6})
        for (double u : {0.0, 0.5, 0x1.fffffffffffffp-1})
            one(0.0, t_max, u);
    log.category("t_max infinite: always a collision");
    for (double sigma : {1e-3, 1.0, 50.0})
        for (double u : {0.0, 0.25, 0.999})
            one(sigma, kInf, u);

    log.category("distribution of t (chi-square: 20 bins of equal probability and the pass at t_max)");
    std::string chi_messages;
    const int bins = 20;
    for (auto [sigma, t_max] : {std::pair{1.0, 2.0}, {0.25, 1.0}, {3.0, kInf}}) {
        const double pass = beer(sigma, t_max), collide = 1 - pass;
        std::vector<double> observed(size_t(bins + 1), 0), expected(size_t(bins + 1), 0);
        for (int b = 0; b < bins; ++b)
            expected[size_t(b)] = samples * collide / bins;
        expected[size_t(bins)] = samples * pass;
        bool valid = true;
        for (int i = 0; i < samples && valid; ++i) {
            const DistanceSample s = env.student.media.sample_distance(sigma, t_max, rng.next_1d());
            if (!problems(sigma, t_max, s).empty()) {
                valid = false;
                break;
            }
            if (!s.scattered) {
                observed[size_t(bins)] += 1;
                continue;
            }
            // The cdf within the collisions, 0 .. 1: equal-probability bins.
            const double c = (1 - std::exp(-sigma * s.t)) / collide;
            observed[size_t(std::clamp(int(c * bins), 0, bins - 1))] += 1;
        }
        ChiSquareResult chi;
        if (!valid)
            chi.message = "not tested: some samples break the contract (above)";
        else
            chi = chi_square_test(observed, expected, significance);
        const std::string what = "sigma_t " + format_num(sigma) + ", t_max " + format_num(t_max);
        chi_messages += (chi_messages.empty() ? "" : "; ") + what + ": " + chi.message;
        if (chi.passed)
            log.agreed();
        else
            log.mismatch(what + ", " + std::to_string(samples) + " samples: " + chi.message);
    }
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "the free-flight distribution");
    r.details.insert(r.details.begin(), "chi-square tests of the distances: " + chi_messages);
    return r;
}

TaskResult check_hg_phase(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-9);
    const int n = param(spec, "cases", 3000);
    Rng rng = check_rng(env.seed, "hg_phase");
    CaseLog log;
    auto run = [&](double mu, double g) {
        const double got = env.student.media.hg_phase(mu, g), want = hg_closed_form(mu, g);
        if (close(got, want, rel_tol))
            log.agreed();
        else
            log.mismatch("cos theta = " + format_num(mu) + ", g = " + format_num(g) + ": " + format_num(got) +
                         " instead of (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^1.5) = " + format_num(want));
    };
    log.category("random g in (-0.99, 0.99) and cos theta in [-1, 1]: the closed form");
    for (int i = 0; i < n; ++i)
        run(uniform(rng, -1, 1), uniform(rng, -0.99, 0.99));
    log.category("forward, backward and sideways; g = 0 (1 / 4 pi) and |g| = 0.999");
    for (double g : {0.0, 0.3, -0.3, 0.9, -0.9, 0.999, -0.999})
        for (double mu : {-1.0, 0.0, 1.0, 0.5, -0.5})
            run(mu, g);
    log.category("integrates to 1 over the sphere (Simpson's rule, 1e-3)");
    std::string integrals;
    for (double g : {-0.9, -0.3, 0.0, 0.5, 0.95}) {
        // 2 pi times the integral over cos theta; the peak of g = 0.95 at
        // cos theta = 1 is about 62 / sr wide 0.05: 2^16 intervals resolve it.
        const int m = 1 << 16;
        const double h = 2.0 / m;
        double sum = 0;
        bool finite = true;
        for (int i = 0; i <= m; ++i) {
            const double v = env.student.media.hg_phase(-1 + i * h, g);
            finite = finite && std::isfinite(v) && v >= 0;
            sum += v * (i == 0 || i == m ? 1 : (i % 2 ? 4 : 2));
        }
        const double integral = kTwoPi * sum * h / 3;
        integrals += (integrals.empty() ? "" : ", ") + std::string("g ") + format_num(g) + ": " + format_num(integral);
        if (finite && std::fabs(integral - 1) <= 1e-3)
            log.agreed();
        else
            log.mismatch("g = " + format_num(g) + ": integrates to " + format_num(integral) +
                         (finite ? "" : " (some value is negative, NaN or infinite)") + ", not 1");
    }
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "the closed form");
    r.details.insert(r.details.begin(), "integrals over the sphere: " + integrals);
    return r;
}

TaskResult check_sample_hg(const TaskSpec& spec, const GradeEnvironment& env) {
    const int samples = param(spec, "samples", 40000);
    const double significance = param(spec, "significance", 1e-5);
    const double rel_tol = param(spec, "rel_tol", 1e-6);
    Rng rng = check_rng(env.seed, "sample_hg");
    CaseLog log;
    const int nmu = 20, nphi = 8;
    std::string chi_messages;
    for (double g : {-0.9, -0.3, 0.0, 0.5, 0.95}) {
        log.category("g = " + format_num(g) + ": unit directions");
        std::vector<double> observed(size_t(nmu * nphi), 0);
        int valid = 0;
        for (int i = 0; i < samples; ++i) {
            const Vec3 wo = random_unit(rng);
            const Vec2 u = rng.next_2d();
            const Vec3 wi = env.student.media.sample_hg(wo, g, u);
            if (!wi.is_finite() || !(std::fabs(wi.norm() - 1) <= rel_tol)) {
                log.mismatch("wo = " + format_vec(wo) + ", u = (" + format_num(u.x) + ", " + format_num(u.y) +
                             "): wi = " + format_vec(wi) + " is not a unit vector");
                continue;
            }
            log.agreed();
            ++valid;
            // cos theta about the direction of travel -wo, azimuth in -wo's frame.
            const Frame frame(-wo);
            const Vec3 local = frame.to_local(wi);
            const double mu = std::clamp(local.z, -1.0, 1.0);
            double phi = std::atan2(local.y, local.x);
            if (phi < 0) phi += kTwoPi;
            const int im = std::clamp(int(hg_cdf(mu, g) * nmu), 0, nmu - 1);
            const int ip = std::clamp(int(phi / kTwoPi * nphi), 0, nphi - 1);
            observed[size_t(im * nphi + ip)] += 1;
        }
        log.category("g = " + format_num(g) + ": distribution (chi-square, " + std::to_string(nmu) + " x " +
                     std::to_string(nphi) + " cells of equal probability)");
        ChiSquareResult chi;
        if (valid < samples / 2)
            chi.message = "too few valid samples to test the distribution";
        else
            chi = chi_square_test(observed, std::vector<double>(observed.size(), double(valid) / observed.size()),
                                  significance);
        chi_messages += (chi_messages.empty() ? "" : "; ") + std::string("g ") + format_num(g) + ": " + chi.message;
        if (chi.passed)
            log.agreed();
        else
            log.mismatch("g = " + format_num(g) + ", " + std::to_string(valid) +
                         " directions against p_HG(-dot(wo, wi)): " + chi.message);
    }
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "the Henyey-Greenstein distribution");
    r.details.insert(r.details.begin(), "chi-square tests: " + chi_messages);
    return r;
}

}  // namespace pt
