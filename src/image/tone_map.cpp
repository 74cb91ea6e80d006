#include "image/tone_map.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pt {
namespace {

/// Narkowicz's ACES fit, one channel; 0 at 0, 1 at about 10.
double aces_filmic(double x) {
    x = std::max(x, 0.0);
    return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

Color clamped(const Color& c) {
    return {std::clamp(c.r, 0.0, 1.0), std::clamp(c.g, 0.0, 1.0), std::clamp(c.b, 0.0, 1.0)};
}

/// The colour c with its luminance changed from y to y_new (hue and
/// saturation kept); black stays black.
Color with_luminance(const Color& c, double y, double y_new) {
    return y > 0 ? c * (y_new / y) : Color(0);
}

/// Durand and Dorsey's operator (see the header).
Image local_operator(const Image& image) {
    const int width = image.width(), height = image.height();
    const size_t n = image.pixel_count();
    std::vector<float> log_y(n);
    // Black pixels (Y = 0) stay black whatever their log; giving them the
    // darkest real value keeps them out of the compression range.
    double darkest = 1e300;
    for (size_t i = 0; i < n; ++i) {
        double y = image.at(int(i % size_t(width)), int(i / size_t(width))).luminance();
        if (y > 0) darkest = std::min(darkest, std::log10(y));
    }
    if (darkest == 1e300) return Image(width, height);  // all black
    for (size_t i = 0; i < n; ++i) {
        double y = image.at(int(i % size_t(width)), int(i / size_t(width))).luminance();
        log_y[i] = float(y > 0 ? std::max(std::log10(y), darkest) : darkest);
    }
    const double sigma_spatial = std::max(1.0, 0.02 * std::max(width, height));
    std::vector<float> base = bilateral_filter(log_y, width, height, sigma_spatial, 0.4);
    auto [low, high] = std::minmax_element(base.begin(), base.end());
    // Compress the base to two decades (100:1); never expand a smaller range.
    const double range = double(*high) - double(*low);
    const double scale = range > 2.0 ? 2.0 / range : 1.0;
    Image out(width, height);
    for (size_t i = 0; i < n; ++i) {
        int x = int(i % size_t(width)), y = int(i / size_t(width));
        Color c = image.at(x, y);
        double detail = double(log_y[i]) - base[i];
        double log_out = (double(base[i]) - *high) * scale + detail;
        out.set(x, y, clamped(with_luminance(c, c.luminance(), std::pow(10.0, log_out))));
    }
    return out;
}

}  // namespace

const char* to_string(ToneMap tone_map) {
    switch (tone_map) {
        case ToneMap::clamp: return "clamp";
        case ToneMap::reinhard: return "reinhard";
        case ToneMap::filmic: return "filmic";
        case ToneMap::local: return "local";
    }
    return "?";
}

std::vector<float> bilateral_filter(const std::vector<float>& values, int width, int height, double sigma_spatial,
                                    double sigma_range) {
    const int radius = int(std::ceil(2.0 * sigma_spatial));
    // The spatial kernel is separable in its weights: exp(-dx^2/2s^2) exp(-dy^2/2s^2).
    std::vector<double> spatial(size_t(radius) + 1);
    for (int d = 0; d <= radius; ++d) spatial[size_t(d)] = std::exp(-0.5 * d * d / (sigma_spatial * sigma_spatial));
    const double range_factor = -0.5 / (sigma_range * sigma_range);
    std::vector<float> out(values.size());
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double center = values[size_t(y) * width + x];
            double sum = 0, weights = 0;
            for (int v = std::max(0, y - radius); v <= std::min(height - 1, y + radius); ++v) {
                const double wy = spatial[size_t(std::abs(v - y))];
                const float* row = &values[size_t(v) * width];
                for (int u = std::max(0, x - radius); u <= std::min(width - 1, x + radius); ++u) {
                    double difference = row[u] - center;
                    double w = wy * spatial[size_t(std::abs(u - x))] * std::exp(range_factor * difference * difference);
                    sum += w * row[u];
                    weights += w;
                }
            }
            out[size_t(y) * width + x] = float(sum / weights);  // weights >= 1: the centre pixel
        }
    }
    return out;
}

Image tone_map(const Image& radiance, const DisplaySettings& settings) {
    const double gain = std::exp2(settings.exposure);
    Image exposed(radiance.width(), radiance.height());
    for (int y = 0; y < radiance.height(); ++y)
        for (int x = 0; x < radiance.width(); ++x) {
            Color c = radiance.at(x, y) * gain;
            // Negative or non-finite components (never from the renderer, but
            // a PFM may hold them) show as black.
            exposed.set(x, y, Color(std::isfinite(c.r) ? std::max(c.r, 0.0) : 0.0,
                                    std::isfinite(c.g) ? std::max(c.g, 0.0) : 0.0,
                                    std::isfinite(c.b) ? std::max(c.b, 0.0) : 0.0));
        }
    if (settings.tone_map == ToneMap::local) return local_operator(exposed);
    Image out(radiance.width(), radiance.height());
    for (int y = 0; y < radiance.height(); ++y)
        for (int x = 0; x < radiance.width(); ++x) {
            Color c = exposed.at(x, y);
            switch (settings.tone_map) {
                case ToneMap::clamp: c = clamped(c); break;
                case ToneMap::reinhard: {
                    double lum = c.luminance();
                    c = clamped(with_luminance(c, lum, lum / (1.0 + lum)));
                    break;
                }
                case ToneMap::filmic: c = Color(aces_filmic(c.r), aces_filmic(c.g), aces_filmic(c.b)); break;
                case ToneMap::local: break;
            }
            out.set(x, y, c);
        }
    return out;
}

}  // namespace pt
