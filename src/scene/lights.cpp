// Light implementations. See light_set.h for the interface and the change
// of variables from area to solid angle that every area light applies.
#include "scene/lights.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/frame.h"
#include "core/math.h"
#include "core/sampling.h"
#include "scene/environment_map.h"
#include "scene/interaction.h"

namespace pt {
namespace {

/// Where shadow rays towards a light at infinity end: twice the distance
/// from p to the far side of the scene's bounding sphere, so nothing in the
/// scene lies beyond it (pbrt-v3 uses 2 * worldRadius the same way).
struct FarAway {
    Vec3 center;
    double radius = 1.0;

    explicit FarAway(const BBox& bounds) {
        if (bounds.empty()) return;
        center = bounds.centroid();
        radius = std::max(0.5 * bounds.extent().norm(), 1e-6);
    }
    Vec3 point(const Vec3& p, const Vec3& w) const {
        return p + w * (2.0 * (radius + (p - center).norm()));
    }
    /// A point uniform on the disk of radius `radius` that faces the
    /// travel direction w and touches the bounding sphere on the side the
    /// light comes from: every ray from it along w crosses the whole scene.
    Vec3 disk_point(const Vec3& w, Vec2 u) const {
        Frame frame(w);
        Vec2 d = sample_concentric_disk(u);
        return center - w * radius + (frame.s * d.x + frame.t * d.y) * radius;
    }
    double disk_pdf() const { return 1.0 / (kPi * radius * radius); }
};

/// A cosine-weighted direction about the unit normal n (an area light's
/// emission, Lambertian), with its solid-angle density.
Vec3 sample_cosine_about(const Vec3& n, Vec2 u, double* pdf) {
    Vec3 local = sample_cosine_hemisphere(u);
    *pdf = cosine_hemisphere_pdf(local.z);
    return Frame(n).to_world(local);
}

class TriangleLight final : public Light {
  public:
    TriangleLight(const std::vector<Triangle>& triangles, const Color& Le) : Le_(Le) {
        for (const Triangle& t : triangles) {
            Vec3 ng = cross(t.p1 - t.p0, t.p2 - t.p0);
            double twice_area = ng.norm();
            if (!(twice_area > 0) || !std::isfinite(twice_area)) continue;  // no area, no light
            triangles_.push_back({t.p0, t.p1, t.p2, ng / twice_area});
            area_ += 0.5 * twice_area;
            cdf_.push_back(area_);
        }
        for (double& c : cdf_)
            c /= area_;
        if (!cdf_.empty()) cdf_.back() = 1.0;
    }

    LightSample sample_Li(const LightSampleContext& ref, Vec2 u) const override {
        if (triangles_.empty()) return {};
        Point q = sample_point(u);
        Vec3 d = q.p - ref.p;
        double r2 = d.norm2();
        if (!(r2 > 0)) return {};  // the shading point is on the light
        Vec3 wi = d / std::sqrt(r2);
        double cos_light = -dot(q.n, wi);
        if (!(cos_light > 0)) return {};  // the back of a one-sided light, or edge-on
        LightSample s;
        s.pdf = r2 / (cos_light * area_);  // pdf_A = 1 / area, to solid angle
        if (!std::isfinite(s.pdf)) return {};
        s.L = Le_;
        s.wi = wi;
        s.p = offset_ray_origin(q.p, q.p_error, q.n, -d);
        return s;
    }

    LightEmission sample_Le(Vec2 u_pos, Vec2 u_dir) const override {
        if (triangles_.empty()) return {};
        Point q = sample_point(u_pos);
        LightEmission e;
        e.p = q.p;
        e.p_error = q.p_error;
        e.n = q.n;
        e.w = sample_cosine_about(q.n, u_dir, &e.pdf_dir);
        e.pdf_pos = 1.0 / area_;
        e.Le = Le_;
        return e;
    }

    LightEmissionPdf pdf_Le(const Vec3&, const Vec3& n, const Vec3& w) const override {
        if (!(area_ > 0)) return {};
        return {1.0 / area_, cosine_hemisphere_pdf(dot(n, w))};
    }

    Color power() const override { return Le_ * (kPi * area_); }
    LightKind kind() const override { return LightKind::area; }

