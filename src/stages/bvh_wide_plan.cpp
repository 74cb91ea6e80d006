// Choosing the 8-wide nodes and their leaves by cost (stages/bvh_wide.h,
// plan_wide_nodes): the plan that collapse_to_wide then follows.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "stages/bvh_wide.h"

namespace pt {

// The 8-wide nodes and their leaves chosen by cost, not greedily: the
// collapse that is optimal under the SAH for wide nodes (Ylitie, Karras and
// Laine, "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide
// BVHs", HPG 2017, section 4.1). Over the binary tree, bottom up, C(n, i) is
// the least cost of the subtree of n given as at most i lanes:
//     C(n, 1) = min(C_leaf(n), c_node A(n) + D(n, 8)),
//     C(n, i) = min(C(n, i - 1), D(n, i)),
//     D(n, i) = min over 1 <= j < i of C(left, j) + C(right, i - j),
// with C_leaf(n) = A(n) blocks(p(n)), a leaf of the whole subtree tested in
// blocks of four (bvh_leaf_block.h), for p(n) <= kWideMergedLeaf (a binary leaf
// is always a leaf); the wide nodes are then read off the choices top down.
// The binary SAH tree's leaves hold at most four triangles (--max-leaf),
// and the 4-wide, binary and student trees keep them. c_node = 2 (the eight
// boxes of a node cost about two blocks of four triangles) measured best of
// 0.5, 1, 1.5, 2 and 3 on the ogre and the bunny. Against the greedy
// collapse (open the interior lane of largest area) with leaves merged by
// the block SAH, as before: ogre nodes 7,136 -> 4,628, triangle tests per
// diffuse ray 13.7 -> 11.3, box tests 55.6 -> 52.8, incoherent and shadow
// rays 2 to 7% faster on every mesh (docs/bvh_history.md, issue 17,
// eleventh run).
// (kWideMergedLeaf and kWidePlanNodeCost are in bvh_wide.h.) A merged
// leaf's primitives are contiguous (depth-first order); its descendants stay
// in `nodes`, unreachable.
void plan_wide_nodes(FlatBvh& bvh, WidePlan& plan) {
    constexpr int W = 8;
    const size_t n = bvh.nodes.size();
    std::vector<uint32_t> count(n), first(n);
    for (size_t i = n; i-- > 0;) {
        const FlatBvhNode& node = bvh.nodes[i];
        count[i] = node.is_leaf() ? node.count : count[i + 1] + count[node.offset];
        first[i] = node.is_leaf() ? node.offset : first[i + 1];
    }
    auto area = [](const FlatBvhNode& b) {
        double x = double(b.bounds[3]) - b.bounds[0], y = double(b.bounds[4]) - b.bounds[1],
               z = double(b.bounds[5]) - b.bounds[2];
        return x * y + y * z + z * x;
    };
    // cost[i][k - 1] = C(i, k); how[i][k - 1]: for k = 1, 1 leaf or 0 a wide
    // node; for k > 1, 0 for C(i, k - 1), else j of the best D(i, k).
    std::vector<std::array<float, W>> cost(n);
    std::vector<std::array<int8_t, W>> how(n);
    std::vector<int8_t> split8(n);  // j of D(i, 8), for a wide node's lanes
    for (size_t i = n; i-- > 0;) {
        const FlatBvhNode& node = bvh.nodes[i];
        const double a = area(node);
        const double leaf = a * double((count[i] + 3) / 4);
        if (node.is_leaf()) {
            cost[i].fill(float(leaf));
            how[i].fill(0);
            how[i][0] = 1;
            continue;
        }
        const std::array<float, W>& l = cost[i + 1];
        const std::array<float, W>& r = cost[node.offset];
        float d[W + 1];
        int8_t dj[W + 1];
        for (int k = 2; k <= W; ++k) {
            d[k] = INFINITY;
            dj[k] = 1;
            for (int j = 1; j < k; ++j) {
                const float c = l[j - 1] + r[k - j - 1];
                if (c < d[k]) {
                    d[k] = c;
                    dj[k] = int8_t(j);
                }
            }
        }
        split8[i] = dj[W];
        const double wide = kWidePlanNodeCost * a + d[W];
        const bool as_leaf = count[i] <= kWideMergedLeaf && leaf <= wide;
        cost[i][0] = float(as_leaf ? leaf : wide);
        how[i][0] = as_leaf ? 1 : 0;
        for (int k = 2; k <= W; ++k) {
            const bool dist = d[k] < cost[i][k - 2];
            cost[i][k - 1] = dist ? d[k] : cost[i][k - 2];
            how[i][k - 1] = dist ? dj[k] : 0;
        }
    }
    plan.first.assign(n, WidePlan::kNoPlan);
    plan.count.assign(n, 0);
    plan.lanes.clear();
    std::vector<uint32_t> wide;  // binary nodes to be made wide nodes
    // The lanes of subtree m given as at most k of them, appended to plan.lanes.
    auto gather = [&](auto&& self, uint32_t m, int k) -> void {
        while (k > 1 && how[m][k - 1] == 0) --k;
        if (k > 1) {
            const int j = how[m][k - 1];
            self(self, m + 1, j);
            self(self, bvh.nodes[m].offset, k - j);
            return;
        }
        FlatBvhNode& node = bvh.nodes[m];
        if (!node.is_leaf()) {
            if (how[m][0] == 1) {  // a leaf of the whole subtree
                node.count = uint16_t(count[m]);
                node.offset = first[m];
                node.axis = 0;
            } else {
                wide.push_back(m);
            }
        }
        plan.lanes.push_back(m);
    };
    if (bvh.nodes[0].is_leaf()) return;
    if (how[0][0] == 1) {
        gather(gather, 0, 1);
        plan.lanes.clear();
        return;
    }
    wide.push_back(0);
    while (!wide.empty()) {
        const uint32_t m = wide.back();
        wide.pop_back();
        plan.first[m] = uint32_t(plan.lanes.size());
        gather(gather, m + 1, split8[m]);
        gather(gather, bvh.nodes[m].offset, W - split8[m]);
        plan.count[m] = uint8_t(plan.lanes.size() - plan.first[m]);
    }
}

}  // namespace pt
