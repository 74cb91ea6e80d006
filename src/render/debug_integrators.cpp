// The two debug integrators of Part 1: normals and depth.
#include <algorithm>

#include "render/integrators.h"
#include "stages/render_context.h"

namespace pt {
namespace {

class NormalsIntegrator final : public Integrator {
public:
    Color Li(const RenderContext& context, const Ray& ray, Rng&) const override {
        std::optional<SurfaceInteraction> si = context.intersect(ray);
        if (!si) return Color(0);
        return Color(si->n.x * 0.5 + 0.5, si->n.y * 0.5 + 0.5, si->n.z * 0.5 + 0.5);
    }
    IntegratorKind kind() const override { return IntegratorKind::normals; }
};

class DepthIntegrator final : public Integrator {
public:
    Color Li(const RenderContext& context, const Ray& ray, Rng&) const override {
        std::optional<SurfaceInteraction> si = context.intersect(ray);
        if (!si) return Color(0);
        // Distances along the ray to the scene's bounding sphere.
        const BBox& b = context.scene.bounds;
        double radius = 0.5 * b.extent().norm();
        double to_center = (b.centroid() - ray.o).norm();
        double near = std::max(0.0, to_center - radius), far = to_center + radius;
        double distance = si->t * ray.d.norm();
        return Color(std::clamp((far - distance) / std::max(far - near, 1e-300), 0.0, 1.0));
    }
    IntegratorKind kind() const override { return IntegratorKind::depth; }
};

}  // namespace

std::unique_ptr<Integrator> make_normals_integrator() { return std::make_unique<NormalsIntegrator>(); }
std::unique_ptr<Integrator> make_depth_integrator() { return std::make_unique<DepthIntegrator>(); }

}  // namespace pt
