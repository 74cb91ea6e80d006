// Pearson's chi-square goodness-of-fit test, for the sampling checks of
// the grader (diffuse_sample_f). The same method as tests/statistical/chi2.h
// (Nori's warptest, Jakob), reduced to what the grader needs at run time:
//
//   - observed counts per cell against the counts a pdf predicts;
//   - cells expecting fewer than 5 samples are pooled (Cochran's rule);
//   - a sample where the pdf predicts none fails outright;
//   - the p-value is the upper tail Q(dof / 2, chi2 / 2) of the chi-square
//     distribution, the regularised upper incomplete gamma function, by its
//     power series or continued fraction (Abramowitz and Stegun 6.5.29 and
//     6.5.31; Lentz's method);
//   - the test rejects when p < the significance the manifest states.
#pragma once

#include <string>
#include <vector>

namespace pt {

/// Q(a, x) = Gamma(a, x) / Gamma(a), a > 0, x >= 0.
double regularized_gamma_q(double a, double x);

/// P(chi-square with `dof` degrees of freedom >= statistic).
double chi_square_p_value(double statistic, int dof);

struct ChiSquareResult {
    bool passed = false;
    double statistic = 0;
    int dof = 0;
    double p_value = 0;
    std::string message;  ///< the figures, or why the test could not be made
};

/// Pearson's test of `observed` against `expected` counts per cell at
/// `significance`, pooling cells that expect fewer than 5.
ChiSquareResult chi_square_test(const std::vector<double>& observed,
                                const std::vector<double>& expected, double significance);

}  // namespace pt
