#include "image/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "image/bitmap_font.h"
#include "image/tonemap.h"

namespace pt {
namespace {

const Color kWhite(1.0), kBlack(0.0);
const Color kMajorGrid(0.62), kMinorGrid(0.84);  // linear greys (sRGB about 205 and 237)

/// An sRGB-encoded colour as the linear value the image stores.
Color linear(const Color& srgb) {
    return Color(srgb_decode(srgb.r), srgb_decode(srgb.g), srgb_decode(srgb.b));
}

bool usable(double x, double y) {
    return x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y);
}

/// The plot area in pixels (right and bottom inclusive) and the decades it shows.
struct Axes {
    int left = 0, top = 0, right = 0, bottom = 0;
    DecadeRange xr, yr;

    double px(double x) const {
        return left + (std::log10(x) - xr.lo) / (xr.hi - xr.lo) * (right - left);
    }
    double py(double y) const {
        return bottom - (std::log10(y) - yr.lo) / (yr.hi - yr.lo) * (bottom - top);
    }
};

/// Pixel drawing, clipped to a rectangle.
struct Canvas {
    Image& image;
    int x0, y0, x1, y1;  ///< the clip rectangle, inclusive

    void put(int x, int y, const Color& c) {
        if (x >= x0 && x <= x1 && y >= y0 && y <= y1) image.set(x, y, c);
    }
    /// A filled square of `size` pixels centred on (x, y).
    void square(double x, double y, int size, const Color& c) {
        const int sx = int(std::lround(x - 0.5 * (size - 1))),
                  sy = int(std::lround(y - 0.5 * (size - 1)));
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i)
                put(sx + i, sy + j, c);
    }
    /// A line of the given thickness. Dashed lines are 10 pixels on, 6 off,
    /// counted along the whole polyline through `travelled`.
    void line(double ax, double ay, double bx, double by, int thickness, const Color& c,
              bool dashed, double& travelled) {
        const double length = std::hypot(bx - ax, by - ay);
        const int steps = std::max(1, int(std::ceil(length * 2)));  // half-pixel steps
        for (int k = 0; k <= steps; ++k) {
            const double t = double(k) / steps;
            const double along = travelled + t * length;
            if (dashed && std::fmod(along, 16.0) >= 10.0) continue;
            square(ax + t * (bx - ax), ay + t * (by - ay), thickness, c);
        }
        travelled += length;
    }
};

void draw_series(Canvas& canvas, const Axes& axes, const PlotSeries& s) {
    const Color c = linear(s.color);
    double travelled = 0;
    bool have_previous = false;
    double px = 0, py = 0;
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (!usable(s.x[i], s.y[i])) {
            have_previous = false;  // a gap in the line
            continue;
        }
        const double x = axes.px(s.x[i]), y = axes.py(s.y[i]);
        if (have_previous) canvas.line(px, py, x, y, 2, c, s.dashed, travelled);
        px = x, py = y, have_previous = true;
    }
    if (!s.markers) return;
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
        if (usable(s.x[i], s.y[i])) canvas.square(axes.px(s.x[i]), axes.py(s.y[i]), 6, c);
}

/// Grid lines at 2..9 times every power of ten, then darker ones at the
/// powers themselves (drawn last, so that they stay on top).
void draw_grid(Canvas& canvas, const Axes& axes) {
    for (int m : {2, 3, 4, 5, 6, 7, 8, 9, 1}) {
        const Color c = m == 1 ? kMajorGrid : kMinorGrid;
        for (int k = axes.xr.lo; k < axes.xr.hi; ++k) {
            const int x = int(std::lround(axes.px(m * std::pow(10.0, k))));
            for (int y = axes.top; y <= axes.bottom; ++y)
                canvas.put(x, y, c);
        }
        for (int k = axes.yr.lo; k < axes.yr.hi; ++k) {
            const int y = int(std::lround(axes.py(m * std::pow(10.0, k))));
            for (int x = axes.left; x <= axes.right; ++x)
                canvas.put(x, y, c);
        }
    }
}

void draw_frame(Canvas& canvas, const Axes& a) {
    for (int x = a.left; x <= a.right; ++x)
        canvas.put(x, a.top, kBlack), canvas.put(x, a.bottom, kBlack);
    for (int y = a.top; y <= a.bottom; ++y)
        canvas.put(a.left, y, kBlack), canvas.put(a.right, y, kBlack);
}

}  // namespace

Color plot_color(size_t i) {
    // Okabe and Ito, "Color Universal Design" (2008), without its yellow,
    // which is unreadable on white; black last.
    static const Color palette[] = {
        {0.000, 0.447, 0.698},  // blue
        {0.835, 0.369, 0.000},  // vermillion
        {0.000, 0.620, 0.451},  // bluish green
        {0.800, 0.475, 0.655},  // reddish purple
        {0.902, 0.624, 0.000},  // orange
        {0.337, 0.706, 0.914},  // sky blue
        {0.500, 0.500, 0.500},  // grey
        {0.000, 0.000, 0.000},  // black
    };
    return palette[i % (sizeof palette / sizeof palette[0])];
}

