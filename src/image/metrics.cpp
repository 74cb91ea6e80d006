#include "image/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"

namespace pt {

void require_same_size(const Image& a, const Image& b, const std::string& what) {
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError(what + ": sizes differ: " + std::to_string(a.width()) + "x" +
                         std::to_string(a.height()) + " against " + std::to_string(b.width()) +
                         "x" + std::to_string(b.height()));
    if (a.empty()) throw InputError(what + ": the images are empty");
}

namespace {

/// Mean over all values of f(a_i, b_i), accumulated in double.
template <typename F>
double mean_of(const Image& a, const Image& b, F f) {
    require_same_size(a, b);
    const std::vector<float>& x = a.data();
    const std::vector<float>& y = b.data();
    double sum = 0;
    for (size_t i = 0; i < x.size(); ++i)
        sum += f(double(x[i]), double(y[i]));
    return sum / double(x.size());
}

}  // namespace

double mse(const Image& a, const Image& b) {
    return mean_of(a, b, [](double x, double y) { return (x - y) * (x - y); });
}

double rmse(const Image& a, const Image& b) {
    return std::sqrt(mse(a, b));
}

double relmse(const Image& a, const Image& b) {
    return mean_of(a, b,
                   [](double x, double y) { return (x - y) * (x - y) / (y * y + kRelMseEpsilon); });
}

double psnr(const Image& a, const Image& b) {
    double e = mse(a, b);
    if (e == 0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(1.0 / e);
}

double mean_abs_diff(const Image& a, const Image& b) {
    return mean_of(a, b, [](double x, double y) { return std::abs(x - y); });
}

namespace {

size_t count_over(const Image& a, const Image& b, double threshold) {
    require_same_size(a, b);
    size_t over = 0;
    for (int y = 0; y < a.height(); ++y) {
        for (int x = 0; x < a.width(); ++x) {
            Color d = a.at(x, y) - b.at(x, y);
            double m = std::max({std::abs(d.r), std::abs(d.g), std::abs(d.b)});
            // NaN counts as over: a broken pixel is never "close enough".
            if (!(m <= threshold)) ++over;
        }
    }
    return over;
}

}  // namespace

double share_over(const Image& a, const Image& b, double threshold) {
    return double(count_over(a, b, threshold)) / double(a.pixel_count());
}

ImageMetrics compare_images(const Image& a, const Image& b, double threshold) {
    ImageMetrics m;
    m.rmse = rmse(a, b);
    m.relmse = relmse(a, b);
    m.psnr = psnr(a, b);
    m.mean_abs_diff = mean_abs_diff(a, b);
    m.threshold = threshold;
    m.pixels_over = count_over(a, b, threshold);
    m.share_over = double(m.pixels_over) / double(a.pixel_count());
    return m;
}

std::vector<double> per_pixel_relmse(const Image& a, const Image& b) {
    require_same_size(a, b);
    std::vector<double> out(a.pixel_count());
    for (int y = 0; y < a.height(); ++y) {
        for (int x = 0; x < a.width(); ++x) {
            Color p = a.at(x, y), q = b.at(x, y);
            double sum = 0;
            for (int c = 0; c < 3; ++c)
                sum += (p[c] - q[c]) * (p[c] - q[c]) / (q[c] * q[c] + kRelMseEpsilon);
            out[size_t(y) * a.width() + x] = sum / 3.0;
        }
    }
    return out;
}

}  // namespace pt
