// Chi-square goodness-of-fit tests for sampling routines, in the style of
// Nori's warptest (Jakob): draw many samples, count them in cells of equal
// measure, compare with the counts the routine's pdf predicts (integrated
// numerically over each cell), and reject when Pearson's statistic is
// improbably large.
//
//   - cells expecting fewer than 5 samples are pooled into one (Cochran's
//     rule for the chi-square approximation to hold);
//   - a sample in a cell where the pdf integrates to 0, or outside the
//     domain, or not finite, fails the test outright (the pdf says it
//     cannot happen);
//   - the p-value is the upper tail of the chi-square distribution with
//     (cells - 1) degrees of freedom: Q(dof / 2, statistic / 2), the
//     regularised upper incomplete gamma function, computed below by its
//     power series or its continued fraction (Abramowitz and Stegun 6.5.29
//     and 6.5.31; evaluated with the modified Lentz method);
//   - the whole suite runs kChiSquareTestCount tests at family-wise
//     significance 0.01, so each test uses the Sidak-corrected level
//     1 - (1 - 0.01)^(1 / kChiSquareTestCount): a correct routine fails any
//     test of the suite with probability 0.01 (for fixed seeds: never, or
//     always; the seeds are fixed so the suite is deterministic).
//
// Part 4 adds the microfacet sample_f (6 tests), the environment map (1)
// and the discrete check of glass's two lobes (2); Part 7 the emission
// sampling of every light kind (10, test_light_emission.cpp); Part 6 the
// uniformity of four samplers in four places each (16,
// test_sampler_uniformity.cpp); the glossy models (14,
// test_glossy_sampling.cpp); Part 9 the phase function and free-flight
// distances (6, test_media_sampling.cpp): 70 in all. Add a test, raise
// kChiSquareTestCount.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/math.h"
#include "core/rng.h"
#include "core/vec3.h"

namespace pt::stats {

/// Every chi-square test in tests/statistical (one per TEST_CASE or
/// SUBCASE that calls chi2_test); the Sidak correction divides the family
/// significance among them. Keep it in sync when adding tests.
constexpr int kChiSquareTestCount = 70;
constexpr double kFamilySignificance = 0.01;

/// Per-test significance that keeps the family-wise error rate at `alpha`
/// over `tests` independent tests (Sidak 1967).
inline double sidak_significance(double alpha, int tests) {
    return 1.0 - std::pow(1.0 - alpha, 1.0 / tests);
}
inline double per_test_significance() {
    return sidak_significance(kFamilySignificance, kChiSquareTestCount);
}

/// Regularised incomplete gamma functions P(a, x) (lower) and Q(a, x) =
/// 1 - P(a, x) (upper), a > 0, x >= 0. The power series converges quickly
/// for x < a + 1 and the continued fraction for x >= a + 1; each is used
/// where it converges, and the other function follows by 1 - value.
inline double gamma_series_p(double a, double x) {
    // P(a, x) = e^-x x^a / Gamma(a + 1) * sum_n x^n / ((a + 1) ... (a + n))
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000; ++n) {
        term *= x / (a + n);
        sum += term;
        if (std::fabs(term) < std::fabs(sum) * 1e-16) break;
    }
    return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}
inline double gamma_fraction_q(double a, double x) {
    // Q(a, x) = e^-x x^a / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - 2 (2 - a) / ...)),
    // evaluated front to back with the modified Lentz method.
    const double tiny = 1e-300;
    double b = x + 1.0 - a;
    double c = 1.0 / tiny;
    double d = 1.0 / b;
    double h = d;
    for (int i = 1; i < 100000; ++i) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-16) break;
    }
    return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}
inline double gamma_p(double a, double x) {
    if (x <= 0) return 0.0;
    return x < a + 1.0 ? gamma_series_p(a, x) : 1.0 - gamma_fraction_q(a, x);
}
inline double gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    return x < a + 1.0 ? 1.0 - gamma_series_p(a, x) : gamma_fraction_q(a, x);
}

/// Probability that a chi-square variable with `dof` degrees of freedom is >= statistic.
inline double chi2_p_value(double statistic, int dof) {
    return gamma_q(0.5 * dof, 0.5 * statistic);
}

struct Chi2Result {
    bool passed = false;
    double statistic = 0;
    int dof = 0;
    double p_value = 0;
    double significance = 0;
    std::string message;  ///< why it failed, or a summary
};

