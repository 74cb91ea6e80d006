// Adaptive sampling (stage `adaptive`, reference): the CS184 interval rule,
// the rare-event guard, unbiased image means, and determinism.
#include <doctest/doctest.h>

#include <cmath>

#include "render_fixture.h"
#include "stages/adaptive.h"

using namespace pt;

namespace {

PixelStatistics sums_of(std::initializer_list<double> xs, int repeat = 1) {
    PixelStatistics s;
    for (int r = 0; r < repeat; ++r)
        for (double x : xs) {
            s.s1 += x;
            s.s2 += x * x;
            s.n++;
        }
    return s;
}

/// CS184's rule without the guard, as a student would write it.
bool textbook_has_converged(const PixelStatistics& s, double tol) {
    double mu = s.s1 / s.n;
    double sigma = std::sqrt(std::max(0.0, (s.s2 - s.s1 * s.s1 / s.n) / (s.n - 1)));
    return 1.96 * sigma / std::sqrt(double(s.n)) <= tol * mu;
}

/// A small bright light seen with probability 1/64: radiance 64 or 0, mean 1.
class RareEventIntegrator final : public Integrator {
public:
    Color Li(const RenderContext&, const Ray&, Rng& rng) const override {
        return Color(rng.next_1d() < 1.0 / 64 ? 64.0 : 0.0);
    }
    IntegratorKind kind() const override { return IntegratorKind::path; }
};

/// Mean radiance 1 everywhere; the left half is bright and smooth (relative
/// standard deviation 0.1), the right half dark and noisy (relative sd 1):
/// exponential samples with mean 1 there.
class TwoHalvesIntegrator final : public Integrator {
public:
    Color Li(const RenderContext&, const Ray& ray, Rng& rng) const override {
        double u = rng.next_1d();
        if (ray.d.x < 0) return Color(1.0 + 0.1 * std::sqrt(12.0) * (u - 0.5));
        return Color(-std::log(1.0 - u));
    }
    IntegratorKind kind() const override { return IntegratorKind::path; }
};

double image_mean(const Image& image) {
    double sum = 0;
    for (float v : image.data()) sum += v;
    return sum / double(image.data().size());
}

/// relMSE against a known mean of 1 in every pixel.
double relmse_against_one(const Image& image) {
    double sum = 0;
    for (float v : image.data()) sum += (v - 1.0) * (v - 1.0) / (1.0 + 0.01);
    return sum / double(image.data().size());
}

}  // namespace

TEST_CASE("the interval rule on hand-computed sums") {
    // Alternating 1 and 3, n = 64: mu = 2, sigma^2 = 64/63, I = 1.96 sigma / 8 = 0.247.
    PixelStatistics s = sums_of({1, 3}, 32);
    CHECK_FALSE(reference::has_converged(s, 0.1));  // 0.247 > 0.1 * 2
    CHECK(reference::has_converged(s, 0.2));        // 0.247 <= 0.2 * 2
    CHECK(textbook_has_converged(s, 0.2) == reference::has_converged(s, 0.2));
}

TEST_CASE("the rare-event guard: equal samples never count as converged") {
    PixelStatistics zeros = sums_of({0}, 32), ones = sums_of({0.7}, 96);
    CHECK(textbook_has_converged(zeros, 0.05));  // the textbook rule stops a black pixel at once
    CHECK_FALSE(reference::has_converged(zeros, 0.05));
    CHECK_FALSE(reference::has_converged(ones, 0.05));
    CHECK_FALSE(reference::has_converged(sums_of({1}), 0.05));  // n = 1 has no variance estimate
}

TEST_CASE("a light seen with probability 1/64 keeps the adaptive image's mean equal to the uniform one") {
    Scene scene = test::make_quad_scene(24, 24);  // 576 pixels
    RareEventIntegrator integrator;
    RenderSettings settings;
    settings.spp = 256;
    settings.seed = 11;
    Stages stages = make_stages(StageSet::none());
    RenderResult uniform = test::render_with(scene, integrator, settings, stages);
    settings.adaptive = true;
    settings.samples_per_batch = 32;
    settings.max_tolerance = 0.05;
    RenderResult adaptive = test::render_with(scene, integrator, settings, stages);
    // Per-sample variance 64 - 1 = 63; the mean of 576 * 256 samples has
    // standard error sqrt(63 / 147456) = 0.021. 4 standard errors: a false
    // failure has probability 6e-5 (and the seed is fixed).
    const double se = std::sqrt(63.0 / (576.0 * 256.0));
    CHECK(std::fabs(image_mean(uniform.image) - 1.0) < 4 * se);
    CHECK(std::fabs(image_mean(adaptive.image) - 1.0) < 4 * se);
    // The textbook rule stops about (63/64)^32 = 60% of pixels at 32 black
    // samples: its image is far too dark.
    stages.adaptive.has_converged = textbook_has_converged;
    RenderResult textbook = test::render_with(scene, integrator, settings, stages);
    CHECK(image_mean(textbook.image) < 0.7);
}

TEST_CASE("at equal total samples, adaptive sampling beats uniform on a bright smooth half and a dark noisy half") {
    Scene scene = test::make_quad_scene(32, 32);
    TwoHalvesIntegrator integrator;
    Stages stages = make_stages(StageSet::none());
    RenderSettings settings;
    settings.seed = 3;
    settings.spp = 512;
    settings.adaptive = true;
    RenderResult adaptive = test::render_with(scene, integrator, settings, stages, 2);
    double mean_spp = double(adaptive.counters.camera_rays) / (32 * 32);
    settings.adaptive = false;
    settings.spp = int(std::lround(mean_spp));
    RenderResult uniform = test::render_with(scene, integrator, settings, stages, 2);
    double a = relmse_against_one(adaptive.image), u = relmse_against_one(uniform.image);
    MESSAGE("mean spp " << mean_spp << ", relMSE adaptive " << a << ", uniform " << u);
    // Expected: the smooth half stops at 32 samples, the noisy half runs to
    // 512: relMSE ~ (0.01/32 + 1/512)/2 = 1.1e-3 against (0.01 + 1)/2/272 =
    // 1.9e-3 for uniform. Each relMSE estimate has a relative spread of
    // about sqrt(2/512) = 6%, so 0.8 leaves a wide margin.
    CHECK(a < 0.8 * u);
}

TEST_CASE("adaptive images and sample counts are identical at any thread count") {
    Scene scene = test::make_quad_scene(40, 24);
    TwoHalvesIntegrator integrator;
    Stages stages = make_stages(StageSet::none());
    RenderSettings settings;
    settings.spp = 128;
    settings.adaptive = true;
    settings.samples_per_batch = 16;
    RenderResult one = test::render_with(scene, integrator, settings, stages, 1);
    RenderResult three = test::render_with(scene, integrator, settings, stages, 3);
    CHECK(one.image.data() == three.image.data());
    CHECK(one.sample_counts == three.sample_counts);
}
