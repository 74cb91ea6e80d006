#include "image/metrics.h"

#include <cmath>
#include <stdexcept>

namespace pt {
namespace {

template <class Term>
double mean_over_channels(const Image& image, const Image& reference, Term term) {
    if (image.width() != reference.width() || image.height() != reference.height())
        throw std::invalid_argument("image metrics: the images differ in size");
    const std::vector<float>& a = image.data();
    const std::vector<float>& b = reference.data();
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i)
        sum += term(double(a[i]), double(b[i]));
    return a.empty() ? 0.0 : sum / double(a.size());
}

}  // namespace

double rmse(const Image& image, const Image& reference) {
    return std::sqrt(
        mean_over_channels(image, reference, [](double a, double b) { return (a - b) * (a - b); }));
}

double relmse(const Image& image, const Image& reference) {
    return mean_over_channels(
        image, reference, [](double a, double b) { return (a - b) * (a - b) / (b * b + 1e-2); });
}

}  // namespace pt
