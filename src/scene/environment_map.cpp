#include "scene/environment_map.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "image/image_io.h"

namespace pt {
namespace {

/// Sampling weights: luminance times sin(theta) of each pixel's centre row
/// (the sin accounts for the rows near the poles covering less solid angle).
std::vector<double> sampling_weights(const Image& image) {
    std::vector<double> f(image.pixel_count());
    for (int y = 0; y < image.height(); ++y) {
        double sin_theta = std::sin(kPi * (y + 0.5) / image.height());
        for (int x = 0; x < image.width(); ++x)
            f[size_t(y) * image.width() + x] = std::max(image.at(x, y).luminance(), 0.0) * sin_theta;
    }
    return f;
}

Image scaled(Image image, Color scale) {
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) image.set(x, y, image.at(x, y) * scale);
    return image;
}

}  // namespace

EnvironmentMap::EnvironmentMap(Image image, Color scale)
    : image_(scaled(std::move(image), scale)),
      distribution_(sampling_weights(image_), image_.width(), image_.height()) {}

EnvironmentMap EnvironmentMap::load(const std::string& path, Color scale) { return EnvironmentMap(read_image(path), scale); }

Vec2 EnvironmentMap::direction_to_uv(const Vec3& w) {
    double theta = std::acos(clamp(w.y, -1.0, 1.0));
    double phi = std::atan2(w.x, -w.z);
    return {0.5 + phi * kInvTwoPi, theta * kInvPi};
}

Vec3 EnvironmentMap::uv_to_direction(Vec2 uv) {
    double phi = (uv.x - 0.5) * kTwoPi, theta = uv.y * kPi;
    double sin_theta = std::sin(theta);
    return {sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)};
}

Color EnvironmentMap::Le(const Vec3& w) const {
    Vec2 uv = direction_to_uv(w);
    int x = std::clamp(int(uv.x * image_.width()), 0, image_.width() - 1);
    int y = std::clamp(int(uv.y * image_.height()), 0, image_.height() - 1);
    return image_.at(x, y);
}

EnvironmentMap::Sample EnvironmentMap::sample(Vec2 u) const {
    Vec2 uv = distribution_.sample_continuous(u, nullptr);
    Sample s;
    s.wi = uv_to_direction(uv);
    s.L = Le(s.wi);
    // The density of the direction as pdf() gives it, so that MIS weights
    // agree exactly even when rounding in uv -> direction -> uv moves a
    // sample on a pixel's edge into its neighbour. At the poles the map is
    // singular; such samples carry no weight (pdf 0).
    s.pdf = pdf(s.wi);
    return s;
}

double EnvironmentMap::pdf(const Vec3& w) const {
    Vec2 uv = direction_to_uv(w);
    double sin_theta = std::sin(uv.y * kPi);
    if (!(sin_theta > 0)) return 0.0;
    return distribution_.pdf(uv) / (2 * kPi * kPi * sin_theta);
}

Color EnvironmentMap::integral() const {
    // A pixel of row y spans theta in [pi y / H, pi (y + 1) / H] and 2 pi / W
    // in phi: solid angle (2 pi / W) (cos theta_top - cos theta_bottom).
    Color sum;
    const int w = image_.width(), h = image_.height();
    for (int y = 0; y < h; ++y) {
        double solid_angle = kTwoPi / w * (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h));
        Color row;
        for (int x = 0; x < w; ++x) row += image_.at(x, y);
        sum += row * solid_angle;
    }
    return sum;
}

Image make_sky_image(int width, int height, double sun_elevation, double sun_azimuth) {
    Image sky(width, height);
    double el = radians(sun_elevation), az = radians(sun_azimuth);
    Vec3 sun(std::cos(el) * std::sin(az), std::sin(el), -std::cos(el) * std::cos(az));
    const double sun_radius = radians(2.5);  // larger than the real sun (0.27 deg) so tiny maps resolve it
    const Color zenith(0.18, 0.35, 0.85), horizon(0.85, 0.9, 1.0), ground(0.12, 0.1, 0.08), sun_color(60, 52, 40);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            Vec3 w = EnvironmentMap::uv_to_direction({(x + 0.5) / width, (y + 0.5) / height});
            Color c;
            if (w.y >= 0) {
                double t = std::pow(w.y, 0.5);  // a gradient that stays light near the horizon
                c = horizon * (1 - t) + zenith * t;
            } else {
                c = ground;
            }
            if (std::acos(clamp(dot(w, sun), -1.0, 1.0)) < sun_radius) c = sun_color;
            sky.set(x, y, c);
        }
    return sky;
}

}  // namespace pt
