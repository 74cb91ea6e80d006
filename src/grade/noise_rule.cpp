#include "grade/noise_rule.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "image/metrics.h"

namespace pt {

NoiseVerdict apply_noise_rule(const NoiseInputs& in, const NoiseRule& rule) {
    const Image& converged = in.converged;
    const Image& student = in.student_bias;
    if (in.runs.empty())
        throw InputError("noise rule: no reference renders at the student's sample count");
    require_same_size(in.student, converged, "student and reference images");
    require_same_size(in.student_bias, converged, "student and reference images");
    require_same_size(in.sample_variance, converged, "reference variance and converged images");
    for (const Image& q : in.runs)
        require_same_size(q, converged, "reference renders");
    if (in.bias_counts && in.bias_counts->size() != size_t(converged.width()) * converged.height())
        throw InputError("noise rule: sample counts of another size than the images");
    auto variance_scale = [&](int x, int y) {
        double m = in.bias_counts ? double((*in.bias_counts)[size_t(y) * converged.width() + x])
                                  : double(in.bias_spp);
        return 1.0 / std::max(m, 1.0) + 1.0 / std::max(in.converged_spp, 1);
    };
    // Rare events: a pixel that a sliver of geometry covers with probability
    // p < 1/N may show no spread in the reference at all, and the student's
    // render may still catch the sliver. When the image is noisy, each
    // pixel's variance is at least that of an event of probability 3/N (the
    // 95% bound when none was seen in N samples) whose size is the local
    // contrast: the largest difference from a neighbour in the converged image.
    const std::vector<float>& s2 = in.sample_variance.data();
    const bool noisy = std::any_of(s2.begin(), s2.end(), [](float x) { return x > 0; });
    const double rare = 3.0 / std::max(in.converged_spp, 1);
    auto pixel_variance = [&](int x, int y, int c) {
        double var = in.sample_variance.at(x, y)[c];
        if (!noisy) return var;
        double r = converged.at(x, y)[c], contrast = 0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (x + dx >= 0 && y + dy >= 0 && x + dx < converged.width() &&
                    y + dy < converged.height())
                    contrast = std::max(contrast, std::fabs(converged.at(x + dx, y + dy)[c] - r));
        return std::max(var, contrast * contrast * rare);
    };
    NoiseVerdict v;

    // 1. The error ratio.
    v.student_relmse = relmse(in.student, converged);
    for (const Image& q : in.runs)
        v.reference_relmse += relmse(q, converged);
    v.reference_relmse /= double(in.runs.size());
    v.relmse_limit = rule.k * v.reference_relmse + rule.floor;
    v.ratio_ok = v.student_relmse <= v.relmse_limit;  // false for NaN

    // 2. The tile z-test.
    const int w = converged.width(), h = converged.height(), t = std::max(1, rule.tile);
    const int tiles_x = (w + t - 1) / t, tiles_y = (h + t - 1) / t;
    v.tests = tiles_x * tiles_y * 3;
    v.sidak_alpha = -std::expm1(std::log1p(-rule.alpha) / v.tests);
    for (int ty = 0; ty < tiles_y; ++ty) {
        for (int tx = 0; tx < tiles_x; ++tx) {
            int x0 = tx * t, y0 = ty * t, x1 = std::min(x0 + t, w), y1 = std::min(y0 + t, h);
            double count = double(x1 - x0) * (y1 - y0);
            for (int c = 0; c < 3; ++c) {
                double diff = 0, var = 0, level = 0;
                for (int y = y0; y < y1; ++y) {
                    for (int x = x0; x < x1; ++x) {
                        double r = converged.at(x, y)[c];
                        diff += student.at(x, y)[c] - r;
                        level += std::fabs(r);
                        var += pixel_variance(x, y, c) * variance_scale(x, y);
                    }
                }
                double tau = rule.tau_rel * (level / count + 0.01);
                double z = (diff / count) / std::sqrt(var / (count * count) + tau * tau);
                double p = std::isnan(z) ? 0.0 : std::erfc(std::fabs(z) / std::sqrt(2.0));
                if (p < v.sidak_alpha) ++v.tiles_failed;
                double abs_z = std::isnan(z) ? INFINITY : std::fabs(z);
                if (abs_z > v.worst_z) {
                    v.worst_z = abs_z;
                    v.worst_p = p;
                    v.worst_tile_x = x0;
                    v.worst_tile_y = y0;
                    v.worst_channel = c;
                }
            }
        }
    }
    v.z_ok = v.tiles_failed == 0;
    v.pass = v.ratio_ok && v.z_ok;

    char buf[512];
    const char* channel = v.worst_channel == 0 ? "red" : (v.worst_channel == 1 ? "green" : "blue");
    std::snprintf(buf, sizeof buf,
                  "relMSE %.4g %s %.4g (%.3g x the reference's %.4g + %.3g); %d of %d tile tests "
                  "below the Sidak "
                  "level %.3g (worst |z| %.3g, p %.3g, %s, tile at %d,%d)",
                  v.student_relmse, v.ratio_ok ? "<=" : ">", v.relmse_limit, rule.k,
                  v.reference_relmse, rule.floor, v.tiles_failed, v.tests, v.sidak_alpha, v.worst_z,
                  v.worst_p, channel, v.worst_tile_x, v.worst_tile_y);
    v.message = buf;
    return v;
}

}  // namespace pt
