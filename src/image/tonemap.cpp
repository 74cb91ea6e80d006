#include "image/tonemap.h"

#include <array>
#include <cmath>

namespace pt {

double srgb_encode(double v) {
    if (!(v > 0.0)) return 0.0;  // also maps NaN to 0
    if (v >= 1.0) return 1.0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double e) {
    if (!(e > 0.0)) return 0.0;
    if (e >= 1.0) return 1.0;
    return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

uint8_t to_srgb8(double linear) {
    return static_cast<uint8_t>(std::lround(srgb_encode(linear) * 255.0));
}

double from_srgb8(uint8_t code) {
    static const std::array<double, 256> table = [] {
        std::array<double, 256> t{};
        for (int i = 0; i < 256; ++i) t[i] = srgb_decode(i / 255.0);
        return t;
    }();
    return table[code];
}

}  // namespace pt
