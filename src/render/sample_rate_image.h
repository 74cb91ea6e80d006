// The sample-rate image of adaptive sampling (CS184's "rate" image): each
// pixel's sample count divided by the largest count, coloured from blue
// (few samples) through green to red (the most).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"

namespace pt {

/// Colour of rate t in [0, 1]: blue at 0, green at 0.5, red at 1.
Color rate_color(double t);

/// The rate image of per-pixel sample counts (row-major, width * height).
Image make_sample_rate_image(const std::vector<uint32_t>& counts, int width, int height);

/// "out/cbox.png" -> "out/cbox_rate.png".
std::string rate_image_path(const std::string& output_png);

}  // namespace pt
