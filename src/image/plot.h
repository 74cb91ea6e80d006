// Log-log line plots drawn on the float image, so that `bench accuracy` can
// write its error-against-time plot as a PNG without gnuplot or any other
// tool (write_png encodes the image as sRGB).
//
// Both axes are logarithmic and span whole decades that enclose every
// point: a grid line and a label at each power of ten ("0.01", "1", "1e-5"),
// lighter lines at 2..9 times each power. One polyline per series in its
// own colour with a square at each point, dashed where asked (reference
// slopes: on log-log axes y = c x^k is a straight line of slope k), and a
// legend to the right of the plot area. Labels use the built-in 5x7 bitmap
// font (image/bitmap_font.h).
#pragma once

#include <string>
#include <vector>

#include "core/color.h"
#include "image/image.h"

namespace pt {

struct PlotSeries {
    std::string label;         ///< legend text; empty: not in the legend
    std::vector<double> x, y;  ///< data points; points with x or y <= 0 or non-finite are skipped
    Color color;               ///< sRGB-encoded components in [0, 1], as a colour picker gives them
    bool dashed = false;       ///< dashed line (reference slopes)
    bool markers = true;       ///< a small square at each point
    bool sets_range = true;    ///< false: clipped to the axes that the other series set
};

struct LogLogPlot {
    std::string title;
    std::string x_label;
    std::string y_label;
    std::vector<PlotSeries> series;
    int width = 800;     ///< pixels
    int height = 520;    ///< pixels
    int text_scale = 2;  ///< font pixels per bitmap pixel
};

/// Colour i (cycling) of the 8-colour palette of Okabe and Ito (2008),
/// distinguishable by colour-blind readers; sRGB-encoded.
Color plot_color(size_t i);

/// The dashed line y = y0 (x / x0)^exponent from x_min to x_max: on log-log
/// axes a straight line of slope `exponent` through (x0, y0). It does not
/// widen the axes.
PlotSeries power_law_series(const std::string& label, double x0, double y0, double exponent,
                            double x_min, double x_max, Color color);

/// Powers of ten 10^lo < 10^hi that enclose every positive finite value
/// (lo < hi always; {0, 1} when there is none).
struct DecadeRange {
    int lo = 0, hi = 1;
};
DecadeRange decade_range(const std::vector<double>& values);

/// The label of 10^k: "0.001" to "1000" written out, "1e-5" and "1e+4" beyond.
std::string decade_label(int k);

/// Draws the plot on a white image of plot.width x plot.height pixels.
Image render_log_log_plot(const LogLogPlot& plot);

}  // namespace pt
