// Reference kd-tree (stages/kdtree.h): build by median selection; the
// k-nearest query descends iteratively, nearer side first (its design and
// what each choice bought: docs/photon_mapping.md, `bench kdtree`).
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

/// Subtrees of at most this many points are scanned, not descended (a
/// bucket): 16 to 32 measured alike (docs/photon_mapping.md).
constexpr size_t kScanBelow = 16;

/// A subtree still to visit, with what the pruning test needs: the
/// squared distance from p to the subtree's cell, the offsets that sum to
/// it (Arya and Mount's incremental distance, 1993: crossing a plane
/// replaces one axis's term, so a far cell is skipped when its whole box,
/// not only its nearest plane, lies beyond the k-th distance) and the node
/// point on the plane between the cell and its sibling.
struct PendingCell {
    uint32_t lo, hi;     ///< the subtree's range [lo, hi)
    uint32_t node;       ///< the parent's node point, on this cell's boundary
    double dist2;        ///< squared distance from p to the cell
    double offset[3];    ///< p's distance to the cell along each axis (0 inside)
};

/// One k-nearest query (reference): the (at most) k points within `bound`
/// nearest to p, nearest first: their squared distances written to
/// dist2[0, count) and their positions in tree order (not yet ids: ids are
/// looked up once, for the answers) to at[0, count); returns count.
/// dist2[-1] must be readable: it is set to -1, a sentinel below every
/// distance, so that the insertion loop needs no test for the front.
///
/// Why it is shaped this way, measured by `bench kdtree` and perf
/// (docs/photon_mapping.md): with k = 50 a query looks at about 400
/// points, and the time went to branch mispredictions in the candidate
/// bookkeeping and to cache misses on the descent, not to the distances.
/// Hence: the best k kept as a sorted array (insertion from the back, so
/// the answer needs no final sort; a heap plus a sort cost more at this
/// k), distances and positions in two arrays (a shift moves one double
/// and one index, not a padded pair), the first k taken best-first (see
/// below), a bucket's distances computed first and filtered without branches,
/// an explicit stack instead of recursion, and the two children
/// prefetched while the parent is examined. The state lives in locals, not
/// in members, so that the compiler keeps the bound in a register.
size_t knn_search(const KdTree& tree, const Vec3& p, size_t k, double bound, double* best_dist2, uint32_t* best_at) {
    const Vec3* points = tree.points.data();
    size_t count = 0;  // how many of the best are filled
    best_dist2[-1] = -1;

    // Keeps a point within the bound: inserted into the sorted best from
    // the back (the farthest drops out once k are held); the bound then
    // becomes the k-th distance.
    auto consider = [&](double dist2, uint32_t at) {
        if (!(dist2 <= bound)) return;  // written so that a NaN distance is never kept
        size_t i = count < k ? count++ : k - 1;
        for (; best_dist2[i - 1] > dist2; --i) {
            best_dist2[i] = best_dist2[i - 1];
            best_at[i] = best_at[i - 1];
        }
        best_dist2[i] = dist2;
        best_at[i] = at;
        if (count == k) bound = best_dist2[k - 1];
    };
    // Every point of the bucket [lo, hi), at most kScanBelow of them.
    auto scan_bucket = [&](uint32_t lo, uint32_t hi) {
        double dist2[kScanBelow];
        uint32_t inside[kScanBelow];
        const uint32_t n = hi - lo;
        for (uint32_t j = 0; j < n; ++j) dist2[j] = (points[lo + j] - p).norm2();
        // Most points of a bucket lie beyond the bound: keep the others by
        // arithmetic, not by a branch that the processor mispredicts.
        uint32_t m = 0;
        for (uint32_t j = 0; j < n; ++j) {
            inside[m] = j;
            m += dist2[j] <= bound;
        }
        for (uint32_t s = 0; s < m; ++s) consider(dist2[inside[s]], lo + inside[s]);
    };

    // A descent pushes at most one cell per level, and a 32-bit size has
    // at most 32 levels. Depth-first, the stack holds one path; a
    // best-first choice leaves older cells below a new descent, so it is
    // made only while a whole descent still fits.
    constexpr int kMaxDescent = 32, kStackSize = 128;
    PendingCell stack[kStackSize];
    int top = 0;
    // The cell being descended, in locals (registers): its range, squared
    // distance from p and per-axis offsets.
    uint32_t lo = 0, hi = uint32_t(tree.size());
    double cell_dist2 = 0, offset[3] = {0, 0, 0};
    for (;;) {
        // Descend to the bucket that holds p, leaving the far child of
        // every node on the stack.
        while (hi - lo > kScanBelow) {
            const uint32_t mid = lo + (hi - lo) / 2;
            // The next node is one of the two children's middles: fetch both
            // while this one is examined (a miss costs more than the
            // distance work of a whole bucket).
            __builtin_prefetch(&points[lo + (mid - lo) / 2]);
            __builtin_prefetch(&points[mid + 1 + (hi - mid - 1) / 2]);
            const int axis = tree.axis[mid];
            const double delta = p[axis] - points[mid][axis];
            PendingCell& far = stack[top++];
            far.node = mid;
            far.dist2 = cell_dist2 - offset[axis] * offset[axis] + delta * delta;
            far.offset[0] = offset[0];
            far.offset[1] = offset[1];
            far.offset[2] = offset[2];
            far.offset[axis] = delta;
            if (delta <= 0) {
                far.lo = mid + 1;
                far.hi = hi;
                hi = mid;
            } else {
                far.lo = lo;
                far.hi = mid;
                lo = mid + 1;
            }
        }
        scan_bucket(lo, hi);
        // Until k points are held the bound is infinite and every point
        // found is kept, so the first k decide how tight the bound starts:
        // take them from the nearest pending cell (best-first), not from
        // the last one pushed. Afterwards the stack's order (depth-first,
        // nearer side first) is as good and costs nothing.
        if (count < k && top > 1 && top + kMaxDescent <= kStackSize) {
            int nearest = top - 1;
            for (int i = top - 2; i >= 0; --i)
                if (stack[i].dist2 < stack[nearest].dist2) nearest = i;
            std::swap(stack[nearest], stack[top - 1]);
        }
        // Back up to the nearest pending cell that can still hold a better
        // point. Its node point lies on its boundary, so it is no nearer
        // than the cell: both are skipped together.
        const PendingCell* next = nullptr;
        while (top > 0 && !next) {
            const PendingCell& pending = stack[--top];
            if (pending.dist2 <= bound) next = &pending;
        }
        if (!next) return count;
        consider((points[next->node] - p).norm2(), next->node);
        lo = next->lo;
        hi = next->hi;
        cell_dist2 = next->dist2;
        offset[0] = next->offset[0];
        offset[1] = next->offset[1];
        offset[2] = next->offset[2];
    }
}

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
    // Reused across queries on this thread: no allocation per query. One
    // more distance than kept, for the sentinel in front.
    thread_local std::vector<double> dist2;
    thread_local std::vector<uint32_t> at;
    const size_t kept = std::min(size_t(k), tree.size());
    if (at.size() < kept) {
        dist2.resize(kept + 1);
        at.resize(kept);
    }
    const size_t found = knn_search(tree, p, kept, max_dist2, dist2.data() + 1, at.data());
    out.resize(found);
    for (size_t i = 0; i < found; ++i) out[i] = {tree.ids[at[i]], dist2[i + 1]};
}

}  // namespace reference
}  // namespace pt