    double pdf_Li(const LightSampleContext& ref, const Vec3& wi, const Vec3& p_light,
                  const Vec3& n_light) const override {
        double cos_light = -dot(n_light, wi);
        if (!(cos_light > 0) || !(area_ > 0)) return 0.0;
        double pdf = (p_light - ref.p).norm2() / (cos_light * area_);
        return std::isfinite(pdf) ? pdf : 0.0;
    }

  private:
    struct Tri {
        Vec3 p0, p1, p2;  ///< corners, world space
        Vec3 n;           ///< unit geometric normal, the emitting side
    };
    struct Point {
        Vec3 p, p_error, n;
    };

    /// A point uniform by area on the light: a triangle picked with
    /// probability area / total area, then what is left of u.x (rescaled to
    /// [0, 1)) places the point in it, so pdf_A = 1 / area_ over the whole light.
    Point sample_point(Vec2 u) const {
        size_t k = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), u.x) - cdf_.begin());
        k = std::min(k, triangles_.size() - 1);
        double lo = k == 0 ? 0.0 : cdf_[k - 1];
        double width = cdf_[k] - lo;
        double ux = width > 0 ? std::min((u.x - lo) / width, 0x1.fffffffffffffp-1) : 0.0;
        const Tri& t = triangles_[k];
        Vec2 b = sample_uniform_triangle({ux, u.y});
        double b0 = 1.0 - b.x - b.y;
        Point q;
        q.p = b0 * t.p0 + b.x * t.p1 + b.y * t.p2;
        // Error bound of barycentric interpolation (pbrt-v3 section 3.9.3).
        q.p_error = gamma(7) * (abs(b0 * t.p0) + abs(b.x * t.p1) + abs(b.y * t.p2));
        q.n = t.n;
        return q;
    }

    std::vector<Tri> triangles_;
    std::vector<double> cdf_;  ///< cumulative area fractions; the last is 1
    double area_ = 0;          ///< total area, scene units^2
    Color Le_;                 ///< emitted radiance, W/(m^2 sr)
};

class SphereLight final : public Light {
  public:
    SphereLight(const Sphere& sphere, const Color& Le) : sphere_(sphere), Le_(Le) {}

    LightSample sample_Li(const LightSampleContext& ref, Vec2 u) const override {
        SphereCapSample c = sample_sphere_cap(u, sphere_.center, sphere_.radius, ref.p);
        if (!(c.pdf > 0) || !std::isfinite(c.pdf)) return {};  // inside: it emits outwards only
        LightSample s;
        s.L = Le_;
        s.wi = c.wi;
        s.pdf = c.pdf;
        // The point is centre + radius * n: a few roundings of |p| (pbrt-v3 section 3.9.4).
        Vec3 p_error = gamma(6) * (abs(c.p) + abs(sphere_.center));
        s.p = offset_ray_origin(c.p, p_error, c.n, ref.p - c.p);
        return s;
    }

    double pdf_Li(const LightSampleContext& ref, const Vec3&, const Vec3&,
                  const Vec3&) const override {
        return sphere_cap_pdf(sphere_.center, sphere_.radius, ref.p);
    }

    LightEmission sample_Le(Vec2 u_pos, Vec2 u_dir) const override {
        // Uniform over the whole sphere (a light subpath may start anywhere
        // on it), cosine-weighted about the outward normal.
        LightEmission e;
        e.n = sample_uniform_sphere(u_pos);
        e.p = sphere_.center + e.n * sphere_.radius;
        e.p_error = gamma(6) * (abs(e.p) + abs(sphere_.center));
        e.w = sample_cosine_about(e.n, u_dir, &e.pdf_dir);
        e.pdf_pos = 1.0 / area();
        e.Le = Le_;
        return e;
    }

    LightEmissionPdf pdf_Le(const Vec3&, const Vec3& n, const Vec3& w) const override {
        return {1.0 / area(), cosine_hemisphere_pdf(dot(n, w))};
    }

    Color power() const override { return Le_ * (kPi * area()); }
    LightKind kind() const override { return LightKind::area; }

  private:
    double area() const { return 4.0 * kPi * sphere_.radius * sphere_.radius; }

    Sphere sphere_;
    Color Le_;  ///< emitted radiance, W/(m^2 sr)
};

class PointLightSource final : public Light {
  public:
    explicit PointLightSource(const PointLight& light) : light_(light) {}

