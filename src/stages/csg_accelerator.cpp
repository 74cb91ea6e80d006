#include "stages/csg_accelerator.h"

#include <algorithm>
#include <cmath>

#include "core/counters.h"
#include "core/math.h"
#include "scene/scene.h"

namespace pt {
namespace {

/// A BVH over one closed mesh that reports every triangle a ray crosses.
/// Median splits along the widest axis of the centroids, leaves of up to 4.
class CrossingBvh {
  public:
    CrossingBvh(const Scene& shape, uint32_t first, uint32_t count) {
        order_.resize(count);
        std::vector<BBox> boxes(count);
        for (uint32_t i = 0; i < count; ++i) {
            order_[i] = first + i;
            Triangle t = shape.triangle(first + i);
            boxes[i].expand(t.p0), boxes[i].expand(t.p1), boxes[i].expand(t.p2);
        }
        auto box_of = [&](uint32_t prim) -> const BBox& { return boxes[prim - first]; };
        if (count > 0) build(0, count, box_of);
        triangles_.reserve(count);
        for (uint32_t prim : order_) triangles_.push_back(shape.triangle(prim));
    }

    /// Appends the crossings of `ray` with t >= ray.t_min (any t_max).
    /// `inverted`: the mesh is stored turned round.
    void crossings(const Ray& ray, bool inverted, std::vector<CsgCrossing>& out) const {
        if (nodes_.empty()) return;
        const Vec3 inv_d(1 / ray.d.x, 1 / ray.d.y, 1 / ray.d.z);
        Ray line = ray;
        line.t_max = kInfinity;
        uint32_t stack[128];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            ++thread_counters().nodes_visited;
            if (!ray_enters(node.box, ray, inv_d, kInfinity)) continue;  // every crossing counts
            if (node.count == 0) {
                stack[top++] = node.second;
                stack[top++] = uint32_t(&node - nodes_.data()) + 1;
                continue;
            }
            thread_counters().primitive_tests += node.count;
            for (uint32_t k = node.first; k < node.first + node.count; ++k) {
                const Triangle& tri = triangles_[k];
                std::optional<Hit> h = reference::intersect_triangle_watertight(tri, line);
                if (!h) continue;
                double facing = dot(cross(tri.p1 - tri.p0, tri.p2 - tri.p0), ray.d);
                if (inverted) facing = -facing;
                if (!(facing != 0)) continue;  // in the triangle's plane: no crossing
                CsgCrossing c;
                c.end.t = h->t;
                c.end.primitive = order_[k];
                c.end.b1 = h->b1;
                c.end.b2 = h->b2;
                c.direction = facing < 0 ? +1 : -1;  // against the outward normal: entering
                out.push_back(c);
            }
        }
    }

    size_t bytes() const {
        return nodes_.size() * sizeof(Node) + order_.size() * sizeof(uint32_t) + triangles_.size() * sizeof(Triangle);
    }
    size_t nodes() const { return nodes_.size(); }

  private:
    struct Node {
        BBox box;
        uint32_t first = 0, count = 0;  ///< leaf: triangles_[first, first + count); inner: count 0
        uint32_t second = 0;            ///< inner: the right child (the left is the next node)
    };

    template <typename BoxOf>
    uint32_t build(uint32_t begin, uint32_t end, const BoxOf& box_of) {
        const uint32_t index = uint32_t(nodes_.size());
        nodes_.emplace_back();
        BBox box, centres;
        for (uint32_t i = begin; i < end; ++i) {
            box.expand(box_of(order_[i]));
            centres.expand(box_of(order_[i]).centroid());
        }
        nodes_[index].box = box;
        if (end - begin <= 4) {
            nodes_[index].first = begin;
            nodes_[index].count = end - begin;
            return index;
        }
        Vec3 e = centres.extent();
        int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
        uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                         [&](uint32_t a, uint32_t b) { return box_of(a).centroid()[axis] < box_of(b).centroid()[axis]; });
        build(begin, mid, box_of);
        nodes_[index].second = build(mid, end, box_of);
        return index;
    }

