#include "stages/kd_tree.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/counters.h"
#include "scene/scene.h"
#include "stages/spatial_subdivision.h"

namespace pt {
namespace {

constexpr double kTraversalCost = 1.0;   ///< K_T
constexpr double kIntersectCost = 0.8;   ///< K_I: of 1.5, 1 and 0.8, 0.8 built and traced fastest (bunny)
constexpr double kEmptyBonus = 0.8;      ///< cost factor when one side is empty

/// One end of a primitive's (clipped) box along one axis.
struct Event {
    enum Type : uint8_t { end = 0, planar = 1, start = 2 };  ///< sort order at equal positions
    double position;
    uint32_t prim;
    uint8_t axis;
    Type type;

    bool operator<(const Event& o) const {
        if (axis != o.axis) return axis < o.axis;
        if (position != o.position) return position < o.position;
        return type < o.type;
    }
};

/// Interior: the split plane and the index of the second child (the first
/// follows the node). Leaf: the range of its primitives in KdTree::refs.
struct KdNode {
    double split = 0;
    uint32_t offset = 0;  ///< interior: second child; leaf: first reference
    uint32_t count = 0;   ///< leaf: number of primitives
    uint8_t axis = 0;     ///< interior: 0, 1, 2
    bool leaf = true;
};

void add_events(std::vector<Event>& events, uint32_t prim, const BBox& box) {
    for (uint8_t a = 0; a < 3; ++a) {
        if (box.min[a] == box.max[a]) {
            events.push_back({box.min[a], prim, a, Event::planar});
        } else {
            events.push_back({box.min[a], prim, a, Event::start});
            events.push_back({box.max[a], prim, a, Event::end});
        }
    }
}

BBox intersection(const BBox& a, const BBox& b) {
    return BBox(max(a.min, b.min), min(a.max, b.max));
}

class KdTreeBuilder {
  public:
    KdTreeBuilder(std::vector<BBox> boxes, std::vector<KdNode>& nodes, std::vector<uint32_t>& refs)
        : boxes_(std::move(boxes)), side_(boxes_.size(), 0), nodes_(nodes), refs_(refs) {}

    void build(const BBox& voxel, std::vector<Event> events, uint32_t n, int depth) {
        uint32_t index = uint32_t(nodes_.size());
        nodes_.push_back({});
        Split best = find_split(voxel, events, n);
        if (depth == 0 || n <= 1 || !(best.cost < kIntersectCost * n)) {
            nodes_[index].offset = uint32_t(refs_.size());
            nodes_[index].count = n;
            for (const Event& e : events)
                if (e.axis == 0 && e.type != Event::end) refs_.push_back(e.prim);
            return;
        }
        // Classify: 1 left only, 2 right only, 3 both.
        for (const Event& e : events) {
            if (e.axis == 0 && e.type != Event::end) side_[e.prim] = 3;
        }
        for (const Event& e : events) {
            if (e.axis != best.axis) continue;
            if (e.type == Event::end && e.position <= best.position) side_[e.prim] = 1;
            if (e.type == Event::start && e.position >= best.position) side_[e.prim] = 2;
            if (e.type == Event::planar)
                side_[e.prim] = e.position <= best.position ? 1 : 2;
        }
        BBox left_voxel = voxel, right_voxel = voxel;
        left_voxel.max[best.axis] = best.position;
        right_voxel.min[best.axis] = best.position;
        // One-sided primitives keep their (sorted) events; straddling ones
        // get new events clipped to each side, sorted and merged in.
        std::vector<Event> left, right, left_new, right_new;
        uint32_t n_left = 0, n_right = 0;
        for (const Event& e : events) {
            if (side_[e.prim] == 1) left.push_back(e);
            if (side_[e.prim] == 2) right.push_back(e);
            if (e.axis == 0 && e.type != Event::end) {
                uint8_t s = side_[e.prim];
                n_left += (s & 1) ? 1 : 0;
                n_right += (s & 2) ? 1 : 0;
                if (s == 3) {
                    add_events(left_new, e.prim, intersection(boxes_[e.prim], left_voxel));
                    add_events(right_new, e.prim, intersection(boxes_[e.prim], right_voxel));
                }
            }
        }
        std::vector<Event>().swap(events);
        merge_in(left, left_new);
        merge_in(right, right_new);
        nodes_[index].leaf = false;
        nodes_[index].axis = uint8_t(best.axis);
        nodes_[index].split = best.position;
        build(left_voxel, std::move(left), n_left, depth - 1);
        nodes_[index].offset = uint32_t(nodes_.size());
        build(right_voxel, std::move(right), n_right, depth - 1);
    }

