// Part 3, power_heuristic and balance_heuristic (task 3.7): both weights
// against their closed forms (Veach 1997, sections 9.2.2 and 9.2.4) on
// random sample counts and densities over twelve decades, the limits the
// contract states (a strategy that cannot draw the sample: 0; a delta
// against a finite density: 1; two deltas: 0.5), densities up to 1e300
// (no overflow to inf / inf), and that the two strategies' weights sum to 1.
// Deterministic: no random numbers reach the student's code.
#include <cmath>

#include "grade/case_log.h"
#include "grade/function_checks.h"
#include "grade/params.h"
#include "grade/random_inputs.h"

namespace pt {
namespace {

/// The exact weights in long double, from the definitions.
double exact_weight(bool power, double nf, double pf, double ng, double pg) {
    long double f = (long double)nf * pf, g = (long double)ng * pg;
    if (power) f *= f, g *= g;
    return double(f / (f + g));
}

}  // namespace

TaskResult check_mis_heuristics(const TaskSpec& spec, const GradeEnvironment& env) {
    const double rel_tol = param(spec, "rel_tol", 1e-9);
    const int n = param(spec, "cases", 2000);
    Rng rng = check_rng(env.seed, "mis_heuristics");
    CaseLog log;
    const double inf = std::numeric_limits<double>::infinity();
    for (bool power : {true, false}) {
        MisHeuristicFn w = power ? env.student.direct.power_heuristic : env.student.direct.balance_heuristic;
        const std::string name = power ? "power_heuristic" : "balance_heuristic";
        auto call = [&](double nf, double pf, double ng, double pg) {
            return "(" + format_num(nf) + ", " + format_num(pf) + ", " + format_num(ng) + ", " +
                   format_num(pg) + ")";
        };
        auto expect = [&](double nf, double pf, double ng, double pg, double want) {
            double got = w(nf, pf, ng, pg);
            if (std::fabs(got - want) <= rel_tol * std::max(1.0, std::fabs(want))) {
                log.agreed();
            } else {
                log.mismatch(name + call(nf, pf, ng, pg) + " = " + format_num(got) + " instead of " +
                             format_num(want));
            }
        };
        log.category(name + ": random counts and densities (1e-6 to 1e6)");
        for (int i = 0; i < n; ++i) {
            double nf = 1 + double(rng.next_index(16)), ng = 1 + double(rng.next_index(16));
            double pf = std::pow(10.0, uniform(rng, -6, 6)), pg = std::pow(10.0, uniform(rng, -6, 6));
            expect(nf, pf, ng, pg, exact_weight(power, nf, pf, ng, pg));
        }
        log.category(name + ": limits (zero, delta, two deltas, huge and tiny densities)");
        expect(1, 0.0, 1, 2.5, 0.0);
        expect(1, 0.0, 1, 0.0, 0.0);
        expect(1, 0.5, 0, 7.0, 1.0);
        expect(1, inf, 1, 0.25, 1.0);
        expect(1, 0.25, 1, inf, 0.0);
        expect(1, inf, 1, inf, 0.5);
        expect(1, 1e300, 1, 1e300, 0.5);
        expect(4, 1e300, 1, 1e300, exact_weight(power, 4, 1, 1, 1));
        expect(1, 1e-300, 1, 1e-300, 0.5);
        log.category(name + ": the two strategies' weights sum to 1");
        for (int i = 0; i < n / 4; ++i) {
            double nf = 1 + double(rng.next_index(8)), ng = 1 + double(rng.next_index(8));
            double pf = std::pow(10.0, uniform(rng, -3, 3)), pg = std::pow(10.0, uniform(rng, -3, 3));
            double sum = w(nf, pf, ng, pg) + w(ng, pg, nf, pf);
            if (std::fabs(sum - 1) <= rel_tol) {
                log.agreed();
            } else {
                log.mismatch(name + call(nf, pf, ng, pg) + " + " + name + call(ng, pg, nf, pf) +
                             " = " + format_num(sum) + ", not 1");
            }
        }
    }
    return log.finish(spec, param(spec, "max_mismatches", 0), "the closed forms");
}

}  // namespace pt
