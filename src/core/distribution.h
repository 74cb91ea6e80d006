// Piecewise-constant distributions for importance sampling tabulated
// functions (pbrt-v3 section 13.3.1 and 13.6.7): Distribution1D samples an
// index or a continuous x in [0, 1) with density proportional to a step
// function; Distribution2D samples (u, v) in [0, 1)^2 proportional to a
// grid of values, as the marginal in v times the conditional in u.
// The environment map uses it to send samples where the sky is bright.
#pragma once

#include <vector>

#include "core/vec3.h"

namespace pt {

class Distribution1D {
public:
    /// `f` >= 0; if every value is 0 the distribution is uniform.
    explicit Distribution1D(std::vector<double> f);

    int count() const { return int(f_.size()); }
    /// Integral of the step function over [0, 1].
    double integral() const { return integral_; }
    /// Continuous sample: x in [0, 1) with density f(x) / integral; `pdf`
    /// receives that density and `index` the step it falls in.
    double sample_continuous(double u, double* pdf, int* index) const;
    /// Density of the continuous sample at step `index`.
    double pdf(int index) const { return f_[index] / integral_; }

private:
    std::vector<double> f_;    ///< the step heights (all 1 when the input was all 0)
    std::vector<double> cdf_;  ///< count + 1 entries, cdf_[0] = 0, cdf_[count] = 1
    double integral_ = 0;
};

class Distribution2D {
public:
    /// `f` has nu * nv values, row v first (f[v * nu + u]), all >= 0.
    Distribution2D(const std::vector<double>& f, int nu, int nv);

    /// (u, v) in [0, 1)^2 with density f / integral; `pdf` receives it.
    Vec2 sample_continuous(Vec2 sample, double* pdf) const;
    /// Density at (u, v) in [0, 1]^2.
    double pdf(Vec2 uv) const;

private:
    std::vector<Distribution1D> conditional_;  ///< one per row v
    Distribution1D marginal_;                  ///< over rows, by their integrals
};

}  // namespace pt