  private:
    struct Split {
        int axis = 0;
        double position = 0;
        double cost = INFINITY;
    };

    static void merge_in(std::vector<Event>& events, std::vector<Event>& added) {
        std::sort(added.begin(), added.end());
        size_t middle = events.size();
        events.insert(events.end(), added.begin(), added.end());
        std::inplace_merge(events.begin(), events.begin() + long(middle), events.end());
    }

    /// The sweep: events of one axis in order; at each position, primitives
    /// ending there leave the right side before the plane is evaluated and
    /// primitives starting there join the left side after.
    Split find_split(const BBox& voxel, const std::vector<Event>& events, uint32_t n) const {
        Split best;
        const double area = voxel.surface_area();
        if (!(area > 0)) return best;
        size_t i = 0;
        while (i < events.size()) {
            const int axis = events[i].axis;
            uint32_t n_left = 0, n_right = n;
            while (i < events.size() && events[i].axis == axis) {
                const double p = events[i].position;
                uint32_t ending = 0, planar = 0, starting = 0;
                for (; i < events.size() && events[i].axis == axis && events[i].position == p; ++i) {
                    if (events[i].type == Event::end) ++ending;
                    if (events[i].type == Event::planar) ++planar;
                    if (events[i].type == Event::start) ++starting;
                }
                n_right -= ending + planar;
                if (p > voxel.min[axis] && p < voxel.max[axis]) {
                    BBox l = voxel, r = voxel;
                    l.max[axis] = p;
                    r.min[axis] = p;
                    uint32_t nl = n_left + planar;
                    double cost = kTraversalCost + kIntersectCost * (l.surface_area() * nl +
                                                                     r.surface_area() * n_right) / area;
                    if (nl == 0 || n_right == 0) cost *= kEmptyBonus;
                    if (cost < best.cost) best = {axis, p, cost};
                }
                n_left += starting + planar;
            }
        }
        return best;
    }

    std::vector<BBox> boxes_;     ///< per primitive, with the insertion margin
    std::vector<uint8_t> side_;   ///< per primitive, scratch for the classification
    std::vector<KdNode>& nodes_;
    std::vector<uint32_t>& refs_;
};

class KdTree final : public Accelerator {
  public:
    KdTree(const Scene& scene, const IntersectStage& stage) : scene_(scene), stage_(stage) {
        const uint32_t n = scene.primitive_count();
        if (n == 0) return;
        for (uint32_t p = 0; p < n; ++p)
            bounds_.expand(padded_primitive_bounds(scene, p));
        const double margin = insertion_margin(bounds_);
        bounds_ = BBox(bounds_.min - Vec3(2 * margin), bounds_.max + Vec3(2 * margin));
        std::vector<BBox> boxes(n);
        std::vector<Event> events;
        events.reserve(6 * size_t(n));
        for (uint32_t p = 0; p < n; ++p) {
            boxes[p] = insertion_bounds(scene, p, margin);
            add_events(events, p, boxes[p]);
        }
        std::sort(events.begin(), events.end());
        int max_depth = int(std::lround(8 + 1.3 * std::log2(double(n))));
        KdTreeBuilder(std::move(boxes), nodes_, refs_).build(bounds_, std::move(events), n, max_depth);
    }

