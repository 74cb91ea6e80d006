#include "render/bvh_view.h"

#include <algorithm>
#include <cmath>

#include "core/counters.h"
#include "core/error.h"
#include "core/math.h"
#include "image/tonemap.h"
#include "stages/render_context.h"
#include "scene/scene.h"

namespace pt {

BvhNodeView select_bvh_node(const Accelerator& accel, const std::string& path) {
    const auto* bvh = dynamic_cast<const InspectableBvh*>(&accel);
    if (!bvh)
        throw InputError("--bvh-view: needs a BVH, but the accelerator is '" + accel.info().name +
                         "' (drop --accel none)");
    std::optional<BvhNodeView> node = bvh->node_at("");
    if (!node) throw InputError("--bvh-view: the scene has no primitives, so its BVH has no nodes");
    for (size_t i = 1; i <= path.size(); ++i) {
        node = bvh->node_at(path.substr(0, i));
        if (!node)
            throw InputError("--bvh-view: '" + path + "' goes below a leaf: node '" +
                             path.substr(0, i - 1) + "' (depth " + std::to_string(i - 1) +
                             ") is a leaf");
    }
    return *node;
}

namespace {

/// The closest approach of the ray o + t d (t >= 0, d unit) to the segment
/// from p to p + e: the ray parameter there and the distance.
struct Approach {
    double t;
    double distance;
};

Approach closest_approach(const Vec3& o, const Vec3& d, const Vec3& p, const Vec3& e) {
    // Minimise |o + t d - p - u e| over t and u (the normal equations of
    // two lines), then clamp u to the segment and t to the ray.
    Vec3 w = o - p;
    double b = dot(d, e), c = dot(e, e), dw = dot(d, w), ew = dot(e, w);
    double denominator = c - b * b;  // |d| = 1
    double u = denominator > 1e-12 * c ? (ew - b * dw) / denominator : 0.0;
    u = std::clamp(u, 0.0, 1.0);
    double t = std::max(0.0, b * u - dw);
    // With t fixed, the best u on the segment.
    u = c > 0 ? std::clamp(dot(o + t * d - p, e) / c, 0.0, 1.0) : 0.0;
    return {t, (o + t * d - (p + u * e)).norm()};
}

class BvhViewIntegrator final : public Integrator {
  public:
    BvhViewIntegrator(const Scene& scene, const BvhNodeView& node, int film_height)
        : box_(node.box), below_(scene.primitive_count(), 0) {
        for (uint32_t prim : node.primitives)
            below_[prim] = 1;
        // The angle one pixel subtends at the centre of the image.
        pixel_angle_ = 2.0 * std::tan(radians(scene.camera.vfov) / 2) / std::max(film_height, 1);
    }

    Color Li(const RenderContext& context, const Ray& ray, Rng&) const override {
        std::optional<SurfaceInteraction> si = context.intersect(ray);
        Color c(0.05);  // background
        double hit_distance = kInfinity;
        double length = ray.d.norm();
        if (si) {
            // A headlight: brightness from the angle to the viewer.
            double lit = 0.12 + 0.78 * std::fabs(dot(si->n, si->wo));
            Color albedo = below_[si->primitive] ? Color(1.0, 0.42, 0.08) : Color(0.75, 0.75, 0.75);
            c = albedo * lit;
            hit_distance = si->t * length;
        }
        double edge = edge_weight(ray.o, ray.d / length, hit_distance);
        return c * (1 - edge) + Color(0.1, 0.85, 1.0) * edge;
    }

    IntegratorKind kind() const override { return IntegratorKind::normals; }

  private:
    /// How much of the box's wireframe covers this ray: 1 on a visible edge,
    /// 0.4 on one hidden behind the surface hit at `hit_distance`, 0 elsewhere.
    double edge_weight(const Vec3& o, const Vec3& d, double hit_distance) const {
        const Vec3 corner[2] = {box_.min, box_.max};
        double weight = 0;
        for (int axis = 0; axis < 3; ++axis) {
            Vec3 e(0);
            e[axis] = box_.max[axis] - box_.min[axis];
            // The four edges along `axis`: every choice of min/max on the other two.
            for (int k = 0; k < 4; ++k) {
                Vec3 p;
                for (int a = 0, bit = 0; a < 3; ++a)
                    p[a] = a == axis ? box_.min[a] : corner[(k >> bit++) & 1][a];
                Approach q = closest_approach(o, d, p, e);
                if (q.distance > 0.75 * pixel_angle_ * q.t) continue;
                weight = std::max(weight, q.t <= hit_distance ? 1.0 : 0.4);
            }
        }
        return weight;
    }

    BBox box_;                    ///< the selected node's box
    std::vector<uint8_t> below_;  ///< per primitive id: 1 when it lies below the node
    double pixel_angle_;          ///< radians per pixel
};

class BvhCostIntegrator final : public Integrator {
  public:
    Color Li(const RenderContext& context, const Ray& ray, Rng&) const override {
        const uint64_t before = thread_counters().nodes_visited;
        context.intersect(ray);
        return Color(double(thread_counters().nodes_visited - before));
    }
    IntegratorKind kind() const override { return IntegratorKind::depth; }
};

}  // namespace

std::unique_ptr<Integrator> make_bvh_view_integrator(const Scene& scene, const BvhNodeView& node,
                                                     int film_height) {
    return std::make_unique<BvhViewIntegrator>(scene, node, film_height);
}

std::unique_ptr<Integrator> make_bvh_cost_integrator() {
    return std::make_unique<BvhCostIntegrator>();
}

Image bvh_cost_heat_map(const Image& counts, double max_count) {
    // sRGB control points sampled from "inferno" (van der Walt and Smith, 2015).
    static const double stops[5][3] = {{0.00, 0.00, 0.02},
                                       {0.34, 0.06, 0.43},
                                       {0.73, 0.21, 0.33},
                                       {0.98, 0.55, 0.04},
                                       {0.99, 1.00, 0.64}};
    Image out(counts.width(), counts.height());
    for (int y = 0; y < counts.height(); ++y) {
        for (int x = 0; x < counts.width(); ++x) {
            double v = max_count > 0 ? std::clamp(counts.at(x, y).r / max_count, 0.0, 1.0) : 0.0;
            double s = v * 4;
            int i = std::min(int(s), 3);
            double f = s - i;
            double rgb[3];
            for (int k = 0; k < 3; ++k)
                rgb[k] = srgb_decode((1 - f) * stops[i][k] + f * stops[i + 1][k]);
            out.set(x, y, Color(rgb[0], rgb[1], rgb[2]));
        }
    }
    return out;
}

}  // namespace pt
