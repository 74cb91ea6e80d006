// Reference kd-tree (stages/kdtree.h): build by median selection, queries
// by recursive descent, nearer side first.
#include "stages/kdtree.h"

#include <algorithm>
#include <numeric>

#include "core/bbox.h"

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

/// Subtrees of at most this many points are scanned, not descended.
constexpr size_t kScanBelow = 16;

/// State of one k-nearest query: a max-heap of the best k found so far.
struct KnnSearch {
    const KdTree& tree;
    Vec3 p;
    size_t k;
    double max_dist2;  ///< shrinks to the k-th distance once k points are found
    std::vector<Neighbor>& heap;  ///< a max-heap by dist2 once it holds k

    /// Keeps point i when it is nearer than the current k-th: the first k
    /// found are appended and then heapified once; afterwards a nearer one
    /// replaces the farthest at the root and sifts down (one pass, half the
    /// work of pop_heap + push_heap).
    void consider(size_t i) {
        const double d2 = (tree.points[i] - p).norm2();
        if (d2 > max_dist2) return;
        const size_t n = heap.size();
        if (n < k) {
            heap.push_back({tree.ids[i], d2});
            if (n + 1 == k) {
                std::make_heap(heap.begin(), heap.end(), farther);
                max_dist2 = heap.front().dist2;
            }
            return;
        }
        size_t hole = 0;
        for (size_t child = 1; child < n; child = 2 * hole + 1) {
            if (child + 1 < n && heap[child + 1].dist2 > heap[child].dist2) ++child;
            if (heap[child].dist2 <= d2) break;
            heap[hole] = heap[child];
            hole = child;
        }
        heap[hole] = {tree.ids[i], d2};
        max_dist2 = heap.front().dist2;
    }

    static bool farther(const Neighbor& a, const Neighbor& b) { return a.dist2 < b.dist2; }

    /// Visits the subtree [lo, hi) whose cell lies at squared distance
    /// cell_dist2 from p; offset[a] is p's distance to the cell along axis a
    /// (0 inside). Arya and Mount's incremental distance (1993): crossing a
    /// plane replaces one axis's term of the sum, so a far cell is skipped
    /// when its whole box, not only its nearest plane, is beyond the k-th
    /// distance.
    void visit(size_t lo, size_t hi, double cell_dist2, double offset[3]) {
        // A small subtree is cheaper to scan than to descend (a bucket).
        if (hi - lo <= kScanBelow) {
            for (size_t i = lo; i < hi; ++i) consider(i);
            return;
        }
        const size_t mid = lo + (hi - lo) / 2;
        const int axis = tree.axis[mid];
        const double delta = p[axis] - tree.points[mid][axis];
        // The side of the plane that holds p first; the other side only if
        // its cell is nearer than the current k-th distance.
        const bool left_first = delta <= 0;
        visit(left_first ? lo : mid + 1, left_first ? mid : hi, cell_dist2, offset);
        consider(mid);
        const double old_offset = offset[axis];
        const double far_dist2 = cell_dist2 - old_offset * old_offset + delta * delta;
        if (far_dist2 > max_dist2) return;
        offset[axis] = delta;
        visit(left_first ? mid + 1 : lo, left_first ? hi : mid, far_dist2, offset);
        offset[axis] = old_offset;
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
    out.clear();
    if (k <= 0 || tree.empty() || max_dist2 < 0) return;
    KnnSearch search{tree, p, size_t(k), max_dist2, out};
    double offset[3] = {0, 0, 0};
    search.visit(0, tree.size(), 0.0, offset);
    // Fewer than k found leaves no heap: a plain sort serves both cases.
    std::sort(out.begin(), out.end(), KnnSearch::farther);
}

}  // namespace reference
}  // namespace pt