    std::optional<Hit> intersect(const Ray& ray) const override {
        ClosestHit closest(ray);
        uint64_t tests = 0;
        traverse(ray, [&](const KdNode& leaf, double t_exit) {
            for (uint32_t i = leaf.offset; i < leaf.offset + leaf.count; ++i) {
                ++tests;
                closest.offer(intersect_primitive(scene_, stage_, refs_[i], closest.ray));
            }
            return !(closest.best && closest.best->t <= t_exit);
        });
        thread_counters().primitive_tests += tests;
        return closest.best;
    }

    bool occluded(const Ray& ray) const override {
        uint64_t tests = 0;
        bool hit = false;
        traverse(ray, [&](const KdNode& leaf, double) {
            for (uint32_t i = leaf.offset; i < leaf.offset + leaf.count && !hit; ++i) {
                ++tests;
                hit = intersect_primitive(scene_, stage_, refs_[i], ray).has_value();
            }
            return !hit;
        });
        thread_counters().primitive_tests += tests;
        return hit;
    }

    AcceleratorInfo info() const override {
        int depth = 0;
        std::vector<std::pair<uint32_t, int>> stack;
        if (!nodes_.empty()) stack.push_back({0, 0});
        while (!stack.empty()) {
            auto [i, d] = stack.back();
            stack.pop_back();
            depth = std::max(depth, d);
            if (!nodes_[i].leaf) {
                stack.push_back({i + 1, d + 1});
                stack.push_back({nodes_[i].offset, d + 1});
            }
        }
        uint64_t bytes = nodes_.size() * sizeof(KdNode) + refs_.size() * sizeof(uint32_t);
        return {"kdtree", nodes_.size(), depth, bytes, bytes};
    }

  private:
    /// Front-to-back traversal: calls visit(leaf, t_exit) for the leaves the
    /// ray crosses within [t_min, t_max], nearest first, until it returns false.
    template <class Visit>
    void traverse(const Ray& ray, Visit visit) const {
        double t_min, t_max;
        if (nodes_.empty() || !clip_ray(bounds_, ray, t_min, t_max)) return;
        struct Todo {
            uint32_t node;
            double t_min, t_max;
        };
        Todo stack[128];
        int size = 0;
        uint32_t node = 0;
        uint64_t visited = 0;
        for (;;) {
            const KdNode& n = nodes_[node];
            ++visited;
            if (!n.leaf) {
                const int a = n.axis;
                // The child on the origin's side first; a ray in the plane
                // (d = 0, o on it) sees the same primitives on both sides.
                bool below_first = ray.o[a] < n.split || (ray.o[a] == n.split && ray.d[a] <= 0);
                uint32_t first = below_first ? node + 1 : n.offset;
                uint32_t second = below_first ? n.offset : node + 1;
                if (ray.d[a] == 0) {
                    node = first;
                    continue;
                }
                double t_split = (n.split - ray.o[a]) / ray.d[a];
                if (t_split > t_max || t_split <= 0) {
                    node = first;
                } else if (t_split < t_min) {
                    node = second;
                } else {
                    stack[size++] = {second, t_split, t_max};
                    node = first;
                    t_max = t_split;
                }
                continue;
            }
            if (!visit(n, t_max) || size == 0) break;
            const Todo& next = stack[--size];
            node = next.node;
            t_min = next.t_min;
            t_max = next.t_max;
        }
        thread_counters().nodes_visited += visited;
    }

    const Scene& scene_;
    IntersectStage stage_;
    BBox bounds_;                ///< the root voxel: all primitives, plus a margin
    std::vector<KdNode> nodes_;  ///< depth-first; the first child follows its parent
    std::vector<uint32_t> refs_;  ///< primitive ids, leaf by leaf
};

}  // namespace

std::unique_ptr<Accelerator> make_kd_tree(const Scene& scene, const IntersectStage& stage) {
    return std::make_unique<KdTree>(scene, stage);
}

}  // namespace pt
