#include "render/splat_film.h"

#include <cmath>

namespace pt {
namespace {

constexpr double kUnit = 268435456.0;  // 2^28 units per unit of radiance
constexpr double kLimit = 9.0e18;      // below 2^63

thread_local SplatFilm* thread_film = nullptr;

int64_t to_fixed(double v) {
    const double scaled = std::nearbyint(v * kUnit);
    if (!(std::fabs(scaled) < kLimit)) return 0;  // NaN, or beyond the range: dropped
    return int64_t(scaled);
}

/// a + b, saturating instead of overflowing.
int64_t add_saturating(int64_t a, int64_t b) {
    int64_t r;
    if (__builtin_add_overflow(a, b, &r)) return b > 0 ? INT64_MAX : INT64_MIN;
    return r;
}

}  // namespace

SplatFilm::SplatFilm(int width, int height, int layers)
    : width_(width), height_(height), layers_(layers),
      sums_(size_t(width) * size_t(height) * 3 * size_t(layers), 0) {}

void SplatFilm::add(int layer, Vec2 film, const Color& c) {
    if (layer < 0 || layer >= layers_ || !c.is_finite()) return;
    const int x = int(std::floor(film.x * width_));
    const int y = int(std::floor((1.0 - film.y) * height_));  // rows run top to bottom
    if (x < 0 || x >= width_ || y < 0 || y >= height_) return;
    int64_t* px = &sums_[((size_t(layer) * height_ + y) * width_ + x) * 3];
    px[0] = add_saturating(px[0], to_fixed(c.r));
    px[1] = add_saturating(px[1], to_fixed(c.g));
    px[2] = add_saturating(px[2], to_fixed(c.b));
}

void SplatFilm::merge(const SplatFilm& other) {
    for (size_t i = 0; i < sums_.size() && i < other.sums_.size(); ++i)
        sums_[i] = add_saturating(sums_[i], other.sums_[i]);
    paths_ += other.paths_;
}

Color SplatFilm::value(int layer, int x, int y) const {
    if (paths_ == 0) return Color(0);
    const int64_t* px = &sums_[((size_t(layer) * height_ + y) * width_ + x) * 3];
    const double scale = double(width_) * double(height_) / (double(paths_) * kUnit);
    return Color(double(px[0]) * scale, double(px[1]) * scale, double(px[2]) * scale);
}

SplatFilm* current_splat_film() { return thread_film; }
void set_current_splat_film(SplatFilm* film) { thread_film = film; }

}  // namespace pt
