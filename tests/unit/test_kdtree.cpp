// The kd-tree of the photon maps (stages/kdtree.h): every query equals a
// brute-force scan (same distances, nearest first), on random points,
// duplicates, points on a plane, a single point and none; the layout's
// invariant holds; the tree is the same whatever order the build sees
// equal points in (determinism needs no more than this).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "stages/kdtree.h"

using namespace pt;

namespace {

std::vector<double> brute_distances(const std::vector<Vec3>& points, const Vec3& p, double max_dist2) {
    std::vector<double> d;
    for (const Vec3& q : points)
        if ((q - p).norm2() <= max_dist2) d.push_back((q - p).norm2());
    std::sort(d.begin(), d.end());
    return d;
}

/// k_nearest and within_radius against brute force at `queries` random points of the box [-1, 2]^3.
void check_queries(const std::vector<Vec3>& points, int queries, uint64_t seed) {
    KdTree tree = reference::build_kdtree(points);
    REQUIRE(kdtree_is_valid(tree));
    Rng rng(seed);
    std::vector<Neighbor> found;
    for (int q = 0; q < queries; ++q) {
        // Half the queries sit on stored points (zero distances, ties).
        Vec3 p = (q % 2 == 0 || points.empty()) ? Vec3(3 * rng.next_1d() - 1, 3 * rng.next_1d() - 1, 3 * rng.next_1d() - 1)
                                                : points[rng.next_u32() % points.size()];
        const int k = 1 + int(rng.next_u32() % 60);
        const double max_dist2 = q % 3 == 0 ? 1e300 : 0.3 * rng.next_1d();
        std::vector<double> brute = brute_distances(points, p, max_dist2);
        reference::k_nearest(tree, p, k, max_dist2, found);
        REQUIRE(found.size() == std::min(brute.size(), size_t(k)));
        for (size_t i = 0; i < found.size(); ++i) {
            CHECK(found[i].dist2 == brute[i]);
            CHECK(found[i].dist2 == (points[found[i].id] - p).norm2());
        }
        const double r2 = max_dist2 > 1 ? 0.05 : max_dist2;
        std::vector<double> in_radius = brute_distances(points, p, r2);
        within_radius(tree, p, r2, found);
        std::vector<double> got;
        for (const Neighbor& n : found) got.push_back((points[n.id] - p).norm2());
        std::sort(got.begin(), got.end());
        CHECK(got == in_radius);
    }
}

}  // namespace

TEST_CASE("kd-tree queries equal brute force on random points") {
    Rng rng(7);
    for (size_t n : {2u, 3u, 10u, 1000u, 5000u}) {
        std::vector<Vec3> points(n);
        for (Vec3& p : points) p = {rng.next_1d(), rng.next_1d(), rng.next_1d()};
        check_queries(points, 200, n);
    }
}

// A large k keeps the query filling (choosing the nearest pending cell)
// for many cells: its fixed stack must not overflow, and the answer is
// still brute force's.
TEST_CASE("kd-tree k-nearest with k in the thousands equals brute force") {
    Rng rng(13);
    std::vector<Vec3> points(20000);
    for (Vec3& p : points) p = {rng.next_1d(), rng.next_1d(), 0.01 * rng.next_1d()};
    KdTree tree = reference::build_kdtree(points);
    std::vector<Neighbor> found;
    for (int q = 0; q < 12; ++q) {
        const Vec3 p(rng.next_1d(), rng.next_1d(), 0.005);
        const int k = q % 3 == 0 ? 20000 : 1000 + 700 * q;
        std::vector<double> brute = brute_distances(points, p, 1e300);
        reference::k_nearest(tree, p, k, 1e300, found);
        REQUIRE(found.size() == size_t(k));
        bool equal = true;
        for (size_t i = 0; i < found.size(); ++i)
            equal = equal && found[i].dist2 == brute[i] && found[i].dist2 == (points[found[i].id] - p).norm2();
        CHECK(equal);
    }
}

TEST_CASE("kd-tree queries on degenerate sets: duplicates, a plane, a line, one point, none") {
    Rng rng(11);
    std::vector<Vec3> duplicates(500, Vec3(0.5, 0.5, 0.5));
    for (int i = 0; i < 100; ++i) duplicates.push_back({rng.next_1d(), rng.next_1d(), rng.next_1d()});
    check_queries(duplicates, 100, 1);

    std::vector<Vec3> plane(2000);
    for (Vec3& p : plane) p = {rng.next_1d(), 0.25, rng.next_1d()};
    check_queries(plane, 200, 2);

    std::vector<Vec3> line(300);
    for (size_t i = 0; i < line.size(); ++i) line[i] = {double(i % 17) * 0.01, 0, 0};  // repeated coordinates too
    check_queries(line, 100, 3);

    check_queries({Vec3(0.1, 0.2, 0.3)}, 50, 4);

    KdTree empty = reference::build_kdtree({});
    CHECK(kdtree_is_valid(empty));
    std::vector<Neighbor> found = {{1, 1.0}};
    reference::k_nearest(empty, Vec3(0), 5, 1e300, found);
    CHECK(found.empty());
    within_radius(empty, Vec3(0), 1.0, found);
    CHECK(found.empty());
}

TEST_CASE("kd-tree edge arguments: k = 0, radius 0, negative radius") {
    std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 0, 0}};
    KdTree tree = reference::build_kdtree(points);
    std::vector<Neighbor> found;
    reference::k_nearest(tree, Vec3(0), 0, 1e300, found);
    CHECK(found.empty());
    within_radius(tree, Vec3(0), 0.0, found);
    CHECK(found.size() == 2);  // both points equal to the query, nothing else
    within_radius(tree, Vec3(0), -1.0, found);
    CHECK(found.empty());
    reference::k_nearest(tree, Vec3(0), 2, 0.0, found);
    CHECK(found.size() == 2);
    // A NaN query point is at no distance <= max_dist2 (as for brute force): none.
    reference::k_nearest(tree, Vec3(std::nan(""), 0, 0), 2, 1e300, found);
    CHECK(found.empty());
}

TEST_CASE("kdtree_is_valid rejects a broken layout") {
    std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    KdTree tree = reference::build_kdtree(points);
    REQUIRE(kdtree_is_valid(tree));
    KdTree swapped = tree;
    std::swap(swapped.points[0], swapped.points[3]);
    std::swap(swapped.ids[0], swapped.ids[3]);
    CHECK_FALSE(kdtree_is_valid(swapped));
    KdTree repeated = tree;
    repeated.ids[1] = repeated.ids[0];
    CHECK_FALSE(kdtree_is_valid(repeated));
}
