#include "stages/instance_accelerator.h"

#include <algorithm>
#include <numeric>
#include <vector>

#include "core/math.h"
#include "scene/scene.h"
#include "stages/bvh.h"
#include "stages/csg_accelerator.h"

namespace pt {
namespace {

/// A node of the top level: a leaf when count > 0 (instances order[first ..
/// first + count)), else an inner node whose children are at index + 1 and
/// `second`.
struct InstanceNode {
    BBox box;
    uint32_t first = 0;   ///< leaf: first slot in order_
    uint32_t second = 0;  ///< inner node: index of the right child
    uint32_t count = 0;   ///< leaf: instances; 0 for an inner node
};

constexpr uint32_t kLeafSize = 2;

class InstanceAccelerator : public Accelerator {
  public:
    InstanceAccelerator(std::unique_ptr<Accelerator> own, const Scene& scene, const Stages& stages,
                        const AcceleratorSettings& settings)
        : own_(std::move(own)), scene_(scene), order_(scene.instances.size()) {
        for (const ShapeRecord& shape : scene.shapes)
            shapes_.push_back(shape.csg ? make_csg_accelerator(*shape.geometry, *shape.csg)
                                        : build_accelerator(*shape.geometry, stages, settings));
        std::iota(order_.begin(), order_.end(), 0u);
        nodes_.reserve(2 * order_.size());
        build(0, uint32_t(order_.size()));
    }

    std::optional<Hit> intersect(const Ray& ray) const override {
        std::optional<Hit> best = own_->intersect(ray);
        double t_max = best ? best->t : ray.t_max;
        visit(ray, t_max, [&](uint32_t index, const Ray& local) {
            Ray bounded = local;
            bounded.t_max = t_max;
            std::optional<Hit> h = shapes_[scene_.instances[index].shape]->intersect(bounded);
            if (!h) return false;
            h->part = h->primitive;
            h->primitive = scene_.primitive_count() + index;
            h->n = scene_.instances[index].to_world.normal(h->n);
            t_max = h->t;
            best = h;
            return false;  // keep looking for a closer one
        });
        return best;
    }

    bool occluded(const Ray& ray) const override {
        if (own_->occluded(ray)) return true;
        bool blocked = false;
        visit(ray, ray.t_max, [&](uint32_t index, const Ray& local) {
            blocked = shapes_[scene_.instances[index].shape]->occluded(local);
            return blocked;  // any hit ends the search
        });
        return blocked;
    }

    AcceleratorInfo info() const override {
        AcceleratorInfo i = own_->info();
        i.name += "+instances";
        i.nodes += nodes_.size();
        i.bytes += nodes_.size() * sizeof(InstanceNode) + order_.size() * sizeof(uint32_t);
        for (const std::unique_ptr<Accelerator>& shape : shapes_) {
            AcceleratorInfo s = shape->info();
            i.nodes += s.nodes;
            i.bytes += s.bytes;
            i.depth = std::max(i.depth, s.depth + 1);
        }
        return i;
    }

  private:
    /// Builds the node over order_[begin, end): split at the median of the
    /// box centres along the widest axis of the centres (instances are few
    /// and evenly spread next to the triangles below them: no SAH needed).
    uint32_t build(uint32_t begin, uint32_t end) {
        const uint32_t index = uint32_t(nodes_.size());
        nodes_.emplace_back();
        BBox box, centres;
        for (uint32_t i = begin; i < end; ++i) {
            const BBox& b = scene_.instances[order_[i]].bounds;
            box.expand(b);
            centres.expand(b.centroid());
        }
        nodes_[index].box = box;
        if (end - begin <= kLeafSize) {
            nodes_[index].first = begin;
            nodes_[index].count = end - begin;
            return index;
        }
        Vec3 extent = centres.extent();
        int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
        uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                         [&](uint32_t a, uint32_t b) {
                             return scene_.instances[a].bounds.centroid()[axis] <
                                    scene_.instances[b].bounds.centroid()[axis];
                         });
        build(begin, mid);
        uint32_t right = build(mid, end);
        nodes_[index].second = right;
        return index;
    }

    /// Calls `test(instance, ray in its object space)` for every instance
    /// whose box the ray enters before t_max (read again after each call,
    /// since a closer hit shrinks it); stops when `test` returns true.
    template <typename Test>
    void visit(const Ray& ray, const double& t_max, Test test) const {
        if (nodes_.empty() || order_.empty()) return;
        const Vec3 inv_d(1 / ray.d.x, 1 / ray.d.y, 1 / ray.d.z);
        uint32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const InstanceNode& node = nodes_[stack[--top]];
            if (!ray_enters(node.box, ray, inv_d, t_max)) continue;
            if (node.count == 0) {
                stack[top++] = node.second;
                stack[top++] = uint32_t(&node - nodes_.data()) + 1;
                continue;
            }
            for (uint32_t slot = node.first; slot < node.first + node.count; ++slot) {
                const uint32_t index = order_[slot];
                const Transform& m = scene_.instances[index].to_world;
                Ray local = ray;
                local.o = m.inverse_point(ray.o);
                local.d = m.inverse_vector(ray.d);
                local.t_max = t_max;
                if (test(index, local)) return;
            }
        }
    }

    std::unique_ptr<Accelerator> own_;                  ///< the scene's triangles and spheres
    const Scene& scene_;
    std::vector<std::unique_ptr<Accelerator>> shapes_;  ///< per shape, in object space
    std::vector<InstanceNode> nodes_;                   ///< the top level, depth first
    std::vector<uint32_t> order_;                       ///< instance indices in leaf order
};

}  // namespace

std::unique_ptr<Accelerator> add_instances(std::unique_ptr<Accelerator> own, const Scene& scene,
                                           const Stages& stages, const AcceleratorSettings& settings) {
    if (scene.instances.empty()) return own;
    return std::make_unique<InstanceAccelerator>(std::move(own), scene, stages, settings);
}

}  // namespace pt
