#include "image/colormap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "image/metrics.h"
#include "image/tonemap.h"

namespace pt {
namespace {

// Viridis at t = 0, 1/9, ..., 1 (8-bit sRGB), read off the published map.
constexpr int kStops = 10;
constexpr unsigned char kViridis[kStops][3] = {
    {68, 1, 84},    {72, 40, 120},  {62, 73, 137},  {49, 104, 142}, {38, 130, 142},
    {31, 158, 137}, {53, 183, 121}, {110, 206, 88}, {181, 222, 43}, {253, 231, 37},
};

}  // namespace

Color viridis_srgb(double t) {
    if (!(t >= 0)) t = 0;  // also catches NaN
    if (t > 1) t = 1;
    double s = t * (kStops - 1);
    int i = std::min(int(s), kStops - 2);
    double f = s - i;
    double v[3];
    for (int k = 0; k < 3; ++k)
        v[k] = ((1 - f) * kViridis[i][k] + f * kViridis[i + 1][k]) / 255.0;
    return Color(v[0], v[1], v[2]);
}

std::vector<std::string> viridis_hex_stops() {
    std::vector<std::string> stops;
    for (const auto& rgb : kViridis) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
        stops.push_back(buf);
    }
    return stops;
}

double heatmap_position(double value, const HeatmapScale& scale) {
    if (std::isnan(value)) return value;
    if (value <= scale.low) return 0;
    if (value >= scale.high) return 1;
    return (std::log10(value) - std::log10(scale.low)) /
           (std::log10(scale.high) - std::log10(scale.low));
}

Image error_heatmap(const Image& image, const Image& reference, const HeatmapScale& scale) {
    std::vector<double> error = per_pixel_relmse(image, reference);
    Image map(image.width(), image.height());
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            double t = heatmap_position(error[size_t(y) * image.width() + x], scale);
            // Stored linear: write_png encodes to sRGB, giving back the map's colours.
            Color srgb = std::isnan(t) ? Color(1, 0, 1) : viridis_srgb(t);
            map.set(x, y, Color(srgb_decode(srgb.r), srgb_decode(srgb.g), srgb_decode(srgb.b)));
        }
    }
    return map;
}

}  // namespace pt
