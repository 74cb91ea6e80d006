// Part 8, tasks 1 to 4, written from the handout's steps: the flux of
// equation 2, a kd-tree built by median selection along the widest axis,
// a k-nearest query with a max-heap, and equation 1 for the three kernels.
#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "scene/light_set.h"
#include "stages/photon.h"

namespace pt::student {

EmittedPhoton emit_photon(const Light& light, double light_probability, uint64_t count, Vec2 u_pos, Vec2 u_dir) {
    const LightEmission e = light.sample_Le(u_pos, u_dir);
    if (!e.valid()) return EmittedPhoton{};
    // A point light has no surface (n = 0): its cos theta is 1.
    const double cos_theta = e.n.norm2() == 0 ? 1.0 : std::fabs(dot(e.n, e.w));
    const double density = e.pdf_pos * e.pdf_dir * light_probability * double(count);
    return EmittedPhoton{e.ray(), e.Le * (cos_theta / density), true};
}

KdTree build_kdtree(const std::vector<Vec3>& points) {
    const size_t n = points.size();
    std::vector<uint32_t> order(n);
    for (size_t i = 0; i < n; ++i) order[i] = uint32_t(i);
    KdTree tree;
    tree.axis.assign(n, 0);
    // The node of [lo, hi) is its middle; the median along the axis of the
    // widest spread goes there, the smaller points to its left.
    auto build = [&](auto& self, size_t lo, size_t hi) -> void {
        if (hi - lo == 0) return;
        const size_t mid = lo + (hi - lo) / 2;
        Vec3 low = points[order[lo]], high = points[order[lo]];
        for (size_t i = lo + 1; i < hi; ++i) {
            low = min(low, points[order[i]]);
            high = max(high, points[order[i]]);
        }
        const Vec3 spread = high - low;
        int a = 0;
        if (spread[1] > spread[a]) a = 1;
        if (spread[2] > spread[a]) a = 2;
        std::nth_element(order.begin() + long(lo), order.begin() + long(mid), order.begin() + long(hi),
                         [&](uint32_t i, uint32_t j) { return points[i][a] < points[j][a]; });
        tree.axis[mid] = uint8_t(a);
        self(self, lo, mid);
        self(self, mid + 1, hi);
    };
    build(build, 0, n);
    tree.points.resize(n);
    for (size_t i = 0; i < n; ++i) tree.points[i] = points[order[i]];
    tree.ids = std::move(order);
    return tree;
}

void k_nearest(const KdTree& tree, const Vec3& p, int k, double max_dist2, std::vector<Neighbor>& out) {
    out.clear();
    if (k <= 0 || max_dist2 < 0) return;
    // A max-heap of the best k so far: out.front() is the farthest of them.
    auto nearer = [](const Neighbor& a, const Neighbor& b) { return a.dist2 < b.dist2; };
    double kth = max_dist2;  // the k-th distance once k are found
    auto visit = [&](auto& self, size_t lo, size_t hi) -> void {
        if (lo >= hi) return;
        const size_t mid = lo + (hi - lo) / 2;
        const int a = tree.axis[mid];
        const double delta = p[a] - tree.points[mid][a];
        if (delta <= 0)
            self(self, lo, mid);
        else
            self(self, mid + 1, hi);
        const double d2 = (tree.points[mid] - p).norm2();
        if (d2 <= kth) {
            out.push_back(Neighbor{tree.ids[mid], d2});
            std::push_heap(out.begin(), out.end(), nearer);
            if (out.size() > size_t(k)) {
                std::pop_heap(out.begin(), out.end(), nearer);
                out.pop_back();
            }
            if (out.size() == size_t(k)) kth = out.front().dist2;
        }
        if (delta * delta > kth) return;  // the other side lies beyond the k-th point
        if (delta <= 0)
            self(self, mid + 1, hi);
        else
            self(self, lo, mid);
    };
    visit(visit, 0, tree.size());
    std::sort_heap(out.begin(), out.end(), nearer);
}

Color density_estimate(const std::vector<PhotonContribution>& found, double radius2, PhotonKernel kernel) {
    const double r = std::sqrt(radius2);
    const double disk = kPi * radius2;
    Color sum;
    for (const PhotonContribution& c : found) {
        double weight;
        if (kernel == PhotonKernel::box)
            weight = 1.0 / disk;
        else if (kernel == PhotonKernel::cone)
            weight = 3.0 * (1.0 - std::sqrt(c.dist2) / r) / disk;
        else
            weight = 2.0 * (1.0 - c.dist2 / radius2) / disk;
        sum = sum + c.weighted_flux * weight;
    }
    return sum;
}

}  // namespace pt::student
