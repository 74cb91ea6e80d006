// Camera importance (scene/camera_importance.h) of the pinhole and the thin
// lens: the round trip of generate_ray, the identity We cos / (pdf_pos
// pdf_dir) = 1 that starts a camera subpath at weight 1, the normalisation
// integral We cos = 1, and the light-tracing identity: importance splatted
// from points drawn on a plane of known radiance renders that radiance in
// every pixel. Statistical checks use fixed seeds and 4.5 standard errors
// (two-sided 7e-6 per check; fewer than 60 checks in the file).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "scene/camera.h"
#include "scene/camera_importance.h"
#include "stages/camera.h"

using namespace pt;

namespace {

/// A camera at (0.3, -0.2, 0.5) looking along -z with a tilted up vector,
/// so that camera and world axes differ; lens_radius 0 is a pinhole.
Camera make_camera(double lens_radius, double focal_distance = 0) {
    Camera c;
    c.position = Vec3(0.3, -0.2, 0.5);
    c.look_at = Vec3(0.3, -0.2, -1.5);
    c.up = Vec3(0.2, 1, 0);
    c.vfov = 50;
    c.aspect = 1.5;
    c.lens_radius = lens_radius;
    c.focal_distance = focal_distance;
    c.finalize();
    return c;
}

/// The mean and standard error of n samples from their sums.
struct Mean {
    double sum = 0, sum2 = 0;
    long n = 0;
    void add(double x) { sum += x, sum2 += x * x, ++n; }
    double mean() const { return sum / double(n); }
    double standard_error() const {
        double m = mean();
        return std::sqrt(std::max(sum2 / double(n) - m * m, 0.0) / double(n));
    }
};

}  // namespace

TEST_CASE("camera importance: generate_ray lands where it was aimed, and starts at weight 1") {
    for (double lens : {0.0, 0.05}) {
        CAPTURE(lens);
        Camera c = make_camera(lens, 1.7);
        Rng rng(5);
        for (int i = 0; i < 2000; ++i) {
            Vec2 film = rng.next_2d(), u = rng.next_2d();
            Ray ray = reference::generate_ray(c, film.x, film.y, u);
            std::optional<Vec2> at = camera_film_position(c, ray.o, ray.d);
            REQUIRE(at);
            CHECK(at->x == doctest::Approx(film.x).epsilon(1e-9));
            CHECK(at->y == doctest::Approx(film.y).epsilon(1e-9));
            // We cos / (pdf_pos pdf_dir) = 1: generate_ray draws rays with
            // exactly the densities that pdf_We reports.
            double cos_theta = -dot(ray.d, c.backward);
            CameraRayPdf pdf = camera_pdf_We(c, ray.o, ray.d);
            double weight = camera_We(c, ray.o, ray.d) * cos_theta / (pdf.pos * pdf.dir);
            CHECK(weight == doctest::Approx(1.0).epsilon(1e-9));
        }
    }
}

TEST_CASE("camera importance: zero off the film and behind the camera") {
    Camera c = make_camera(0);
    Vec3 behind = c.backward;
    CHECK(camera_We(c, c.position, behind) == 0);
    CHECK(camera_pdf_We(c, c.position, behind).dir == 0);
    // Just outside the right edge of the film: tan(hfov/2) * 1.01 to the right.
    Vec3 outside = c.to_world(Vec3(1.01 * c.tan_half_hfov, 0, -1)).unit();
    CHECK(camera_We(c, c.position, outside) == 0);
    Vec3 inside = c.to_world(Vec3(0.99 * c.tan_half_hfov, 0, -1)).unit();
    CHECK(camera_We(c, c.position, inside) > 0);
    // A point behind the camera cannot be connected to it.
    CHECK_FALSE(camera_sample_Wi(c, c.position + c.backward * 2.0, {0.5, 0.5}).valid());
}

TEST_CASE("camera importance: the whole camera's importance integrates to 1") {
    // integral over the lens and the sphere of directions of We cos theta:
    // Monte Carlo with lens points uniform (density 1 / A_lens) and
    // directions uniform on the sphere (1 / (4 pi)).
    for (double lens : {0.0, 0.1}) {
        CAPTURE(lens);
        Camera c = make_camera(lens, 2.0);
        double lens_area = lens > 0 ? kPi * lens * lens : 1.0;
        Rng rng(11);
        Mean m;
        for (int i = 0; i < 400000; ++i) {
            Vec2 d = sample_concentric_disk(rng.next_2d());
            Vec3 p = c.position + c.to_world(Vec3(lens * d.x, lens * d.y, 0));
            Vec3 w = sample_uniform_sphere(rng.next_2d());
            double cos_theta = std::max(0.0, -dot(w, c.backward));
            m.add(camera_We(c, p, w) * cos_theta * lens_area / uniform_sphere_pdf());
        }
        CAPTURE(m.mean());
        CAPTURE(m.standard_error());
        CHECK(std::fabs(m.mean() - 1.0) < 4.5 * m.standard_error());
    }
}