/// Pearson's test of observed against expected counts per cell. Cells
/// expecting fewer than `min_expected` samples are pooled into one cell
/// (merged into the smallest regular cell if the pool itself is still
/// below `min_expected`). A count in a cell expecting 0 fails.
inline Chi2Result chi2_test(const std::vector<double>& observed,
                            const std::vector<double>& expected, double significance,
                            double min_expected = 5.0) {
    Chi2Result r;
    r.significance = significance;
    std::vector<size_t> order(expected.size());
    for (size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return expected[a] < expected[b]; });

    double pool_observed = 0, pool_expected = 0;
    std::vector<std::pair<double, double>> cells;  // (observed, expected) after pooling
    for (size_t i : order) {
        if (!(expected[i] > 0)) {
            if (observed[i] > 0) {
                std::ostringstream s;
                s << observed[i] << " samples in cell " << i << ", where the pdf is 0";
                r.message = s.str();
                return r;
            }
            continue;
        }
        if (expected[i] < min_expected) {
            pool_observed += observed[i];
            pool_expected += expected[i];
        } else {
            cells.push_back({observed[i], expected[i]});
        }
    }
    if (pool_expected > 0) {
        if (pool_expected < min_expected && !cells.empty()) {
            cells.front().first += pool_observed;  // the smallest regular cell (sorted order)
            cells.front().second += pool_expected;
        } else {
            cells.push_back({pool_observed, pool_expected});
        }
    }
    if (cells.size() < 2) {
        r.message = "fewer than 2 cells after pooling: the test has no power";
        return r;
    }
    for (const auto& [o, e] : cells)
        r.statistic += (o - e) * (o - e) / e;
    r.dof = int(cells.size()) - 1;
    r.p_value = chi2_p_value(r.statistic, r.dof);
    r.passed = r.p_value >= significance;
    std::ostringstream s;
    s << "chi2 = " << r.statistic << ", dof = " << r.dof << ", p = " << r.p_value
      << (r.passed ? " >= " : " < ") << "significance " << significance;
    r.message = s.str();
    return r;
}

/// Directions binned on a (z = cos theta, phi) grid about frame.n: every
/// cell has the same solid angle, since d(omega) = dz dphi (Archimedes).
/// Only z in [z_min, 1] is covered: a direction below z_min is outside.
struct DirectionGrid {
    Frame frame;        ///< cells are laid out about frame.n
    int nz = 40;        ///< cells in z
    int nphi = 80;      ///< cells in phi
    double z_min = -1;  ///< lowest z covered

    int cells() const { return nz * nphi; }
    /// The cell of the unit world direction w, or -1 (outside, not unit, not finite).
    int cell(const Vec3& w) const {
        if (!w.is_finite() || std::fabs(w.norm() - 1.0) > 1e-9) return -1;
        Vec3 l = frame.to_local(w);
        // Rounding in the frame change may put a direction on the edge a
        // hair below z_min; more than 1e-9 below is a real escape.
        if (l.z < z_min - 1e-9) return -1;
        int iz = std::clamp(int((l.z - z_min) / (1.0 - z_min) * nz), 0, nz - 1);
        double phi = std::atan2(l.y, l.x);
        if (phi < 0) phi += kTwoPi;
        int ip = std::clamp(int(phi / kTwoPi * nphi), 0, nphi - 1);
        return iz * nphi + ip;
    }
    /// integral over cell c of pdf(w) d(omega), by Gauss-Legendre in (z, phi);
    /// pdf takes a unit world direction.
    template <class Pdf>
    double integrate(int c, Pdf pdf) const {
        int iz = c / nphi, ip = c % nphi;
        double dz = (1.0 - z_min) / nz, dphi = kTwoPi / nphi;
        double z0 = z_min + iz * dz, phi0 = ip * dphi;
        return gauss_2d(z0, z0 + dz, phi0, phi0 + dphi, [&](double z, double phi) {
            double s = safe_sqrt(1.0 - z * z);
            return pdf(frame.to_world(Vec3(s * std::cos(phi), s * std::sin(phi), z)));
        });
    }

    /// 5 x 5-point Gauss-Legendre rule over [x0, x1] x [y0, y1]: exact for
    /// polynomials of degree 9 in each variable, and it never evaluates f on
    /// the cell's edges, where a pdf may step (the hemisphere at z = 0).
    template <class F>
    static double gauss_2d(double x0, double x1, double y0, double y1, F f) {
        static const double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                       0.5384693101056831, 0.9061798459386640};
        static const double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                         0.4786286704993665, 0.2369268850561891};
        double cx = 0.5 * (x0 + x1), hx = 0.5 * (x1 - x0), cy = 0.5 * (y0 + y1),
               hy = 0.5 * (y1 - y0);
        double sum = 0;
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j)
                sum += weight[i] * weight[j] * f(cx + hx * node[i], cy + hy * node[j]);
        return sum * hx * hy;
    }
};

