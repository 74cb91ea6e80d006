#include "scene/texture.h"

#include <cmath>

#include "core/error.h"
#include "core/files.h"
#include "image/image_io.h"

namespace pt {
namespace {

/// i modulo n in [0, n), also for negative i.
int wrap(long long i, int n) {
    long long m = i % n;
    return int(m < 0 ? m + n : m);
}

}  // namespace

Color ImageTexture::evaluate(Vec2 uv) const {
    const int w = image_.width(), h = image_.height();
    // Continuous texel coordinates, with texel centres at integers.
    double s = uv.x * scale_.x * w - 0.5;
    double t = (1.0 - uv.y * scale_.y) * h - 0.5;
    if (!std::isfinite(s) || !std::isfinite(t)) return image_.at(0, 0);
    double fs = std::floor(s), ft = std::floor(t);
    double a = s - fs, b = t - ft;
    long long x0 = (long long)fs, y0 = (long long)ft;
    int xa = wrap(x0, w), xb = wrap(x0 + 1, w), ya = wrap(y0, h), yb = wrap(y0 + 1, h);
    return (1 - a) * (1 - b) * image_.at(xa, ya) + a * (1 - b) * image_.at(xb, ya) + (1 - a) * b * image_.at(xa, yb) +
           a * b * image_.at(xb, yb);
}

Color CheckerboardTexture::evaluate(Vec2 uv) const {
    double i = std::floor(uv.x * scale_.x), j = std::floor(uv.y * scale_.y);
    if (!std::isfinite(i + j)) return even_;
    return std::fmod(std::fabs(i + j), 2.0) < 1.0 ? even_ : odd_;
}

std::shared_ptr<const Texture> load_albedo_texture(const std::string& path, const std::string& where, Vec2 scale) {
    require_readable_file(path, where);
    Image image;
    try {
        image = read_image(path);
    } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
    }
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            Color c = image.at(x, y);
            if (!c.is_finite() || c.r < 0 || c.g < 0 || c.b < 0 || c.r > 1 || c.g > 1 || c.b > 1)
                throw InputError(where + ": " + path + ": texel (" + std::to_string(x) + ", " + std::to_string(y) +
                                 ") is not a reflectance in [0, 1]");
        }
    return std::make_shared<const ImageTexture>(std::move(image), scale);
}

}  // namespace pt
