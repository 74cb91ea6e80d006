#include "grade/chi_square.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pt {
namespace {

// P(a, x) = e^-x x^a / Gamma(a + 1) * sum_n x^n / ((a + 1) ... (a + n)), for x < a + 1.
double gamma_p_series(double a, double x) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000; ++n) {
        term *= x / (a + n);
        sum += term;
        if (std::fabs(term) < std::fabs(sum) * 1e-16) break;
    }
    return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by its continued fraction (modified Lentz), for x >= a + 1.
double gamma_q_fraction(double a, double x) {
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-16) break;
    }
    return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double regularized_gamma_q(double a, double x) {
    if (!(x > 0)) return 1.0;
    return x < a + 1.0 ? 1.0 - gamma_p_series(a, x) : gamma_q_fraction(a, x);
}

double chi_square_p_value(double statistic, int dof) {
    return regularized_gamma_q(0.5 * dof, 0.5 * statistic);
}

ChiSquareResult chi_square_test(const std::vector<double>& observed,
                                const std::vector<double>& expected, double significance) {
    const double min_expected = 5.0;
    ChiSquareResult r;
    std::vector<std::pair<double, double>> cells;  // (observed, expected) after pooling
    double pool_observed = 0, pool_expected = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        if (!(expected[i] > 0)) {
            if (observed[i] > 0) {
                r.message = std::to_string(int(observed[i])) + " samples in cell " +
                            std::to_string(i) + ", where the pdf predicts none";
                return r;
            }
        } else if (expected[i] < min_expected) {
            pool_observed += observed[i];
            pool_expected += expected[i];
        } else {
            cells.push_back({observed[i], expected[i]});
        }
    }
    if (pool_expected > 0) {
        if (pool_expected < min_expected && !cells.empty()) {
            cells.back().first += pool_observed;
            cells.back().second += pool_expected;
        } else {
            cells.push_back({pool_observed, pool_expected});
        }
    }
    if (cells.size() < 2) {
        r.message = "fewer than 2 cells after pooling: the test has no power";
        return r;
    }
    for (const auto& [o, e] : cells)
        r.statistic += (o - e) * (o - e) / e;
    r.dof = int(cells.size()) - 1;
    r.p_value = chi_square_p_value(r.statistic, r.dof);
    r.passed = r.p_value >= significance;
    char buf[200];
    std::snprintf(buf, sizeof buf, "chi2 = %.1f with %d degrees of freedom, p = %.3g %s %.3g",
                  r.statistic, r.dof, r.p_value, r.passed ? ">=" : "<", significance);
    r.message = buf;
    return r;
}

}  // namespace pt