/// A DirectionGrid whose cells are each integrated as k x k sub-cells: for
/// peaked pdfs (glossy lobes), where one Gauss rule per cell is not exact.
struct SubdividedDirectionGrid {
    DirectionGrid grid;
    int k = 4;

    int cells() const { return grid.cells(); }
    int cell(const Vec3& w) const { return grid.cell(w); }
    template <class Pdf>
    double integrate(int c, Pdf pdf) const {
        int iz = c / grid.nphi, ip = c % grid.nphi;
        double dz = (1.0 - grid.z_min) / grid.nz, dphi = kTwoPi / grid.nphi;
        double z0 = grid.z_min + iz * dz, phi0 = ip * dphi;
        double sum = 0;
        for (int a = 0; a < k; ++a)
            for (int b = 0; b < k; ++b)
                sum += DirectionGrid::gauss_2d(z0 + a * dz / k, z0 + (a + 1) * dz / k, phi0 + b * dphi / k,
                                               phi0 + (b + 1) * dphi / k, [&](double z, double phi) {
                                                   double r = safe_sqrt(1.0 - z * z);
                                                   return pdf(grid.frame.to_world(
                                                       Vec3(r * std::cos(phi), r * std::sin(phi), z)));
                                               });
        return sum;
    }
};

/// Points of the unit disk binned on an (r^2, phi) grid: equal area per cell.
struct DiskGrid {
    int nr = 40, nphi = 80;

    int cells() const { return nr * nphi; }
    int cell(const Vec2& p) const {
        double r2 = p.x * p.x + p.y * p.y;
        if (!std::isfinite(r2) || r2 > 1.0 + 1e-12) return -1;
        int ir = std::clamp(int(r2 * nr), 0, nr - 1);
        double phi = std::atan2(p.y, p.x);
        if (phi < 0) phi += kTwoPi;
        int ip = std::clamp(int(phi / kTwoPi * nphi), 0, nphi - 1);
        return ir * nphi + ip;
    }
    /// integral over cell c of pdf(p) dA, with dA = r dr dphi = d(r^2) dphi / 2.
    template <class Pdf>
    double integrate(int c, Pdf pdf) const {
        int ir = c / nphi, ip = c % nphi;
        double d = 1.0 / nr, dphi = kTwoPi / nphi;
        return 0.5 *
               DirectionGrid::gauss_2d(ir * d, (ir + 1) * d, ip * dphi, (ip + 1) * dphi,
                                       [&](double r2, double phi) {
                                           double r = std::sqrt(r2);
                                           return pdf(Vec2(r * std::cos(phi), r * std::sin(phi)));
                                       });
    }
};

/// Points on a set of world-space triangles, each cut into n^2 congruent
/// sub-triangles (equal area within a triangle): the natural cells for
/// area sampling of triangle lights and of the triangle warp.
struct TriangleGrid {
    struct Tri {
        Vec3 p0, p1, p2;
    };
    std::vector<Tri> triangles;
    int n = 30;  ///< sub-triangles per edge

    /// Cells per triangle: n x n squares of the (b1, b2) plane, two halves each;
    /// the halves outside the triangle expect 0 and stay empty.
    int cells_per_triangle() const { return n * n * 2; }
    int cells() const { return int(triangles.size()) * cells_per_triangle(); }