PlotSeries power_law_series(const std::string& label, double x0, double y0, double exponent,
                            double x_min, double x_max, Color color) {
    PlotSeries s;
    s.label = label;
    s.color = color;
    s.dashed = true;
    s.markers = false;
    s.sets_range = false;
    for (double x : {x_min, x_max}) {
        s.x.push_back(x);
        s.y.push_back(y0 * std::pow(x / x0, exponent));
    }
    return s;
}

DecadeRange decade_range(const std::vector<double>& values) {
    double lo = INFINITY, hi = -INFINITY;
    for (double v : values)
        if (v > 0 && std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (lo > hi) return {};
    DecadeRange r;
    r.lo = int(std::floor(std::log10(lo) + 1e-9));
    r.hi = int(std::ceil(std::log10(hi) - 1e-9));
    if (r.hi <= r.lo) r.hi = r.lo + 1;
    return r;
}

std::string decade_label(int k) {
    if (k >= 0 && k <= 3) return std::to_string(int(std::lround(std::pow(10.0, k))));
    if (k < 0 && k >= -3) return "0." + std::string(size_t(-k - 1), '0') + "1";
    char buf[16];
    std::snprintf(buf, sizeof buf, "1e%+d", k);
    return buf;
}

Image render_log_log_plot(const LogLogPlot& plot) {
    Image image(plot.width, plot.height);
    for (float& v : image.data())
        v = 1.0f;
    const int s = plot.text_scale, line = kLineHeight * s;

    // The axes' decades, from the series that set them.
    std::vector<double> xs, ys;
    for (const PlotSeries& series : plot.series)
        if (series.sets_range)
            for (size_t i = 0; i < series.x.size() && i < series.y.size(); ++i)
                if (usable(series.x[i], series.y[i]))
                    xs.push_back(series.x[i]), ys.push_back(series.y[i]);
    Axes axes;
    axes.xr = decade_range(xs);
    axes.yr = decade_range(ys);

    // Layout: title on top, y label and tick labels on the left, x tick
    // labels and x label below, the legend on the right.
    int tick_label_width = 0, legend_width = 0;
    for (int k = axes.yr.lo; k <= axes.yr.hi; ++k)
        tick_label_width = std::max(tick_label_width, text_width(decade_label(k), s));
    for (const PlotSeries& series : plot.series)
        if (!series.label.empty())
            legend_width = std::max(legend_width, 18 * s + text_width(series.label, s));
    axes.top = plot.title.empty() ? 12 : 12 + line + 8;
    axes.left = 8 + line + 6 + tick_label_width + 8;
    axes.bottom = plot.height - 1 - (10 + line + 4 + line + 6);
    axes.right = plot.width - 1 - (legend_width > 0 ? legend_width + 16 * s : 24);
    Canvas whole{image, 0, 0, plot.width - 1, plot.height - 1};
    Canvas area{image, axes.left, axes.top, axes.right, axes.bottom};

    draw_grid(area, axes);
    for (const PlotSeries& series : plot.series)
        draw_series(area, axes, series);
    draw_frame(whole, axes);

    // Tick labels at the powers of ten.
    for (int k = axes.xr.lo; k <= axes.xr.hi; ++k) {
        const std::string label = decade_label(k);
        const int x = int(std::lround(axes.px(std::pow(10.0, k))));
        draw_text(image, x - text_width(label, s) / 2, axes.bottom + 10, label, kBlack, s);
    }
    for (int k = axes.yr.lo; k <= axes.yr.hi; ++k) {
        const std::string label = decade_label(k);
        const int y = int(std::lround(axes.py(std::pow(10.0, k))));
        draw_text(image, axes.left - 8 - text_width(label, s), y - kGlyphHeight * s / 2, label,
                  kBlack, s);
    }
    // Axis labels and title, centred on the plot area.
    const int mid_x = (axes.left + axes.right) / 2, mid_y = (axes.top + axes.bottom) / 2;
    draw_text(image, mid_x - text_width(plot.x_label, s) / 2, axes.bottom + 10 + line + 4,
              plot.x_label, kBlack, s);
    draw_text_up(image, 8, mid_y + text_width(plot.y_label, s) / 2, plot.y_label, kBlack, s);
    draw_text(image, (plot.width - text_width(plot.title, s)) / 2, 12, plot.title, kBlack, s);

    // The legend: a stretch of each line with its marker, then the label.
    int y = axes.top + 4;
    for (const PlotSeries& series : plot.series) {
        if (series.label.empty()) continue;
        const Color c = linear(series.color);
        const int x = axes.right + 10 * s, mid = y + kGlyphHeight * s / 2;
        double travelled = 0;
        whole.line(x, mid, x + 14 * s, mid, 2, c, series.dashed, travelled);
        if (series.markers) whole.square(x + 7 * s, mid, 6, c);
        draw_text(image, x + 18 * s, y, series.label, kBlack, s);
        y += line + 4;
    }
    return image;
}

}  // namespace pt
