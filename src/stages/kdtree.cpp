// Reference kd-tree (stages/kdtree.h): build by median selection; the
// k-nearest query (stages/kdtree_search.h) reads the inner nodes from the
// students' layout here (its design and what each choice bought:
// docs/photon_mapping.md, `bench kdtree`).
#include "stages/kdtree.h"

#include <algorithm>
#include <numeric>

#include "core/bbox.h"
#include "stages/kdtree_search.h"

namespace pt {
namespace {

void build_range(KdTree& tree, std::vector<uint32_t>& order, const std::vector<Vec3>& input, size_t lo, size_t hi) {
    if (hi - lo <= 1) {
        if (hi > lo) tree.axis[lo] = 0;
        return;
    }
    BBox box;
    for (size_t i = lo; i < hi; ++i) box.expand(input[order[i]]);
    const int axis = max_dimension(box.extent());
    const size_t mid = lo + (hi - lo) / 2;
    // The median by the split coordinate: smaller-or-equal to its left,
    // greater-or-equal to its right (nth_element's guarantee).
    std::nth_element(order.begin() + long(lo), order.begin() + long(mid), order.begin() + long(hi),
                     [&](uint32_t a, uint32_t b) { return input[a][axis] < input[b][axis]; });
    tree.axis[mid] = uint8_t(axis);
    build_range(tree, order, input, lo, mid);
    build_range(tree, order, input, mid + 1, hi);
}

using kdtree_detail::kScanBelow;

/// The search reads the inner nodes from the students' layout itself: the
/// node of [lo, hi) is points[mid]. The next node is one of the two
/// children's middles: both are fetched while this one is examined (a
/// miss costs more than the distance work of a whole bucket).
struct TreeNodes {
    const Vec3* points;
    const uint8_t* axes;
    int axis(uint32_t mid, uint32_t) const { return axes[mid]; }
    const Vec3& point(uint32_t mid, uint32_t) const { return points[mid]; }
    void prefetch(uint32_t lo, uint32_t mid, uint32_t hi, uint32_t) const {
        __builtin_prefetch(&points[lo + (mid - lo) / 2]);
        __builtin_prefetch(&points[mid + 1 + (hi - mid - 1) / 2]);
    }
};

void radius_visit(const KdTree& tree, const Vec3& p, double r2, size_t lo, size_t hi, std::vector<Neighbor>& out) {
    while (lo < hi) {
        if (hi - lo <= kScanBelow) {
            for (size_t i = lo; i < hi; ++i) {
                const double d2 = (tree.points[i] - p).norm2();
                if (d2 <= r2) out.push_back({tree.ids[i], d2});
            }
            return;
        }
        const size_t mid = lo + (hi - lo) / 2;
        const double d2 = (tree.points[mid] - p).norm2();
        if (d2 <= r2) out.push_back({tree.ids[mid], d2});
        const int axis = tree.axis[mid];
        const double delta = p[axis] - tree.points[mid][axis];
        // Recurse into the far side only when the sphere crosses the plane;
        // continue the loop on the near side.
        if (delta <= 0) {
            if (delta * delta <= r2) radius_visit(tree, p, r2, mid + 1, hi, out);
            hi = mid;
        } else {
            if (delta * delta <= r2) radius_visit(tree, p, r2, lo, mid, out);
            lo = mid + 1;
        }
    }
}

bool range_is_valid(const KdTree& tree, size_t lo, size_t hi) {
    if (hi - lo <= 1) return true;
    const size_t mid = lo + (hi - lo) / 2;
    const int axis = tree.axis[mid];
    if (axis > 2) return false;
    const double split = tree.points[mid][axis];
    for (size_t i = lo; i < mid; ++i)
        if (tree.points[i][axis] > split) return false;
    for (size_t i = mid + 1; i < hi; ++i)
        if (tree.points[i][axis] < split) return false;
    return range_is_valid(tree, lo, mid) && range_is_valid(tree, mid + 1, hi);
}

}  // namespace

bool kdtree_is_valid(const KdTree& tree) {
    const size_t n = tree.points.size();
    if (tree.ids.size() != n || tree.axis.size() != n) return false;
    std::vector<bool> seen(n, false);
    for (uint32_t id : tree.ids) {
        if (id >= n || seen[id]) return false;
        seen[id] = true;
    }
    return range_is_valid(tree, 0, n);
}

void within_radius(const KdTree& tree, const Vec3& p, double radius2, std::vector<Neighbor>& out) {
    out.clear();
    if (radius2 < 0) return;
    radius_visit(tree, p, radius2, 0, tree.size(), out);
}

namespace reference {

KdTree build_kdtree(const std::vector<Vec3>& points) {
    KdTree tree;
    const size_t n = points.size();
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    tree.axis.assign(n, 0);
    build_range(tree, order, points, 0, n);
    tree.points.resize(n);
    for (size_t i = 0; i < n; ++i) tree.points[i] = points[order[i]];
    tree.ids = std::move(order);
    return tree;
}

void k_nearest(const KdTree& tree, const Vec3& p, int k, double max_dist2, std::vector<Neighbor>& out) {
    kdtree_detail::k_nearest(tree, TreeNodes{tree.points.data(), tree.axis.data()}, p, k, max_dist2, out);
}

}  // namespace reference
}  // namespace pt
