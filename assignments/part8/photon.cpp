// Part 8, tasks 1 to 4: photon emission, the kd-tree and the density
// estimate. Read assignments/part8/README.md first; the contract of each
// function is in src/stages/photon.h and src/stages/kdtree.h.
#include <algorithm>

#include "core/error.h"
#include "core/stub_fallback.h"
#include "scene/light_set.h"
#include "stages/photon.h"

namespace pt::student {

EmittedPhoton emit_photon(const Light& light, double light_probability, uint64_t count, Vec2 u_pos, Vec2 u_dir) {
    // TODO(part8.1): emit_photon, as src/stages/photon.h states its contract (equation 2 of the handout).
    // [guided]
    // Draw a ray leaving the light, e = light.sample_Le(u_pos, u_dir).
    // If it is not valid (e.valid()), return an EmittedPhoton with valid = false.
    // Else the photon travels along e.ray() and carries (equation 2 of the handout)
    //     flux = e.Le |cos theta| / (e.pdf_pos * e.pdf_dir * light_probability * count)
    // with cos theta = dot(e.n, e.w) (use 1 when e.n is (0, 0, 0): a point light).
    // [/guided]
    (void)light, (void)light_probability, (void)count, (void)u_pos, (void)u_dir;
    throw NotImplemented(8, "1", "emit_photon");
}

KdTree build_kdtree(const std::vector<Vec3>& points) {
    // TODO(part8.2): build_kdtree, as src/stages/kdtree.h states its contract.
    // [guided]
    // Build the balanced tree of src/stages/kdtree.h:
    // tree.points (the points in tree order), tree.ids (their input
    // indices) and tree.axis (one split dimension per node), all of size n.
    // Recursively, for the index range [lo, hi) of an array of input
    // indices: mid = lo + (hi - lo) / 2; pick the axis along which the
    // range's points spread the most; std::nth_element the range by that
    // coordinate so that the median lands at mid; axis[mid] = that axis;
    // then recurse on [lo, mid) and [mid + 1, hi).
    // [/guided]
    (void)points;
    throw NotImplemented(8, "2", "build_kdtree");
}

void k_nearest(const KdTree& tree, const Vec3& p, int k, double max_dist2, std::vector<Neighbor>& out) {
    // TODO(part8.3): k_nearest, as src/stages/kdtree.h states its contract.
    // [guided]
    // Descend from the root range [0, n): at the node mid,
    // first visit the side of the splitting plane that holds p, consider
    // the node's own point, then visit the other side only if the plane is
    // closer than the current k-th distance (delta^2 <= max_dist2, where
    // max_dist2 shrinks to the k-th distance once k points are found). Keep
    // the best k in a max-heap (std::push_heap / std::pop_heap by dist2),
    // and return them sorted nearest first.
    // [/guided]
    //
    // Until then: a brute-force scan, correct on any tree but O(n) per query.
    stub_fallback(8, "3", "k_nearest", "a brute-force scan of every photon");
    out.clear();
    if (k <= 0 || max_dist2 < 0) return;
    for (size_t i = 0; i < tree.size(); ++i) {
        const double d2 = (tree.points[i] - p).norm2();
        if (d2 <= max_dist2) out.push_back({tree.ids[i], d2});
    }
    std::sort(out.begin(), out.end(), [](const Neighbor& a, const Neighbor& b) { return a.dist2 < b.dist2; });
    if (out.size() > size_t(k)) out.resize(size_t(k));
}

Color density_estimate(const std::vector<PhotonContribution>& found, double radius2, PhotonKernel kernel) {
    // TODO(part8.4): density_estimate, as src/stages/photon.h states its contract (equation 1 of the handout).
    // [guided]
    // Equation 1 of the handout: the sum over `found` of
    // c.weighted_flux * K(d), d^2 = c.dist2, for the kernel of radius
    // r = sqrt(radius2) whose integral over the disk is 1:
    //     box           K = 1 / (pi r^2)
    //     cone          K = 3 (1 - d / r) / (pi r^2)
    //     epanechnikov  K = 2 (1 - d^2 / r^2) / (pi r^2)
    // Black when `found` is empty.
    // [/guided]
    (void)found, (void)radius2, (void)kernel;
    throw NotImplemented(8, "4", "density_estimate");
}

}  // namespace pt::student