    std::vector<Node> nodes_;
    std::vector<uint32_t> order_;      ///< triangle ids in leaf order
    std::vector<Triangle> triangles_;  ///< the triangles, in leaf order
};

class CsgAccelerator : public Accelerator {
  public:
    CsgAccelerator(const Scene& shape, const CsgTree& tree) : shape_(shape), tree_(tree) {
        meshes_.resize(tree.nodes.size());
        for (size_t i = 0; i < tree.nodes.size(); ++i) {
            const CsgNode& node = tree.nodes[i];
            if (node.op == CsgOp::leaf && !node.sphere)
                meshes_[i] = std::make_unique<CrossingBvh>(shape, node.first, node.count);
        }
    }

    std::optional<Hit> intersect(const Ray& ray) const override {
        if (tree_.nodes.empty()) return std::nullopt;
        for (const CsgSpan& span : spans(0, ray))
            for (const CsgEnd* end : {&span.in, &span.out}) {
                if (end->t > ray.t_max) return std::nullopt;
                if (end->primitive != kNoIndex && end->t >= ray.t_min) return hit(*end, ray);
            }
        return std::nullopt;
    }

    bool occluded(const Ray& ray) const override { return intersect(ray).has_value(); }

    AcceleratorInfo info() const override {
        AcceleratorInfo i;
        i.name = "csg";
        for (const std::unique_ptr<CrossingBvh>& m : meshes_)
            if (m) i.nodes += m->nodes(), i.bytes += m->bytes();
        i.tree_bytes = i.bytes;
        i.depth = 1;
        return i;
    }

  private:
    CsgSpans spans(uint32_t index, const Ray& ray) const {
        const CsgNode& node = tree_.nodes[index];
        if (node.op == CsgOp::leaf) {
            if (node.sphere) {
                ++thread_counters().primitive_tests;
                return csg_sphere_spans(shape_.spheres[node.first].sphere, ray,
                                        uint32_t(shape_.triangles.size()) + node.first);
            }
            std::vector<CsgCrossing> crossings;
            meshes_[index]->crossings(ray, node.inverted, crossings);
            return csg_spans_of_crossings(std::move(crossings));
        }
        CsgSpans result = spans(node.children[0], ray);
        for (size_t k = 1; k < node.children.size(); ++k) {
            // Nothing left to intersect with or subtract from.
            if (result.empty() && node.op != CsgOp::union_op) break;
            result = csg_combine(node.op, result, spans(node.children[k], ray));
        }
        return result;
    }

    /// The hit at a span end, with the normal of the surface as stored
    /// (turned round for subtracted leaves by the loader).
    Hit hit(const CsgEnd& end, const Ray& ray) const {
        Hit h;
        h.t = end.t;
        h.primitive = end.primitive;
        if (shape_.is_sphere(end.primitive)) {
            const SphereRecord& s = shape_.sphere_record(end.primitive);
            h.n = (ray.at(end.t) - s.sphere.center).unit();
            if (s.inward) h.n = -h.n;
            return h;
        }
        h.b1 = end.b1;
        h.b2 = end.b2;
        Triangle tri = shape_.triangle(end.primitive);
        Vec3 n;
        if (tri.has_normals) n = (1 - end.b1 - end.b2) * tri.n0 + end.b1 * tri.n1 + end.b2 * tri.n2;
        if (!(n.norm() > 0)) n = cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
        h.n = n.unit();
        return h;
    }

    const Scene& shape_;
    const CsgTree& tree_;
    std::vector<std::unique_ptr<CrossingBvh>> meshes_;  ///< per node: the mesh leaves' BVHs
};

}  // namespace

std::unique_ptr<Accelerator> make_csg_accelerator(const Scene& shape, const CsgTree& tree) {
    return std::make_unique<CsgAccelerator>(shape, tree);
}

}  // namespace pt
