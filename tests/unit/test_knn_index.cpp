// The query-side index of the kd-tree (stages/knn_index.h): the reference
// k-nearest query through it returns exactly what the query on the tree
// alone returns (same ids in the same order, same distances bit for bit,
// ties included) and brute force's distances, on random points, duplicates,
// points on a plane and on a line, one point, none, sizes whose inner
// levels are incomplete (holes in the breadth-first numbering), and k up
// to the thousands; queries along a walk that start from a guessed first
// bound, on random points and on ties. Deterministic (fixed seeds): no
// significance level.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/rng.h"
#include "stages/kdtree.h"
#include "stages/knn_index.h"

using namespace pt;

namespace {

/// The tree query and the index query at p; whether they answer alike (the
/// same ids and distances in the same order). The answers stay in plain and indexed.
bool queries_agree(const KdTree& tree, const KnnIndex& index, const Vec3& p, int k, double max_dist2,
                   std::vector<Neighbor>& plain, std::vector<Neighbor>& indexed) {
    reference::k_nearest(tree, p, k, max_dist2, plain);
    reference::k_nearest(tree, index, p, k, max_dist2, indexed);
    bool same = plain.size() == indexed.size();
    for (size_t i = 0; same && i < plain.size(); ++i)
        same = plain[i].id == indexed[i].id && plain[i].dist2 == indexed[i].dist2;
    return same;
}

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
        bool same = queries_agree(tree, index, p, k, max_dist2, plain, indexed);
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

namespace {

/// `queries` queries with one k along a random walk of small steps (as a
/// renderer's gathers come, so that the query starts from a guessed bound):
/// the index's answers equal the tree query's (ids, order, distances) and
/// brute force's distances. Returns how many did not.
int walk_differences(const std::vector<Vec3>& points, int queries, int k, double step, uint64_t seed) {
    const KdTree tree = reference::build_kdtree(points);
    const KnnIndex index = build_knn_index(tree);
    Rng rng(seed);
    Vec3 p = points[rng.next_u32() % points.size()];
    std::vector<Neighbor> plain, indexed;
    int differ = 0;
    for (int q = 0; q < queries; ++q) {
        // Every fifth query jumps back onto a stored point (zero distance, ties).
        p = q % 5 == 4 ? points[rng.next_u32() % points.size()]
                       : p + step * Vec3(rng.next_1d() - 0.5, rng.next_1d() - 0.5, rng.next_1d() - 0.5);
        const double max_dist2 = q % 7 == 6 ? 1e-4 : 1e300;
        reference::k_nearest(tree, p, k, max_dist2, plain);
        reference::k_nearest(tree, index, p, k, max_dist2, indexed);
        std::vector<double> brute;
        for (const Vec3& x : points)
            if ((x - p).norm2() <= max_dist2) brute.push_back((x - p).norm2());
        std::sort(brute.begin(), brute.end());
        brute.resize(std::min(brute.size(), size_t(k)));
        bool same = plain.size() == indexed.size() && indexed.size() == brute.size();
        for (size_t i = 0; same && i < plain.size(); ++i)
            same = plain[i].id == indexed[i].id && plain[i].dist2 == indexed[i].dist2 && indexed[i].dist2 == brute[i];
        differ += !same;
    }
    return differ;
}

}  // namespace

// The guessed first bound (stages/knn_index.h) must not change an answer:
// on random points most queries are answered from the guess; on
// duplicates and a grid (ties everywhere) many fall back to the search
// without it, and the answers still equal the tree query's, ties included.
TEST_CASE("knn index: queries from a guessed first bound give the same answers") {
    Rng rng(37);
    std::vector<Vec3> random(20000);
    for (Vec3& p : random) p = {rng.next_1d(), rng.next_1d(), rng.next_1d()};
    KnnGuessCounts before = knn_guess_counts();
    CHECK(walk_differences(random, 2000, 50, 0.02, 1) == 0);
    KnnGuessCounts after = knn_guess_counts();
    const uint64_t guessed = after.guessed - before.guessed, fell_back = after.fell_back - before.fell_back;
    // 2000 queries, every fifth on a stored point and every seventh with a
    // small radius: well over half start from a guess, and most of those
    // stand (a few percent fell back when this was written).
    CHECK(guessed > 1000);
    CHECK(fell_back * 5 < guessed);

    std::vector<Vec3> duplicates(3000, Vec3(0.5, 0.5, 0.5));
    for (int i = 0; i < 3000; ++i) duplicates.push_back({rng.next_1d(), rng.next_1d(), rng.next_1d()});
    std::vector<Vec3> grid;
    for (int x = 0; x < 16; ++x)
        for (int y = 0; y < 16; ++y)
            for (int z = 0; z < 16; ++z) grid.push_back({x * 0.0625, y * 0.0625, z * 0.0625});
    before = knn_guess_counts();
    CHECK(walk_differences(duplicates, 1000, 50, 0.05, 2) == 0);
    CHECK(walk_differences(grid, 1000, 30, 0.05, 3) == 0);
    CHECK(walk_differences(grid, 500, 7, 0.0, 4) == 0);  // standing still between jumps: the same k-th distance
    after = knn_guess_counts();
    CHECK(after.fell_back - before.fell_back > 100);
}

// A tie at the k-th distance only: two mirror-image points at the same
// distance from the query compete for the last place, every other distance
// differs. Which of the two the search keeps depends on the order it meets
// them, so a query from a guessed bound must fall back rather than answer.
TEST_CASE("knn index: a tie for the k-th place is broken as the tree query breaks it") {
    Rng rng(41);
    int differ = 0, trials = 0;
    std::vector<Neighbor> plain, indexed;
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<Vec3> points(2000);
        for (Vec3& p : points) p = {rng.next_1d() - 0.5, rng.next_1d() - 0.5, rng.next_1d() - 0.5};
        const Vec3 a(0.03 + 0.01 * rng.next_1d(), 0.02 * rng.next_1d(), 0.02 * rng.next_1d());
        points.push_back(a);
        points.push_back({-a.x, a.y, a.z});  // the same squared distance from the origin, bit for bit
        const double r2 = a.norm2();
        int closer = 0;
        for (const Vec3& p : points) closer += p.norm2() < r2;
        const KdTree tree = reference::build_kdtree(points);
        const KnnIndex index = build_knn_index(tree);
        const int k = closer + 1;  // one place for the two
        // The first query leaves its k-th distance; the second starts from it.
        for (int repeat = 0; repeat < 2; ++repeat) {
            differ += !queries_agree(tree, index, Vec3(0), k, 1e300, plain, indexed);
            ++trials;
        }
    }
    CHECK(trials == 600);
    CHECK(differ == 0);
}

