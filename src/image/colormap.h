// False-colour maps for error images (heat maps).
//
// The map is viridis (van der Walt and Smith, matplotlib 2.0, 2015):
// perceptually uniform, readable in grey and by colour-blind readers, dark
// purple for "no error" to yellow for "large error". It is approximated
// here by ten control points taken at equal steps along the map and joined
// linearly in sRGB; between control points the error against the full
// 256-entry table is below two 8-bit levels.
//
// A heat map shows the per-pixel relMSE (image/metrics.h) on a log scale
// from `low` (darkest) to `high` (brightest); values outside are clamped,
// and NaN pixels are drawn magenta so that they are never mistaken for a
// small error.
#pragma once

#include <string>
#include <vector>

#include "core/color.h"
#include "image/image.h"

namespace pt {

/// Viridis at t in [0, 1] (clamped), as sRGB-encoded components in [0, 1].
Color viridis_srgb(double t);

/// The control points of viridis_srgb as "#rrggbb" strings, for CSS
/// gradients that show the same scale in HTML reports.
std::vector<std::string> viridis_hex_stops();

/// How error values map to the colour scale.
struct HeatmapScale {
    double low = 1e-4;  ///< per-pixel relMSE drawn darkest (and everything below)
    double high = 1.0;  ///< per-pixel relMSE drawn brightest (and everything above)
};

/// Position in [0, 1] of `value` on the log scale [low, high]; NaN stays NaN.
double heatmap_position(double value, const HeatmapScale& scale);

/// The heat map of `image` against `reference`, ready for write_png (its
/// values are linear, so that the PNG shows the map's sRGB colours).
/// Throws InputError when the sizes differ.
Image error_heatmap(const Image& image, const Image& reference, const HeatmapScale& scale = {});

}  // namespace pt