    LightSample sample_Li(const LightSampleContext& ref, Vec2) const override {
        Vec3 d = light_.position - ref.p;
        double r2 = d.norm2();
        LightSample s;
        s.L = light_.intensity / r2;  // inverse-square law: E = I / r^2 at normal incidence
        if (!(r2 > 0) || !s.L.is_finite()) return {};
        s.wi = d / std::sqrt(r2);
        s.pdf = 1.0;
        s.p = light_.position;  // nothing to offset: a point is not a surface
        s.is_delta = true;
        return s;
    }
    double pdf_Li(const LightSampleContext&, const Vec3&, const Vec3&, const Vec3&) const override {
        return 0.0;
    }
    bool is_delta() const override { return true; }

    LightEmission sample_Le(Vec2, Vec2 u_dir) const override {
        LightEmission e;
        e.p = light_.position;
        e.w = sample_uniform_sphere(u_dir);
        e.Le = light_.intensity;
        e.pdf_pos = 1.0;  // a delta in position
        e.pdf_dir = uniform_sphere_pdf();
        return e;
    }
    LightEmissionPdf pdf_Le(const Vec3&, const Vec3&, const Vec3&) const override {
        return {0.0, uniform_sphere_pdf()};
    }
    Color power() const override { return light_.intensity * (4.0 * kPi); }
    LightKind kind() const override { return LightKind::point; }

  private:
    PointLight light_;
};

class DirectionalLightSource final : public Light {
  public:
    DirectionalLightSource(const DirectionalLight& light, const BBox& bounds)
        : light_(light), far_(bounds) {}

    LightSample sample_Li(const LightSampleContext& ref, Vec2) const override {
        LightSample s;
        s.L = light_.irradiance;
        s.wi = -light_.direction;
        s.pdf = 1.0;
        s.p = far_.point(ref.p, s.wi);
        s.is_delta = true;
        return s;
    }
    double pdf_Li(const LightSampleContext&, const Vec3&, const Vec3&, const Vec3&) const override {
        return 0.0;
    }
    bool is_delta() const override { return true; }

    LightEmission sample_Le(Vec2 u_pos, Vec2) const override {
        LightEmission e;
        e.w = light_.direction;
        e.p = far_.disk_point(e.w, u_pos);
        e.n = e.w;
        e.Le = light_.irradiance;
        e.pdf_pos = far_.disk_pdf();
        e.pdf_dir = 1.0;  // a delta in direction
        return e;
    }
    LightEmissionPdf pdf_Le(const Vec3&, const Vec3&, const Vec3&) const override {
        return {far_.disk_pdf(), 0.0};
    }
    Color power() const override { return light_.irradiance / far_.disk_pdf(); }
    LightKind kind() const override { return LightKind::directional; }

  private:
    DirectionalLight light_;
    FarAway far_;
};

/// Constant radiance from every direction. Sampled cosine-weighted about the
/// shading normal: for a Lambertian surface f cos / pdf is then constant,
/// so an unoccluded diffuse point gets albedo * L with zero variance. With
/// no normal (ref.n = 0), uniformly over the sphere.
class ConstantEnvironmentLight final : public Light {
  public:
    ConstantEnvironmentLight(const Color& radiance, const BBox& bounds)
        : radiance_(radiance), far_(bounds) {}

    LightSample sample_Li(const LightSampleContext& ref, Vec2 u) const override {
        LightSample s;
        if (ref.n.norm2() > 0) {
            Frame frame(ref.n);
            Vec3 local = sample_cosine_hemisphere(u);
            s.pdf = cosine_hemisphere_pdf(local.z);
            s.wi = frame.to_world(local);
        } else {
            s.wi = sample_uniform_sphere(u);
            s.pdf = uniform_sphere_pdf();
        }
        if (!(s.pdf > 0)) return {};
        s.L = radiance_;
        s.p = far_.point(ref.p, s.wi);
        return s;
    }

    double pdf_Li(const LightSampleContext& ref, const Vec3& wi, const Vec3&,
                  const Vec3&) const override {
        if (ref.n.norm2() > 0) return cosine_hemisphere_pdf(dot(ref.n, wi));
        return uniform_sphere_pdf();
    }

    Color Le(const Vec3&) const override { return radiance_; }