TEST_CASE("camera importance: sample_Wi agrees with We and pdf_We") {
    Camera c = make_camera(0.08, 2.5);
    Rng rng(3);
    int valid = 0;
    for (int i = 0; i < 5000; ++i) {
        Vec3 ref = c.position + Vec3(4 * rng.next_1d() - 2, 4 * rng.next_1d() - 2, -0.5 - 4 * rng.next_1d());
        CameraImportanceSample s = camera_sample_Wi(c, ref, rng.next_2d());
        if (!s.valid()) continue;
        ++valid;
        CHECK((s.p_lens - c.position).norm() <= 0.08 * (1 + 1e-12));
        CHECK(s.distance == doctest::Approx((s.p_lens - ref).norm()));
        CHECK(camera_We(c, s.p_lens, -s.wi) == doctest::Approx(s.We));
        // The lens density 1 / A_lens, to solid angle at ref.
        CameraRayPdf pdf = camera_pdf_We(c, s.p_lens, -s.wi);
        double cos_lens = -dot(-s.wi, c.backward);
        CHECK(s.pdf == doctest::Approx(pdf.pos * s.distance * s.distance / cos_lens));
        // The ray from the lens point to ref lands at the film position reported.
        std::optional<Vec2> at = camera_film_position(c, s.p_lens, (ref - s.p_lens).unit());
        REQUIRE(at);
        CHECK(at->x == doctest::Approx(s.film.x));
        CHECK(at->y == doctest::Approx(s.film.y));
    }
    CHECK(valid > 1000);
}

TEST_CASE("camera importance: light tracing a plane of known radiance renders it in every pixel") {
    // A plane 3 units in front of the camera, perpendicular to its axis,
    // emitting radiance L(x) = 1 + 0.25 s + 0.1 t in the plane's coordinates
    // (s right, t up), and a 6x4 film. Points drawn uniformly on a rectangle
    // that covers the view from every lens point are connected to the camera
    // (camera_sample_Wi) and their importance splatted (x N pixels / M
    // points): pixel j estimates the mean radiance of its footprint. The
    // projection of a plane parallel to the film is affine, so that mean is
    // L at the footprint's centre. A film flipped in x or y, a half-pixel
    // offset, a wrong cos^4 or a missing pixel count all fail.
    const int W = 6, H = 4, N = W * H;
    const long M = 600000;
    for (double lens : {0.0, 0.1}) {
        CAPTURE(lens);
        Camera c = make_camera(lens, 2.2);  // the thin lens focuses off the plane: blur changes nothing
        const double D = 3.0, half_w = 3.0 * c.tan_half_hfov + 0.5, half_h = 3.0 * c.tan_half_vfov + 0.5;
        const Vec3 centre = c.position - c.backward * D;
        auto radiance = [&](double s, double t) { return 1.0 + 0.25 * s + 0.1 * t; };
        std::vector<double> sums(N, 0.0), sums2(N, 0.0);
        Rng rng(17);
        for (long k = 0; k < M; ++k) {
            double s = (2 * rng.next_1d() - 1) * half_w, t = (2 * rng.next_1d() - 1) * half_h;
            Vec3 x = centre + c.right * s + c.true_up * t;
            double pdf_area = 1.0 / (4 * half_w * half_h);
            CameraImportanceSample cs = camera_sample_Wi(c, x, rng.next_2d());
            if (!cs.valid()) continue;
            double cos_x = std::fabs(dot(cs.wi, c.backward));  // the plane's normal is the camera axis
            double value = radiance(s, t) * cs.We * cos_x / (cs.pdf * pdf_area) * N;
            int px = std::min(W - 1, int(cs.film.x * W)), py = std::min(H - 1, int((1 - cs.film.y) * H));
            sums[size_t(py * W + px)] += value;
            sums2[size_t(py * W + px)] += value * value;
        }
        for (int py = 0; py < H; ++py)
            for (int px = 0; px < W; ++px) {
                double mean = sums[size_t(py * W + px)] / double(M);
                double se = std::sqrt((sums2[size_t(py * W + px)] / double(M) - mean * mean) / double(M));
                // The footprint's centre: the pinhole ray through the pixel centre, on the plane.
                double sx = (2.0 * (px + 0.5) / W - 1.0) * c.tan_half_hfov * D;
                double sy = (2.0 * (1.0 - (py + 0.5) / H) - 1.0) * c.tan_half_vfov * D;
                CAPTURE(px);
                CAPTURE(py);
                CAPTURE(mean);
                CAPTURE(se);
                CHECK(std::fabs(mean - radiance(sx, sy)) < 4.5 * se);
            }
    }
}