    /// The cell of point p on triangle k, from barycentrics (b1, b2).
    int cell_of(int k, double b1, double b2) const {
        if (!(b1 >= -1e-9 && b2 >= -1e-9 && b1 + b2 <= 1 + 1e-9)) return -1;
        int i = std::clamp(int(b1 * n), 0, n - 1), j = std::clamp(int(b2 * n), 0, n - 1);
        double f1 = b1 * n - i, f2 = b2 * n - j;
        int upper = f1 + f2 > 1.0 ? 1 : 0;
        if (i + j > n - 1 || (upper && i + j > n - 2)) {  // on the far edge, by rounding
            upper = 0;
            j = n - 1 - i;
        }
        return k * cells_per_triangle() + (i * n + j) * 2 + upper;
    }
    /// The cell of a world point on (within 1e-6 of) one of the triangles, or -1.
    int cell(const Vec3& p) const {
        for (int k = 0; k < int(triangles.size()); ++k) {
            const Tri& t = triangles[size_t(k)];
            Vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0, d = p - t.p0;
            Vec3 ng = cross(e1, e2);
            double area2 = ng.norm2();
            if (std::fabs(dot(d, ng)) > 1e-6 * std::sqrt(area2)) continue;  // off the plane
            // Barycentrics by the ratios of sub-areas (projected on ng).
            double b1 = dot(cross(d, e2), ng) / area2;
            double b2 = dot(cross(e1, d), ng) / area2;
            if (b1 >= -1e-9 && b2 >= -1e-9 && b1 + b2 <= 1 + 1e-9) return cell_of(k, b1, b2);
        }
        return -1;
    }
    /// integral over cell c of pdf(p) dA (pdf per unit world area): centroid
    /// rule on the cell cut into 8^2 sub-triangles.
    template <class Pdf>
    double integrate(int c, Pdf pdf) const {
        int k = c / cells_per_triangle(), r = c % cells_per_triangle();
        int upper = r % 2, ij = r / 2, i = ij / n, j = ij % n;
        if (upper ? i + j > n - 2 : i + j > n - 1) return 0.0;
        const Tri& t = triangles[size_t(k)];
        auto at = [&](double b1, double b2) {
            return t.p0 + (t.p1 - t.p0) * b1 + (t.p2 - t.p0) * b2;
        };
        double a1[3], a2[3];  // barycentric corners of the cell
        if (!upper) {
            a1[0] = i, a2[0] = j, a1[1] = i + 1, a2[1] = j, a1[2] = i, a2[2] = j + 1;
        } else {
            a1[0] = i + 1, a2[0] = j + 1, a1[1] = i, a2[1] = j + 1, a1[2] = i + 1, a2[2] = j;
        }
        const int m = 8;
        double cell_area = 0.5 * cross(t.p1 - t.p0, t.p2 - t.p0).norm() / (n * n);
        double sum = 0;
        // Sub-triangles of the cell in its own barycentrics (s, u), s + u <= 1.
        for (int si = 0; si < m; ++si) {
            for (int ui = 0; ui + si < m; ++ui) {
                for (int half = 0; half < 2; ++half) {
                    if (half && si + ui > m - 2) continue;
                    double s = half ? (si + 2.0 / 3) / m : (si + 1.0 / 3) / m;
                    double u = half ? (ui + 2.0 / 3) / m : (ui + 1.0 / 3) / m;
                    double b1 = (a1[0] + (a1[1] - a1[0]) * s + (a1[2] - a1[0]) * u) / n;
                    double b2 = (a2[0] + (a2[1] - a2[0]) * s + (a2[2] - a2[0]) * u) / n;
                    sum += pdf(at(b1, b2));
                }
            }
        }
        return sum * cell_area / (m * m);
    }
};

/// Runs a chi-square test of a sampling routine: `n` samples from
/// sample(rng) -> std::optional<Point> (nullopt: the routine returned no
/// sample, which fails), binned by grid.cell, against grid.integrate(pdf).
/// Also fails when the pdf does not integrate to 1 over the grid (to 1e-3):
/// a pdf that is wrong by a constant factor would pass the shape test.
///
/// With `may_fail` (a routine that legitimately returns no sample for some
/// u, such as microfacet sampling reflecting below the surface), "no sample"
/// is one more cell, expecting n (1 - integral of the pdf): the pdf then
/// integrates to the probability of a sample, at most 1.
template <class Grid, class SampleFn, class PdfFn>
Chi2Result chi2_sampling_test(const Grid& grid, SampleFn sample, PdfFn pdf, int n, uint64_t seed,
                              bool may_fail = false) {
    std::vector<double> observed(size_t(grid.cells()), 0.0), expected(size_t(grid.cells()), 0.0);
    Rng rng(seed);
    int missing = 0, outside = 0;
    for (int i = 0; i < n; ++i) {
        auto x = sample(rng);
        if (!x) {
            ++missing;
            continue;
        }
        int c = grid.cell(*x);
        if (c < 0) {
            ++outside;
            continue;
        }
        observed[size_t(c)] += 1;
    }
    double total = 0;
    for (int c = 0; c < grid.cells(); ++c) {
        expected[size_t(c)] = n * grid.integrate(c, pdf);
        total += expected[size_t(c)];
    }
    Chi2Result r;
    if (may_fail) {
        if (outside || total / n > 1.0 + 1e-3) {
            std::ostringstream s;
            s << outside << " samples outside the domain; the pdf integrates to " << total / n;
            r.message = s.str();
            return r;
        }
        observed.push_back(missing);
        expected.push_back(std::max(0.0, n - total));
        return chi2_test(observed, expected, per_test_significance());
    }
    if (missing || outside) {
        std::ostringstream s;
        s << missing << " invalid samples and " << outside
          << " samples outside the domain (where the pdf is 0), of " << n;
        r.message = s.str();
        return r;
    }
    if (std::fabs(total / n - 1.0) > 1e-3) {
        std::ostringstream s;
        s << "the pdf integrates to " << total / n << ", not 1, over the domain";
        r.message = s.str();
        return r;
    }
    return chi2_test(observed, expected, per_test_significance());
}

}  // namespace pt::stats
