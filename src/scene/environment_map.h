// EnvironmentMap: light from infinitely far away, tabulated in a lat-long
// (equirectangular) image, importance-sampled in proportion to its
// luminance (pbrt-v3 section 14.2.4).
//
// Mapping, with +y up as in the scene files: a unit direction w towards the
// sky has theta = acos(w.y) (0 at the zenith) and phi = atan2(w.x, -w.z)
// (0 looking down -z); the image coordinates are u = 1/2 + phi / (2 pi)
// across and v = theta / pi down, so the top row is the zenith and the
// centre column is the -z horizon. Radiance is constant over each pixel,
// which is what makes the sampling density exact:
//     pdf_solid_angle(w) = pdf_uv(u, v) / (2 pi^2 sin theta).
#pragma once

#include <string>

#include "core/color.h"
#include "core/distribution.h"
#include "core/vec3.h"
#include "image/image.h"

namespace pt {

class EnvironmentMap {
public:
    /// `image` is linear radiance; every pixel is multiplied by `scale`.
    EnvironmentMap(Image image, Color scale);
    /// Reads a .hdr or .pfm lat-long map (InputError if it cannot).
    static EnvironmentMap load(const std::string& path, Color scale);

    /// Radiance arriving from direction `w` (unit, pointing away from the scene).
    Color Le(const Vec3& w) const;

    struct Sample {
        Vec3 wi;      ///< unit direction towards the environment
        Color L;      ///< radiance from wi
        double pdf;   ///< solid-angle density of wi; 0 if it should be ignored
    };
    /// Importance sample: a direction with density proportional to luminance times sin(theta).
    Sample sample(Vec2 u) const;
    /// Solid-angle density with which sample() picks `w`.
    double pdf(const Vec3& w) const;
    /// The integral of Le over the sphere of directions, W/m^2 (exact for
    /// the piecewise-constant map: each pixel's radiance times its solid angle).
    Color integral() const;

    const Image& image() const { return image_; }

    /// (u, v) in [0, 1]^2 of a unit direction, and back.
    static Vec2 direction_to_uv(const Vec3& w);
    static Vec3 uv_to_direction(Vec2 uv);

private:
    Image image_;
    Distribution2D distribution_;
};

/// A procedural sky for tests and demos: a horizon-to-zenith gradient, a
/// dim ground, and a small bright sun at the given elevation (degrees).
Image make_sky_image(int width, int height, double sun_elevation_degrees, double sun_azimuth_degrees);

}  // namespace pt
