// The bitmap font and the log-log plots of image/bitmap_font.h and
// image/plot.h (bench accuracy's error-against-time plot).
#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <string>

#include "image/bitmap_font.h"
#include "image/plot.h"
#include "image/tonemap.h"

using namespace pt;

namespace {

/// The glyph of `c` as a string of 35 '0'/'1', to compare glyphs.
std::string bits_of(char c) {
    std::string bits;
    for (int row = 0; row < kGlyphHeight; ++row)
        for (int column = 0; column < kGlyphWidth; ++column)
            bits += glyph_pixel(c, column, row) ? '1' : '0';
    return bits;
}

/// Pixels of `image` within 1e-6 of `color` (linear).
int count_color(const Image& image, const Color& color) {
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            Color c = image.at(x, y);
            n += std::fabs(c.r - color.r) < 1e-6 && std::fabs(c.g - color.g) < 1e-6 &&
                 std::fabs(c.b - color.b) < 1e-6;
        }
    return n;
}

Color linear(const Color& srgb) {
    return Color(float(srgb_decode(srgb.r)), float(srgb_decode(srgb.g)),
                 float(srgb_decode(srgb.b)));
}

}  // namespace

TEST_CASE("every printable ASCII character has its own glyph") {
    std::set<std::string> seen;
    for (char c = 32; c < 127; ++c) {
        CAPTURE(c);
        CHECK(has_glyph(c));
        const std::string bits = bits_of(c);
        CHECK((c == ' ') == (bits.find('1') == std::string::npos));  // only space is empty
        CHECK(seen.insert(bits).second);                             // no two glyphs alike
    }
    CHECK_FALSE(has_glyph('\t'));
    CHECK_FALSE(glyph_pixel('A', 5, 0));
    CHECK_FALSE(glyph_pixel('A', 0, 7));
}

TEST_CASE("text is measured and drawn inside its cells") {
    CHECK(text_width("", 1) == 0);
    CHECK(text_width("a", 1) == kGlyphWidth);
    CHECK(text_width("ab", 1) == kCharAdvance + kGlyphWidth);
    CHECK(text_width("ab", 3) == 3 * (kCharAdvance + kGlyphWidth));
    Image image(40, 30);
    draw_text(image, 2, 3, "Ty", Color(1.0), 2);
    int set = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (image.at(x, y).r > 0) {
                ++set;
                CHECK(x >= 2);
                CHECK(x < 2 + text_width("Ty", 2));
                CHECK(y >= 3);
                CHECK(y < 3 + kLineHeight * 2);  // y descends below the capitals, within the line
            }
    CHECK(set > 0);
    draw_text(image, -100, -100, "clipped", Color(1.0), 1);  // off the image: no crash
}

TEST_CASE("decades enclose the data and are labelled") {
    CHECK(decade_range({0.03, 2.0}).lo == -2);
    CHECK(decade_range({0.03, 2.0}).hi == 1);
    CHECK(decade_range({1.0, 10.0}).lo == 0);
    CHECK(decade_range({1.0, 10.0}).hi == 1);
    CHECK(decade_range({5.0}).hi == 1);
    CHECK(decade_range({}).lo == 0);
    CHECK(decade_range({-1.0, 0.0, NAN}).hi == 1);  // nothing positive
    CHECK(decade_label(-3) == "0.001");
    CHECK(decade_label(0) == "1");
    CHECK(decade_label(3) == "1000");
    CHECK(decade_label(-4) == "1e-4");
    CHECK(decade_label(5) == "1e+5");
}

TEST_CASE("a plot draws each series in its colour, dashed reference lines included") {
    LogLogPlot plot;
    plot.title = "error against time";
    plot.x_label = "seconds";
    plot.y_label = "sqrt(relMSE)";
    PlotSeries data;
    data.label = "light";
    data.color = plot_color(0);
    for (double t : {0.01, 0.1, 1.0, 10.0}) {
        data.x.push_back(t);
        data.y.push_back(0.1 / std::sqrt(t));
    }
    data.x.push_back(-1.0);  // skipped
    data.y.push_back(1.0);
    plot.series.push_back(data);
    plot.series.push_back(power_law_series("1/sqrt(time)", 1, 0.3, -0.5, 1e-6, 1e6, plot_color(1)));
    const Image image = render_log_log_plot(plot);
    CHECK(image.width() == plot.width);
    CHECK(image.height() == plot.height);
    CHECK(image.at(0, 0) == Color(1.0f));  // white background
    CHECK(count_color(image, linear(plot_color(0))) > 300);
    const int dashed = count_color(image, linear(plot_color(1)));
    // The same reference line drawn solid: dashes are 10 pixels on, 6 off.
    plot.series.back().dashed = false;
    const int solid = count_color(render_log_log_plot(plot), linear(plot_color(1)));
    CHECK(solid > 300);
    CHECK(dashed > 0.5 * solid);
    CHECK(dashed < 0.75 * solid);
    // The palette's colours are distinct.
    std::set<std::string> colours;
    for (size_t i = 0; i < 8; ++i) {
        Color c = plot_color(i);
        colours.insert(std::to_string(c.r) + std::to_string(c.g) + std::to_string(c.b));
    }
    CHECK(colours.size() == 8);
}
