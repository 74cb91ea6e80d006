#include "scene/microfacet_distribution.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math.h"
#include "scene/microfacet.h"

namespace pt {
namespace {

/// The regularised incomplete beta function I_x(a, b), by its continued
/// fraction evaluated with the modified Lentz method (Abramowitz and Stegun
/// 26.5.8; Numerical Recipes section 6.4), where it converges quickly.
double beta_fraction(double a, double b, double x) {
    const double tiny = 1e-300;
    double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
    if (std::fabs(d) < tiny) d = tiny;
    d = 1.0 / d;
    double h = d;
    for (int m = 1; m < 300; ++m) {
        double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((a - 1.0 + m2) * (a + m2));
        d = 1.0 + aa * d;
        d = std::fabs(d) < tiny ? 1.0 / tiny : 1.0 / d;
        c = 1.0 + aa / c;
        if (std::fabs(c) < tiny) c = tiny;
        h *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + 1.0 + m2));
        d = 1.0 + aa * d;
        d = std::fabs(d) < tiny ? 1.0 / tiny : 1.0 / d;
        c = 1.0 + aa / c;
        if (std::fabs(c) < tiny) c = tiny;
        double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-15) break;
    }
    return h;
}
double incomplete_beta(double a, double b, double x) {
    if (x <= 0) return 0.0;
    if (x >= 1) return 1.0;
    double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
    if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_fraction(a, b, x) / a;
    return 1.0 - front * beta_fraction(b, a, 1.0 - x) / b;
}

/// Smith's Lambda of the Blinn-Phong distribution, exactly. Its facet slopes
/// s have the density (e + 2) / (2 pi) (1 + |s|^2)^(-(e + 4) / 2), whose
/// one-dimensional marginal P2(q) = C (1 + q^2)^(-(e + 3) / 2) with
/// C = (e + 2) / (2 sqrt(pi)) Gamma((e + 3) / 2) / Gamma((e + 4) / 2); Smith's
/// Lambda(mu) = integral over q > mu of (q - mu) P2(q) dq / mu, mu = cot theta,
/// works out to
///     C sin^(e+1)(theta) tan(theta) / (e + 1) - I_{sin^2 theta}((e + 2) / 2, 1/2) / 2.
/// (Walter et al. 2007 use Beckmann's Lambda instead, which gains up to 30%
/// of energy at grazing angles for exponents below 2.)
double blinn_phong_lambda(double exponent, double cos_theta) {
    double cos2 = cos_theta * cos_theta, sin2 = std::max(0.0, 1.0 - cos2);
    if (sin2 <= 0) return 0.0;
    double e = exponent;
    double log_c = std::log((e + 2.0) / (2.0 * std::sqrt(kPi))) + std::lgamma(0.5 * (e + 3.0)) - std::lgamma(0.5 * (e + 4.0));
    double tan_theta = std::sqrt(sin2 / cos2);
    double first = std::exp(log_c + 0.5 * (e + 1.0) * std::log(sin2)) * tan_theta / (e + 1.0);
    return std::max(0.0, first - 0.5 * incomplete_beta(0.5 * (e + 2.0), 0.5, sin2));
}

}  // namespace

const char* to_string(MicrofacetModel model) {
    switch (model) {
        case MicrofacetModel::ggx: return "ggx";
        case MicrofacetModel::beckmann: return "beckmann";
        case MicrofacetModel::blinn_phong: return "blinn_phong";
    }
    return "?";
}

MicrofacetDistribution::MicrofacetDistribution(MicrofacetModel model, double alpha_x, double alpha_y)
    : MicrofacetDistribution(model, std::max(alpha_x, ggx::kMinAlpha), std::max(alpha_y, ggx::kMinAlpha), 0.0) {}

MicrofacetDistribution::MicrofacetDistribution(MicrofacetModel model, double alpha_x, double alpha_y, double exponent)
    : model_(model), alpha_x_(alpha_x), alpha_y_(alpha_y), exponent_(exponent) {}

