#include "render/sample_rate_image.h"

#include <algorithm>

namespace pt {

Color rate_color(double t) {
    t = std::clamp(t, 0.0, 1.0);
    if (t < 0.5) return Color(0, 2 * t, 1 - 2 * t);
    return Color(2 * t - 1, 2 - 2 * t, 0);
}

Image make_sample_rate_image(const std::vector<uint32_t>& counts, int width, int height) {
    Image image(width, height);
    uint32_t most = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            uint32_t n = counts[size_t(y) * width + x];
            // Pixels outside a -p cell have no samples: leave them black.
            if (n > 0) image.set(x, y, rate_color(double(n) / most));
        }
    return image;
}

std::string rate_image_path(const std::string& output_png) {
    size_t dot = output_png.find_last_of('.');
    size_t slash = output_png.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return output_png + "_rate.png";
    return output_png.substr(0, dot) + "_rate" + output_png.substr(dot);
}

}  // namespace pt
