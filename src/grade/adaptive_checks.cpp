// Part 5, has_converged: the student's convergence test against CS184's
// rule on hand-constructed pixel statistics:
//
//     mu = s1 / n,  sigma^2 = (s2 - s1^2 / n) / (n - 1),  I = 1.96 sigma / sqrt(n),
//     converged  <=>  I <= max_tolerance * mu
//
// evaluated in long double from the statistics given. Either answer is
// accepted where the rule says nothing reliable:
//   - n < 2 (no variance estimate);
//   - samples that are all equal, up to rounding (sigma^2 <= 1e-12 mu^2),
//     including all zero: the textbook rule stops there, the reference's
//     rare-event guard (stages/adaptive.h) does not, and both are right;
//   - I within edge_band (relative) of max_tolerance * mu, where one
//     rounding flips the verdict.
// Everything else must match the rule. The statistics are drawn near the
// threshold (I / (tol mu) = 1 +- delta, delta from 1e-6 to 0.5: a variance
// divided by n instead of n - 1, or 1.645 for 1.96, shows there), far from
// it, and accumulated from real sample sequences (uniform, exponential,
// rare bright events), as the pixel loop accumulates them.
#include <cmath>

#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"

namespace pt {
namespace {

enum class Verdict { converged, not_converged, either };

struct RuleAnswer {
    Verdict verdict = Verdict::either;
    long double interval = 0, limit = 0;  ///< I and max_tolerance * mu
    const char* why_either = "";
};

RuleAnswer textbook_rule(const PixelStatistics& s, double tol, double edge_band) {
    RuleAnswer a;
    if (s.n < 2) {
        a.why_either = "n < 2: no variance estimate";
        return a;
    }
    const long double n = s.n, mu = s.s1 / n;
    const long double variance = (s.s2 - (long double)s.s1 * s.s1 / n) / (n - 1);
    if (!(variance > 1e-12L * mu * mu)) {
        a.why_either = "all samples equal: the rare-event guard may continue";
        return a;
    }
    a.interval = 1.96L * sqrtl(variance) / sqrtl(n);
    a.limit = tol * mu;
    if (fabsl(a.interval - a.limit) <= edge_band * (a.interval + a.limit)) {
        a.why_either = "on the threshold";
        return a;
    }
    a.verdict = a.interval <= a.limit ? Verdict::converged : Verdict::not_converged;
    return a;
}

/// Statistics of n samples with mean mu and sample standard deviation sigma.
PixelStatistics statistics(int n, double mu, double sigma) {
    PixelStatistics s;
    s.n = n;
    s.s1 = n * mu;
    s.s2 = (n - 1) * sigma * sigma + s.s1 * s.s1 / n;
    return s;
}

int random_n(Rng& rng) {
    const int batches[] = {2, 4, 8, 16, 32, 64, 96, 128, 256, 512, 1024, 4096, 65536};
    if (rng.next_1d() < 0.8) return batches[rng.next_index(13)];
    return 2 + int(rng.next_index(5000));
}

double random_tolerance(Rng& rng) {
    const double tolerances[] = {0.01, 0.05, 0.1, 0.2};
    return rng.next_1d() < 0.7 ? tolerances[rng.next_index(4)] : log_uniform(rng, 1e-3, 0.5);
}

}  // namespace

TaskResult check_has_converged(const TaskSpec& spec, const GradeEnvironment& env) {
    const HasConvergedFn student = env.student.adaptive.has_converged;
    const double band = param(spec, "edge_band", 1e-9);
    const int n_cases = param(spec, "cases", 3000);
    Rng rng = check_rng(env.seed, "has_converged");
    CaseLog log;
    auto run = [&](const PixelStatistics& s, double tol) {
        RuleAnswer want = textbook_rule(s, tol, band);
        bool got = student(s, tol);
        if (want.verdict == Verdict::either) {
            log.allowed();
            return;
        }
        if (got == (want.verdict == Verdict::converged)) {
            log.agreed();
            return;
        }
        log.mismatch("n = " + std::to_string(s.n) + ", s1 = " + format_num(s.s1) +
                     ", s2 = " + format_num(s.s2) + ", max_tolerance " + format_num(tol) +
                     ": says " + (got ? "converged" : "not converged") +
                     ", but I = 1.96 sigma / sqrt(n) = " + format_num(double(want.interval)) +
                     (want.verdict == Verdict::converged ? " <= " : " > ") +
                     "max_tolerance * mu = " + format_num(double(want.limit)));
    };

    log.category("near the threshold (I / (tol mu) = 1 +- 1e-6 .. 0.5)");
    for (int i = 0; i < n_cases; ++i) {
        int n = random_n(rng);
        double mu = log_uniform(rng, 1e-3, 1e3), tol = random_tolerance(rng);
        double ratio = 1 + (i % 2 ? 1 : -1) * log_uniform(rng, 1e-6, 0.5);
        run(statistics(n, mu, ratio * tol * mu * std::sqrt(double(n)) / 1.96), tol);
    }
    log.category("far from the threshold (I / (tol mu) = 0.01 .. 0.5 or 2 .. 100)");
    for (int i = 0; i < n_cases / 2; ++i) {
        int n = random_n(rng);
        double mu = log_uniform(rng, 1e-3, 1e3), tol = random_tolerance(rng);
        double ratio = i % 2 ? log_uniform(rng, 2, 100) : log_uniform(rng, 0.01, 0.5);
        run(statistics(n, mu, ratio * tol * mu * std::sqrt(double(n)) / 1.96), tol);
    }
    log.category("sums of real samples, as the pixel loop keeps them");
    for (int i = 0; i < n_cases / 4; ++i) {
        int batch = 1 << (2 + rng.next_index(5)), batches = 1 + int(rng.next_index(16));
        double tol = random_tolerance(rng), scale = log_uniform(rng, 1e-2, 1e2);
        PixelStatistics s;
        const uint32_t kind = rng.next_index(4);
        double p = log_uniform(rng, 1e-3, 0.5);
        for (int k = 0; k < batch * batches; ++k) {
            double u = rng.next_1d(), x = 0;
            switch (kind) {
                case 0:
                    x = scale * (1 + 0.2 * (u - 0.5));
                    break;  // smooth wall
                case 1:
                    x = -scale * std::log(1 - u);
                    break;  // exponential
                case 2:
                    x = u < p ? scale / p : 0;
                    break;  // a rare bright light
                default:
                    x = scale * (u < 0.5 ? 1 : 3);
                    break;  // an edge
            }
            s.s1 += x;
            s.s2 += x * x;
            s.n = k + 1;
            if (s.n % batch == 0) run(s, tol);  // after every batch, as the pixel loop asks
        }
    }
    log.category("all samples equal, n < 2 (either answer is accepted)");
    for (int n : {1, 2, 32, 64, 1024})
        for (double x : {0.0, 0.5, 17.0}) {
            PixelStatistics s;
            for (int k = 0; k < n; ++k)
                s.s1 += x, s.s2 += x * x, s.n = k + 1;
            run(s, 0.05);
        }
    TaskResult r = log.finish(spec, param(spec, "max_mismatches", 0), "CS184's rule");
    if (r.status == TaskStatus::pass) {
        r.message = "agrees with CS184's rule on " +
                    std::to_string(log.cases() - log.allowed_count()) + " statistics; " +
                    std::to_string(log.allowed_count()) +
                    " more accept either answer (equal samples, n < 2, or on the threshold)";
    }
    return r;
}

}  // namespace pt