MicrofacetDistribution MicrofacetDistribution::blinn_phong(double exponent) {
    exponent = std::max(exponent, 0.0);
    double alpha = std::sqrt(2.0 / (exponent + 2.0));  // Walter et al. 2007, eq. 35's matching roughness
    return MicrofacetDistribution(MicrofacetModel::blinn_phong, alpha, alpha, exponent);
}

double MicrofacetDistribution::D(const Vec3& m) const {
    if (m.z <= 0) return 0.0;
    switch (model_) {
        case MicrofacetModel::ggx: {
            if (is_isotropic()) return ggx::D(m, alpha_x_);
            double t = sqr(m.x / alpha_x_) + sqr(m.y / alpha_y_) + m.z * m.z;
            return 1.0 / (kPi * alpha_x_ * alpha_y_ * t * t);
        }
        case MicrofacetModel::beckmann: {
            double cos2 = m.z * m.z;
            double e = (sqr(m.x / alpha_x_) + sqr(m.y / alpha_y_)) / cos2;  // tan^2 theta (cos^2 phi / ax^2 + ...)
            return std::exp(-e) / (kPi * alpha_x_ * alpha_y_ * cos2 * cos2);
        }
        case MicrofacetModel::blinn_phong:
            return (exponent_ + 2.0) * kInvTwoPi * std::pow(m.z, exponent_);
    }
    return 0.0;
}

double MicrofacetDistribution::lambda(const Vec3& w) const {
    if (model_ == MicrofacetModel::ggx && is_isotropic()) return ggx::lambda(w, alpha_x_);
    double cos2 = w.z * w.z;
    if (cos2 <= 0) return std::numeric_limits<double>::infinity();  // grazing: fully masked
    // alpha(w)^2 tan^2(theta): the roughness in w's azimuth times its slope.
    double a2t2 = (sqr(alpha_x_ * w.x) + sqr(alpha_y_ * w.y)) / cos2;
    if (model_ == MicrofacetModel::ggx) return 0.5 * (std::sqrt(1.0 + a2t2) - 1.0);
    if (model_ == MicrofacetModel::blinn_phong) return blinn_phong_lambda(exponent_, std::fabs(w.z));
    // Beckmann, with a = 1 / (alpha tan theta).
    if (!(a2t2 > 0)) return 0.0;  // straight along the normal: nothing masks it
    double a = 1.0 / std::sqrt(a2t2);
    return 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
}

Vec3 MicrofacetDistribution::sample_normal(const Vec3& wo, Vec2 u) const {
    switch (model_) {
        case MicrofacetModel::ggx:
            // The facets seen from below the surface are those seen from -wo above it.
            return ggx::sample_visible_normal(wo.z >= 0 ? wo : -wo, alpha_x_, alpha_y_, u);
        case MicrofacetModel::beckmann: {
            // D cos(theta) is the Gaussian density of the facet slopes
            // (-m.x / m.z, -m.y / m.z) with deviations ax / sqrt(2), ay / sqrt(2):
            // draw a unit Gaussian slope (Box-Muller), stretch it, turn it into a normal.
            double r = std::sqrt(-std::log(1.0 - u.x)), phi = kTwoPi * u.y;
            double sx = alpha_x_ * r * std::cos(phi), sy = alpha_y_ * r * std::sin(phi);
            return Vec3(-sx, -sy, 1.0).unit();
        }
        case MicrofacetModel::blinn_phong: {
            double cos_theta = std::pow(u.x, 1.0 / (exponent_ + 2.0));
            double sin_theta = safe_sqrt(1.0 - cos_theta * cos_theta), phi = kTwoPi * u.y;
            return Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
        }
    }
    return Vec3(0, 0, 1);
}

double MicrofacetDistribution::normal_pdf(const Vec3& wo, const Vec3& m) const {
    if (model_ != MicrofacetModel::ggx) return D(m) * std::max(m.z, 0.0);
    // Visible normals: only facets on wo's side of their own plane are seen.
    double cos_om = dot(wo, m);
    if (wo.z == 0 || cos_om * wo.z <= 0) return 0.0;
    return G1(wo) * std::fabs(cos_om) * D(m) / std::fabs(wo.z);
}

}  // namespace pt
