#include "core/distribution.h"

#include <algorithm>
#include <cmath>

namespace pt {

Distribution1D::Distribution1D(std::vector<double> f) : f_(std::move(f)), cdf_(f_.size() + 1, 0.0) {
    const double n = double(f_.size());
    for (size_t i = 0; i < f_.size(); ++i) cdf_[i + 1] = cdf_[i] + std::max(f_[i], 0.0) / n;
    integral_ = cdf_.back();
    if (!(integral_ > 0)) {
        // Nothing to prefer: sample uniformly.
        std::fill(f_.begin(), f_.end(), 1.0);
        for (size_t i = 0; i < f_.size(); ++i) cdf_[i + 1] = double(i + 1) / n;
        integral_ = 1.0;
    } else {
        for (double& c : cdf_) c /= integral_;
    }
    cdf_.back() = 1.0;
}

double Distribution1D::sample_continuous(double u, double* pdf, int* index) const {
    // The last step whose cdf is <= u; steps of zero width are never chosen.
    int i = int(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()) - 1;
    i = std::clamp(i, 0, count() - 1);
    while (i > 0 && f_[i] <= 0) --i;  // only reachable through rounding at a boundary
    double width = cdf_[i + 1] - cdf_[i];
    double du = width > 0 ? (u - cdf_[i]) / width : 0.5;
    if (pdf) *pdf = f_[i] / integral_;
    if (index) *index = i;
    return std::min((i + std::clamp(du, 0.0, 1.0)) / count(), std::nextafter(1.0, 0.0));
}

namespace {
std::vector<double> row_integrals(const std::vector<double>& f, int nu, int nv) {
    std::vector<double> rows(size_t(nv), 0.0);
    for (int v = 0; v < nv; ++v)
        for (int u = 0; u < nu; ++u) rows[size_t(v)] += std::max(f[size_t(v) * nu + u], 0.0) / nu;
    return rows;
}
}  // namespace

Distribution2D::Distribution2D(const std::vector<double>& f, int nu, int nv)
    : marginal_(row_integrals(f, nu, nv)) {
    conditional_.reserve(size_t(nv));
    for (int v = 0; v < nv; ++v)
        conditional_.emplace_back(std::vector<double>(f.begin() + long(v) * nu, f.begin() + long(v + 1) * nu));
}

Vec2 Distribution2D::sample_continuous(Vec2 sample, double* pdf) const {
    double pdf_v = 0, pdf_u = 0;
    int row = 0;
    double v = marginal_.sample_continuous(sample.y, &pdf_v, &row);
    double u = conditional_[size_t(row)].sample_continuous(sample.x, &pdf_u, nullptr);
    if (pdf) *pdf = pdf_u * pdf_v;
    return {u, v};
}

double Distribution2D::pdf(Vec2 uv) const {
    int nv = marginal_.count();
    int row = std::clamp(int(uv.y * nv), 0, nv - 1);
    const Distribution1D& c = conditional_[size_t(row)];
    int column = std::clamp(int(uv.x * c.count()), 0, c.count() - 1);
    return c.pdf(column) * marginal_.pdf(row);
}

}  // namespace pt