// The guessed query collects the points within the guess and places them
// by ranks counted on float copies of their distances (stages/knn_index.cpp).
// Two distances that differ in double but round to the same float must not
// be ordered by chance: here the k-th and the (k+1)-th nearest differ by
// about 1e-12 relative (one float), so the query must fall back and still
// answer as the tree query does. And a guess far too large for the next
// query (a sparse cloud, then a dense one) crowds the collection: those
// queries search with insertions from the guess, with the same answers.
TEST_CASE("knn index: float ranks never order two distances that round alike; crowded guesses") {
    Rng rng(43);
    int differ = 0, trials = 0;
    std::vector<Neighbor> plain, indexed;
    const KnnGuessCounts before = knn_guess_counts();
    for (int trial = 0; trial < 100; ++trial) {
        std::vector<Vec3> points(3000);
        for (Vec3& p : points) p = {rng.next_1d() - 0.5, rng.next_1d() - 0.5, rng.next_1d() - 0.5};
        // Two points just outside the 29 nearest, 1e-12 apart in distance.
        std::vector<double> d2;
        for (const Vec3& p : points) d2.push_back(p.norm2());
        std::nth_element(d2.begin(), d2.begin() + 29, d2.end());
        const double r = std::sqrt(d2[29]) * 0.999999;
        points.push_back({r, 0, 0});
        points.push_back({0, r * (1 + 1e-12), 0});
        const KdTree tree = reference::build_kdtree(points);
        const KnnIndex index = build_knn_index(tree);
        for (int repeat = 0; repeat < 2; ++repeat) {  // the second from the first's guess
            for (int k : {30, 31}) {
                differ += !queries_agree(tree, index, Vec3(0), k, 1e300, plain, indexed);
                ++trials;
            }
        }
    }
    CHECK(trials == 400);
    CHECK(differ == 0);

    // One tree: a sparse cloud in [0, 1]^3 and a dense one in [2, 2.1]^3;
    // queries alternate between the two, so every dense query's guess is
    // the sparse one's.
    std::vector<Vec3> points;
    for (int i = 0; i < 2000; ++i) points.push_back({rng.next_1d(), rng.next_1d(), rng.next_1d()});
    for (int i = 0; i < 20000; ++i)
        points.push_back({2 + 0.1 * rng.next_1d(), 2 + 0.1 * rng.next_1d(), 2 + 0.1 * rng.next_1d()});
    const KdTree tree = reference::build_kdtree(points);
    const KnnIndex index = build_knn_index(tree);
    const KnnGuessCounts middle = knn_guess_counts();
    differ = 0;
    for (int q = 0; q < 400; ++q) {
        const Vec3 p = q % 2 == 0 ? Vec3(0.2 + 0.6 * rng.next_1d(), 0.2 + 0.6 * rng.next_1d(), 0.5)
                                  : Vec3(2.02 + 0.06 * rng.next_1d(), 2.05, 2.02 + 0.06 * rng.next_1d());
        differ += !queries_agree(tree, index, p, 20, 1e300, plain, indexed);
    }
    const KnnGuessCounts after = knn_guess_counts();
    CHECK(differ == 0);
    // With AVX2 the float ties fell back (with their k = 31 the ranks
    // tie) and the dense queries were crowded; without it the guessed
    // queries all use insertions.
    if (__builtin_cpu_supports("avx2")) {
        CHECK(middle.fell_back - before.fell_back >= 100);
        CHECK(after.crowded - middle.crowded >= 150);
    }
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

namespace {

/// Every group of `tree` (the first ranges of at most kKnnGroupBelow points) with its breadth-first number.
struct GroupRange {
    size_t lo, hi;
    uint32_t h;
};
std::vector<GroupRange> tree_groups(const KdTree& tree) {
    std::vector<GroupRange> groups, todo = {{0, tree.size(), 1}};
    while (!todo.empty()) {
        const GroupRange r = todo.back();
        todo.pop_back();
        if (r.hi - r.lo <= kKnnGroupBelow) {
            groups.push_back(r);
            continue;
        }
        const size_t mid = r.lo + (r.hi - r.lo) / 2;
        todo.push_back({r.lo, mid, 2 * r.h});
        todo.push_back({mid + 1, r.hi, 2 * r.h + 1});
    }
    return groups;
}

/// The quantised filter on every group of the tree over `points`, for
/// queries near the groups and on their points, with each point's exact
/// squared distance as the bound (the hardest case: a point exactly at the
/// bound must be kept): returns how many points within the bound it
/// dropped (must be none), and adds to `dropped_far` / `far` how many
/// points beyond twice the bound it dropped / saw.
int filter_misses(const std::vector<Vec3>& points, uint64_t seed, int& dropped_far, int& far) {
    const KdTree tree = reference::build_kdtree(points);
    const KnnIndex index = build_knn_index(tree);
    REQUIRE(!index.groups.empty());
    Rng rng(seed);
    int misses = 0;
    for (const GroupRange& b : tree_groups(tree)) {
        const KnnGroup& group = index.groups[b.h - index.first_group];
        const uint32_t n = uint32_t(b.hi - b.lo);
        for (int q = 0; q < 8; ++q) {
            // On a stored point, or near one (within about the group's
            // extent), or far from the group (hundreds of its extents: the
            // query's position in steps is then clamped to 16 bits).
            const Vec3 at = tree.points[b.lo + rng.next_u32() % n];
            const Vec3 spread = tree.points[b.lo] - tree.points[b.hi - 1];
            const Vec3 p = q < 2   ? at
                           : q < 6 ? at + Vec3((rng.next_1d() - 0.5) * spread.x, (rng.next_1d() - 0.5) * spread.y,
                                               (rng.next_1d() - 0.5) * spread.z)
                                   : at + spread * (q == 6 ? 300.0 : -3000.0);
            for (uint32_t j = 0; j < n; ++j) {
                const double bound = (tree.points[b.lo + j] - p).norm2();
                if (!knn_group_filter_applies(p, bound)) continue;
                const uint64_t mask = knn_group_candidates(group, n, p, bound);
                for (uint32_t i = 0; i < n; ++i) {
                    const double d2 = (tree.points[b.lo + i] - p).norm2();
                    const bool kept = (mask >> i) & 1;
                    misses += d2 <= bound && !kept;
                    if (d2 > 2 * bound) {
                        ++far;
                        dropped_far += !kept;
                    }
                }
            }
        }
    }
    return misses;
}

}  // namespace

// The quantised groups (stages/knn_index.h) only filter: a point within
// the bound must never be dropped, whatever the rounding (coordinates far
// from the origin with tiny spreads, duplicates, a plane, one outlier that
// makes a group's step coarse); and the filter must drop most points
// beyond twice the bound on random points (else it saves nothing).
TEST_CASE("knn index: the quantised groups never drop a point within the bound") {
    if (!__builtin_cpu_supports("avx2")) return;  // the filter is used with AVX2 only
    Rng rng(41);
    int dropped_far = 0, far = 0;
    std::vector<Vec3> random(3000);
    for (Vec3& p : random) p = {rng.next_1d(), rng.next_1d(), rng.next_1d()};
    CHECK(filter_misses(random, 1, dropped_far, far) == 0);
    // At least 90% of the points beyond twice the bound are dropped.
    CHECK(dropped_far >= 0.9 * far);
    CHECK(far > 10000);

    std::vector<Vec3> offset(2000);  // 1000 + 10^-9 spreads: float cannot hold the points
    for (Vec3& p : offset) p = {1000 + 1e-9 * rng.next_1d(), -1000 + 1e-9 * rng.next_1d(), 1e-9 * rng.next_1d()};
    std::vector<Vec3> duplicates(400, Vec3(0.3, 0.6, 0.9));
    for (int i = 0; i < 40; ++i) duplicates.push_back({rng.next_1d(), rng.next_1d(), rng.next_1d()});
    std::vector<Vec3> plane(2000);
    for (Vec3& p : plane) p = {rng.next_1d(), 0.1, rng.next_1d()};
    std::vector<Vec3> outliers(2000);
    for (size_t i = 0; i < outliers.size(); ++i)
        outliers[i] = i % 16 == 0 ? Vec3(1e6 * rng.next_1d(), 0, 0) : Vec3(1e-3 * rng.next_1d(), 1e-3 * rng.next_1d(), 0);
    std::vector<Vec3> large(2000);  // near the filter's range (10^18)
    for (Vec3& p : large) p = {1e17 * rng.next_1d(), -1e17 * rng.next_1d(), 1e17 + 1e7 * rng.next_1d()};
    int unused = 0;
    for (const auto* points : {&offset, &duplicates, &plane, &outliers, &large})
        CHECK(filter_misses(*points, 2, unused, unused) == 0);

    // Whole queries through the filter agree with the tree query there too.
    check_same_answers(offset, 200, 8);
    check_same_answers(outliers, 200, 9);
    CHECK(walk_differences(offset, 300, 20, 1e-10, 10) == 0);
    CHECK(walk_differences(random, 300, 50, 0.5, 11) == 0);

    // Out of the filter's range: no groups, the queries still agree.
    std::vector<Vec3> huge = random;
    huge[7] = {1e20, 0, 0};
    CHECK(build_knn_index(reference::build_kdtree(huge)).groups.empty());
    check_same_answers(huge, 100, 12);
}

// A walk from a dense cloud into one 1.5 times sparser: the guess from the
// dense side is too small for some queries on the sparse side, which
// collect again from 1.5 times it; the answers still equal the tree
// query's (ids, order, distances).
TEST_CASE("knn index: a guess too small is collected again with the same answers") {
    Rng rng(43);
    std::vector<Vec3> points;
    for (int i = 0; i < 9000; ++i) points.push_back({rng.next_1d(), rng.next_1d(), rng.next_1d()});
    for (int i = 0; i < 6000; ++i) points.push_back({1 + rng.next_1d(), rng.next_1d(), rng.next_1d()});
    const KdTree tree = reference::build_kdtree(points);
    const KnnIndex index = build_knn_index(tree);
    const KnnGuessCounts before = knn_guess_counts();
    std::vector<Neighbor> plain, indexed;
    int agree = 0;
    const int queries = 2000;
    for (int q = 0; q < queries; ++q) {
        // Far apart (the quantised groups) or close (the bucket scan), alternately in runs.
        const double jitter = (q / 50) % 2 == 0 ? 0.3 : 0.01;
        const Vec3 p(0.1 + 1.8 * q / queries, 0.5 + jitter * (rng.next_1d() - 0.5), 0.5 + jitter * (rng.next_1d() - 0.5));
        agree += queries_agree(tree, index, p, 30, 1e300, plain, indexed);
    }
    CHECK(agree == queries);
    if (__builtin_cpu_supports("avx2")) {
        const KnnGuessCounts after = knn_guess_counts();
        CHECK(after.retried - before.retried >= 20);
    }
}
