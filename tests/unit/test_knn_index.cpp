// The query-side index of the kd-tree (stages/knn_index.h): the reference
// k-nearest query through it returns exactly what the query on the tree
// alone returns (same ids in the same order, same distances bit for bit,
// ties included) and brute force's distances, on random points, duplicates,
// points on a plane and on a line, one point, none, sizes whose inner
// levels are incomplete (holes in the breadth-first numbering), and k up
// to the thousands. Deterministic (fixed seeds): no significance level.
#include <doctest/doctest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "core/rng.h"
#include "stages/kdtree.h"
#include "stages/knn_index.h"

using namespace pt;

namespace {

/// Queries at random points of [-1, 2]^3 and on stored points (ties), random
/// k and maximum distance; the two queries must agree exactly and match brute force.
void check_same_answers(const std::vector<Vec3>& points, int queries, uint64_t seed, int max_k = 60) {
    const KdTree tree = reference::build_kdtree(points);
    const KnnIndex index = build_knn_index(tree);
    CHECK(index.tree_size == points.size());
    Rng rng(seed);
    std::vector<Neighbor> plain, indexed;
    int agree = 0;
    for (int q = 0; q < queries; ++q) {
        const Vec3 p = (q % 2 == 0 || points.empty())
                           ? Vec3(3 * rng.next_1d() - 1, 3 * rng.next_1d() - 1, 3 * rng.next_1d() - 1)
                           : points[rng.next_u32() % points.size()];
        const int k = 1 + int(rng.next_u32() % uint32_t(max_k));
        const double max_dist2 = q % 3 == 0 ? 1e300 : 0.3 * rng.next_1d();
        reference::k_nearest(tree, p, k, max_dist2, plain);
        reference::k_nearest(tree, index, p, k, max_dist2, indexed);
        bool same = plain.size() == indexed.size();
        for (size_t i = 0; same && i < plain.size(); ++i)
            same = plain[i].id == indexed[i].id && plain[i].dist2 == indexed[i].dist2;
        // Brute force's distances, nearest first.
        std::vector<double> brute;
        for (const Vec3& x : points)
            if ((x - p).norm2() <= max_dist2) brute.push_back((x - p).norm2());
        std::sort(brute.begin(), brute.end());
        brute.resize(std::min(brute.size(), size_t(k)));
        same = same && indexed.size() == brute.size();
        for (size_t i = 0; same && i < indexed.size(); ++i)
            same = indexed[i].dist2 == brute[i] && indexed[i].dist2 == (points[indexed[i].id] - p).norm2();
        agree += same;
    }
    CHECK(agree == queries);
}

}  // namespace

TEST_CASE("knn index: same answers as the tree query on random points of many sizes") {
    Rng rng(21);
    // 16 and below: no inner node; 17, 33, 50, 1000, 5000: incomplete inner levels.
    for (size_t n : {1u, 2u, 16u, 17u, 33u, 50u, 1000u, 5000u, 20000u}) {
        std::vector<Vec3> points(n);
        for (Vec3& p : points) p = {rng.next_1d(), rng.next_1d(), rng.next_1d()};
        check_same_answers(points, 200, n);
    }
}

TEST_CASE("knn index: same answers on duplicates, a plane, a line, one point, none") {
    Rng rng(23);
    std::vector<Vec3> duplicates(500, Vec3(0.5, 0.5, 0.5));
    for (int i = 0; i < 100; ++i) duplicates.push_back({rng.next_1d(), rng.next_1d(), rng.next_1d()});
    check_same_answers(duplicates, 200, 1);

    std::vector<Vec3> plane(3000);
    for (Vec3& p : plane) p = {rng.next_1d(), 0.25, rng.next_1d()};
    check_same_answers(plane, 200, 2);

    std::vector<Vec3> line(400);
    for (size_t i = 0; i < line.size(); ++i) line[i] = {double(i % 17) * 0.01, 0, 0};  // repeated coordinates
    check_same_answers(line, 200, 3);

    // A coarse grid: many points at equal distances from grid-aligned queries.
    std::vector<Vec3> grid;
    for (int x = 0; x < 12; ++x)
        for (int y = 0; y < 12; ++y)
            for (int z = 0; z < 12; ++z) grid.push_back({x * 0.125, y * 0.125, z * 0.125});
    check_same_answers(grid, 300, 4);

    check_same_answers({Vec3(0.1, 0.2, 0.3)}, 20, 5);
    check_same_answers({}, 5, 6);
}

TEST_CASE("knn index: k in the thousands, and an index of another tree is refused") {
    Rng rng(29);
    std::vector<Vec3> points(6000);
    for (Vec3& p : points) p = {rng.next_1d(), rng.next_1d(), 0.01 * rng.next_1d()};
    check_same_answers(points, 30, 7, 6000);

    const KdTree tree = reference::build_kdtree(points);
    const KnnIndex other = build_knn_index(reference::build_kdtree({Vec3(0), Vec3(1)}));
    std::vector<Neighbor> found;
    CHECK_THROWS_AS(reference::k_nearest(tree, other, Vec3(0.5), 5, 1e300, found), std::logic_error);
}

TEST_CASE("knn index: each inner node's record is the tree's node point and axis") {
    Rng rng(31);
    std::vector<Vec3> points(777);
    for (Vec3& p : points) p = {rng.next_1d(), rng.next_1d(), rng.next_1d()};
    const KdTree tree = reference::build_kdtree(points);
    const KnnIndex index = build_knn_index(tree);
    // Walk the inner nodes (more than 16 points) with their breadth-first numbers.
    struct Range { size_t lo, hi; uint32_t h; };
    std::vector<Range> todo = {{0, tree.size(), 1}};
    int inner = 0, equal = 0;
    while (!todo.empty()) {
        const Range r = todo.back();
        todo.pop_back();
        if (r.hi - r.lo <= 16) continue;
        const size_t mid = r.lo + (r.hi - r.lo) / 2;
        ++inner;
        const KnnNode& node = index.node(r.h);
        equal += node.point == tree.points[mid] && node.axis == tree.axis[mid];
        todo.push_back({r.lo, mid, 2 * r.h});
        todo.push_back({mid + 1, r.hi, 2 * r.h + 1});
    }
    CHECK(inner == 63);  // 777 points: inner levels 0 to 5 are complete (2^6 - 1 nodes)
    CHECK(equal == inner);
}