    LightEmission sample_Le(Vec2 u_pos, Vec2 u_dir) const override {
        LightEmission e;
        e.w = -sample_uniform_sphere(u_dir);  // travelling away from the sky direction drawn
        e.p = far_.disk_point(e.w, u_pos);
        e.n = e.w;
        e.Le = radiance_;
        e.pdf_pos = far_.disk_pdf();
        e.pdf_dir = uniform_sphere_pdf();
        return e;
    }
    LightEmissionPdf pdf_Le(const Vec3&, const Vec3&, const Vec3&) const override {
        return {far_.disk_pdf(), uniform_sphere_pdf()};
    }
    Color power() const override { return radiance_ * (4.0 * kPi / far_.disk_pdf()); }
    LightKind kind() const override { return LightKind::environment; }

  private:
    Color radiance_;  ///< W/(m^2 sr), the same from every direction
    FarAway far_;
};

/// A lat-long environment map (scene/environment_map.h), importance-sampled
/// in proportion to luminance times sin(theta) by a 2D piecewise-constant
/// distribution; the density ignores the shading normal (directions below
/// the surface are drawn and then rejected by the estimator).
class EnvironmentMapLight final : public Light {
  public:
    EnvironmentMapLight(EnvironmentMap map, const BBox& bounds)
        : map_(std::move(map)), far_(bounds) {}

    LightSample sample_Li(const LightSampleContext& ref, Vec2 u) const override {
        EnvironmentMap::Sample e = map_.sample(u);
        if (!(e.pdf > 0) || !std::isfinite(e.pdf)) return {};
        LightSample s;
        s.L = e.L;
        s.wi = e.wi;
        s.pdf = e.pdf;
        s.p = far_.point(ref.p, s.wi);
        return s;
    }

    double pdf_Li(const LightSampleContext&, const Vec3& wi, const Vec3&,
                  const Vec3&) const override {
        return map_.pdf(unit(wi));
    }

    Color Le(const Vec3& direction) const override { return map_.Le(unit(direction)); }

    LightEmission sample_Le(Vec2 u_pos, Vec2 u_dir) const override {
        EnvironmentMap::Sample m = map_.sample(u_dir);
        if (!(m.pdf > 0) || !std::isfinite(m.pdf)) return {};
        LightEmission e;
        e.w = -m.wi;  // the ray travels from the sky into the scene
        e.p = far_.disk_point(e.w, u_pos);
        e.n = e.w;
        e.Le = m.L;
        e.pdf_pos = far_.disk_pdf();
        e.pdf_dir = m.pdf;
        return e;
    }
    LightEmissionPdf pdf_Le(const Vec3&, const Vec3&, const Vec3& w) const override {
        return {far_.disk_pdf(), map_.pdf(unit(-w))};
    }
    Color power() const override { return map_.integral() / far_.disk_pdf(); }
    LightKind kind() const override { return LightKind::environment; }

  private:
    /// w / |w|, but w itself when it is unit already: renormalising would move
    /// a direction on a pixel's edge into the neighbour, and the radiance and
    /// density of a sample would no longer be those of its direction.
    static Vec3 unit(const Vec3& w) {
        double n2 = w.norm2();
        return std::fabs(n2 - 1.0) < 1e-12 ? w : w / std::sqrt(n2);
    }

    EnvironmentMap map_;
    FarAway far_;
};

}  // namespace

std::unique_ptr<Light> make_triangle_light(const std::vector<Triangle>& triangles,
                                           const Color& Le) {
    return std::make_unique<TriangleLight>(triangles, Le);
}

std::unique_ptr<Light> make_sphere_light(const Sphere& sphere, const Color& Le) {
    return std::make_unique<SphereLight>(sphere, Le);
}

std::unique_ptr<Light> make_point_light(const PointLight& light) {
    return std::make_unique<PointLightSource>(light);
}

std::unique_ptr<Light> make_directional_light(const DirectionalLight& light, const BBox& bounds) {
    return std::make_unique<DirectionalLightSource>(light, bounds);
}

std::unique_ptr<Light> make_environment_light(const EnvironmentLight& light, const BBox& bounds) {
    if (!light.file.empty()) {
        // The map's pixels times "radiance" (a tint, default white) times "scale".
        return std::make_unique<EnvironmentMapLight>(
            EnvironmentMap::load(light.file, light.radiance * light.scale), bounds);
    }
    return std::make_unique<ConstantEnvironmentLight>(light.radiance * light.scale, bounds);
}

}  // namespace pt
