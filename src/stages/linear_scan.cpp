#include <optional>

#include "core/counters.h"
#include "scene/scene.h"
#include "stages/accelerator.h"

namespace pt {

std::optional<Hit> intersect_primitive(const Scene& scene, const IntersectStage& stage, uint32_t prim,
                                       const Ray& ray) {
    std::optional<Hit> hit = scene.is_sphere(prim)
                                 ? stage.intersect_sphere(scene.sphere_record(prim).sphere, ray)
                                 : stage.intersect_triangle(scene.triangle(prim), ray);
    if (hit) hit->primitive = prim;
    return hit;
}

namespace {

class LinearScan final : public Accelerator {
public:
    LinearScan(const Scene& scene, const IntersectStage& stage) : scene_(scene), stage_(stage) {}

    std::optional<Hit> intersect(const Ray& ray) const override {
        Ray r = ray;
        std::optional<Hit> closest;
        uint32_t n = scene_.primitive_count();
        for (uint32_t i = 0; i < n; ++i) {
            // Shrinking t_max makes every later test reject farther hits.
            if (std::optional<Hit> hit = intersect_primitive(scene_, stage_, i, r)) {
                closest = hit;
                r.t_max = hit->t;
            }
        }
        thread_counters().primitive_tests += n;
        return closest;
    }

    bool occluded(const Ray& ray) const override {
        uint32_t n = scene_.primitive_count();
        for (uint32_t i = 0; i < n; ++i) {
            if (intersect_primitive(scene_, stage_, i, ray)) {
                thread_counters().primitive_tests += i + 1;
                return true;
            }
        }
        thread_counters().primitive_tests += n;
        return false;
    }

    AcceleratorInfo info() const override { return {"linear", 0, 0, 0}; }

private:
    const Scene& scene_;
    IntersectStage stage_;
};

}  // namespace

std::unique_ptr<Accelerator> make_linear_scan(const Scene& scene, const IntersectStage& stage) {
    return std::make_unique<LinearScan>(scene, stage);
}

}  // namespace pt
