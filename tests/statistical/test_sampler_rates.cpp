// Convergence rates of the samplers (core/sampler.h) on two pixel
// integrals, measured, not quoted (docs/sampling.md):
//   (a) smooth: f(u, v) = exp(u) (1 + v^2) over the pixel, exactly (e - 1) 4/3;
//   (b) one hard edge: the indicator of a u + b v < c_p, a line at 23.5
//       degrees whose offset c_p differs per pixel, its area exact.
// Each of P pixels of a film is one independent randomisation of the
// sampler; the MSE at N samples per pixel is the mean over the pixels of
// (estimate - exact)^2, and its log-log slope against N (N = 4 ... 256, a
// least-squares fit) is compared with the theory of stages/sampler.h:
//
//   sampler       (a) smooth    (b) edge
//   independent   -1            -1
//   stratified    -2            -1.5      (Mitchell 1996)
//   halton        -2            -1.5      (Koksma-Hlawka, (log N)^2 / N^2)
//   sobol         -3            -1.5      (Owen 1997 for smooth f; an edge is not smooth)
//   zsobol        -3            -1.5
//
// Tolerance 0.15 in the slope, the target of issue 16. The seeds are fixed,
// so the test is deterministic; with P = 4096 pixels the slopes' standard
// deviation over seeds is about 0.02 to 0.04 (docs/sampling.md).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/sampler.h"
#include "stages/sampler.h"

namespace pt {
namespace {

constexpr int kWidth = 64, kHeight = 64;  // P = 4096 pixels

double smooth_integrand(Vec2 u) { return std::exp(u.x) * (1 + u.y * u.y); }
const double kSmoothExact = (std::exp(1.0) - 1) * (4.0 / 3.0);

// The edge a u + b v < c: a = sin(theta), b = cos(theta), theta = 23.5 degrees.
const double kEdgeA = std::sin(0.41015237), kEdgeB = std::cos(0.41015237);
double edge_offset(int pixel) { return 0.15 + 0.9 * std::fmod(pixel * 0.6180339887498949, 1.0); }
/// Area of {(u, v) in [0,1]^2 : a u + b v < c}: v-length min(1, max(0, (c - a u) / b))
/// is piecewise linear in u, so Simpson's rule between its breakpoints is exact.
double edge_area(double c) {
    auto length = [c](double u) { return std::min(1.0, std::max(0.0, (c - kEdgeA * u) / kEdgeB)); };
    std::vector<double> cuts{0, 1, c / kEdgeA, (c - kEdgeB) / kEdgeA};
    std::sort(cuts.begin(), cuts.end());
    double area = 0;
    for (size_t i = 0; i + 1 < cuts.size(); ++i) {
        double lo = std::clamp(cuts[i], 0.0, 1.0), hi = std::clamp(cuts[i + 1], 0.0, 1.0);
        if (hi > lo) area += (hi - lo) * (length(lo) + length(hi)) / 2;
    }
    return area;
}

struct RateFit {
    std::vector<double> mse;  // per N
    double slope = 0;
};

/// MSE of the pixel estimates at N = 4, 8, ..., 256 and its fitted slope.
RateFit measure(SamplerKind kind, bool edge, uint64_t seed) {
    std::vector<int> counts;
    for (int n = 4; n <= 256; n *= 2) counts.push_back(n);
    RateFit fit;
    for (int n : counts) {
        SamplerSettings settings;
        settings.kind = kind;
        settings.seed = seed;
        settings.spp = n;
        settings.width = kWidth, settings.height = kHeight;
        Sampler sampler(settings, {reference::stratified_sample_2d, reference::scrambled_radical_inverse});
        double sum_sq = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const int pixel = y * kWidth + x;
                double c = edge_offset(pixel);
                double sum = 0;
                for (int i = 0; i < n; ++i) {
                    Rng rng = kind == SamplerKind::independent ? Rng(seed, uint64_t(pixel), uint64_t(i))
                                                                : Rng(sampler, uint32_t(x), uint32_t(y), uint64_t(pixel), uint64_t(i));
                    Vec2 u = rng.next_2d();  // dimensions 0 and 1: the point in the pixel
                    sum += edge ? (kEdgeA * u.x + kEdgeB * u.y < c ? 1.0 : 0.0) : smooth_integrand(u);
                }
                double exact = edge ? edge_area(c) : kSmoothExact;
                sum_sq += (sum / n - exact) * (sum / n - exact);
            }
        }
        fit.mse.push_back(sum_sq / (kWidth * kHeight));
    }
    // Least squares of log MSE against log N.
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double k = double(counts.size());
    for (size_t i = 0; i < counts.size(); ++i) {
        double lx = std::log(double(counts[i])), ly = std::log(fit.mse[i]);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    }
    fit.slope = (k * sxy - sx * sy) / (k * sxx - sx * sx);
    return fit;
}

struct Theory {
    SamplerKind kind;
    double smooth, edge;
};
const Theory kTheory[] = {{SamplerKind::independent, -1, -1},
                          {SamplerKind::stratified, -2, -1.5},
                          {SamplerKind::halton, -2, -1.5},
                          {SamplerKind::sobol, -3, -1.5},
                          {SamplerKind::zsobol, -3, -1.5}};

}  // namespace

TEST_CASE("the exact edge area: a quarter of the square at the centre line, 0 and 1 outside") {
    CHECK(edge_area(-0.1) == 0);
    CHECK(edge_area(kEdgeA + kEdgeB + 0.1) == doctest::Approx(1));
    CHECK(edge_area((kEdgeA + kEdgeB) / 2) == doctest::Approx(0.5).epsilon(1e-12));
    // A brute-force count on a fine grid agrees.
    const double c = 0.7;
    int inside = 0, n = 2000;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) inside += kEdgeA * (i + 0.5) / n + kEdgeB * (j + 0.5) / n < c;
    CHECK(edge_area(c) == doctest::Approx(double(inside) / (double(n) * n)).epsilon(1e-3));
}

TEST_CASE("convergence rates of every sampler on a smooth pixel integral and on an edge, within 0.15 of theory") {
    for (const Theory& t : kTheory) {
        for (bool edge : {false, true}) {
            RateFit fit = measure(t.kind, edge, 2026);
            const double theory = edge ? t.edge : t.smooth;
            INFO(std::string(to_string(t.kind)) << std::string(edge ? " edge" : " smooth") << ": slope " << fit.slope << ", theory " << theory
                                   << ", MSE at 4 and 256: " << fit.mse.front() << ", " << fit.mse.back());
            if (std::getenv("PT_RATES_VERBOSE"))
                MESSAGE(std::string(to_string(t.kind)) << std::string(edge ? " edge" : " smooth") << ": slope " << fit.slope);
            CHECK(std::fabs(fit.slope - theory) <= 0.15);
        }
    }
}

}  // namespace pt
