// Display encoding: linear radiance to 8-bit sRGB and back.
//
// PNG output clamps each linear component to [0, 1] (no exposure, no tone
// curve, as CS184 does) and applies the sRGB transfer function of
// IEC 61966-2-1:
//     v <= 0.0031308 ? 12.92 v : 1.055 v^(1/2.4) - 0.055
// then rounds to the nearest of 256 levels. Reading a PNG inverts it, so a
// PNG round trip is exact to within half a quantisation step.
#pragma once

#include <cstdint>

namespace pt {

/// Linear [0, 1] to sRGB-encoded [0, 1] (clamps first; NaN maps to 0).
double srgb_encode(double linear);
/// sRGB-encoded [0, 1] to linear.
double srgb_decode(double encoded);
/// Linear value to the nearest 8-bit sRGB code.
uint8_t to_srgb8(double linear);
/// 8-bit sRGB code to linear value (table lookup).
double from_srgb8(uint8_t code);

}  // namespace pt
