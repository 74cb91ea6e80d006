// Building the reference BVH (stages/flat_bvh.h): top-down, depth-first,
// one node at a time, with binned SAH, median or middle splits.
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstring>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "core/error.h"
#include "scene/scene.h"
#include "stages/bvh.h"
#include "stages/flat_bvh.h"
#include "stages/stages.h"

namespace pt {

BvhSplit parse_bvh_split(const std::string& name) {
    if (name == "sah") return BvhSplit::sah;
    if (name == "median") return BvhSplit::median;
    if (name == "middle") return BvhSplit::middle;
    throw InputError("--bvh-split: expected one of sah, median, middle, got '" + name + "'");
}

const char* to_string(BvhSplit split) {
    switch (split) {
        case BvhSplit::sah:
            return "sah";
        case BvhSplit::median:
            return "median";
        case BvhSplit::middle:
            return "middle";
    }
    return "?";
}

void round_box_outward(const BBox& box, float lo[3], float hi[3]) {
    for (int a = 0; a < 3; ++a) {
        lo[a] = float_down(box.min[a]);
        hi[a] = float_up(box.max[a]);
    }
}

namespace {

// SAH costs (flat_bvh.h, "Leaf cost model"), relative to one triangle test.
constexpr double kTraversalCost = 1.0;
constexpr double kIntersectionCost = 1.0;
constexpr int kBins = 16;
// Nodes of fewer primitives are split by an exact sweep instead of bins.
constexpr int kSweepBelow = 16;
// Nodes of at least this many primitives are binned with two sets of bins
// (Builder::bin_two_sets); smaller ones with one, which saves clearing and
// merging the second set.
constexpr size_t kTwoBinSetsFrom = 256;
// Nodes of at most this many primitives are partitioned out of place
// (32 bytes each, twice: 256 KB, within the 2 MB L2).
constexpr size_t kOutOfPlaceBelow = 4096;
// Below this depth every split is an object median (flat_bvh.h, "Robustness").
constexpr int kMedianDepth = 48;
// SAH: a node of at most this many primitives (and at most max_leaf) is a
// leaf without weighing a split. Embree's leaves hold up to four triangles
// too; the build makes about half the nodes and runs 10 to 20% faster, and
// the 8-wide BVH tests such a leaf's triangles four at a time
// (bvh_leaf_block.h), so the rays do not pay for the larger leaves (docs/bvh.md).
constexpr size_t kForcedLeaf = 4;
// The SAH counts a side's primitives in leaf blocks of four (rounded up),
// as the 8-wide BVH tests them (bvh_leaf_block.h) and as Embree's builder
// does for its four-triangle leaves: splits that fill whole blocks win.
inline uint32_t blocks(uint32_t count) { return (count + 3) / 4; }

// The build works on 4-float vectors (GCC's vector extensions: SSE on
// x86-64, plain code elsewhere): x, y, z and an unused fourth lane. Binning
// is most of the build time, and with vectors one min and one max grow a
// box, and one subtract, multiply and convert give a centroid's bins on all
// three axes at once (as Embree's binner does; Wald 2007).
typedef float F4 __attribute__((vector_size(16)));
typedef int32_t I4 __attribute__((vector_size(16)));

/// MINPS and MAXPS: b when either is NaN. Through the intrinsics on x86:
/// inlined, GCC compiled the selects below as a compare and three logic
/// operations in most places (111 of them), not as one MINPS or MAXPS.
#if defined(__SSE__)
inline F4 vmin(F4 a, F4 b) { return F4(_mm_min_ps(__m128(a), __m128(b))); }
inline F4 vmax(F4 a, F4 b) { return F4(_mm_max_ps(__m128(a), __m128(b))); }
#else
inline F4 vmin(F4 a, F4 b) { return a < b ? a : b; }
inline F4 vmax(F4 a, F4 b) { return a > b ? a : b; }
#endif

/// One primitive during the build, 32 bytes (the old 48-byte record with a
/// stored centroid moved 1.5 times the memory in every partition): its
/// float box rounded outward, and its id in the first vector's fourth lane.
struct alignas(32) PrimRef {
    F4 lo;  ///< x, y, z bounds; lane 3 holds the id's bits
    F4 hi;  ///< lane 3 is 0
    uint32_t id() const {
        uint32_t i;
        float f = lo[3];
        std::memcpy(&i, &f, sizeof i);
        return i;
    }
};
static_assert(sizeof(PrimRef) == 32, "a build primitive is 32 bytes");

/// lo with its fourth lane (the id) cleared.
inline F4 lo_xyz(const PrimRef& p) {
    const I4 mask = {-1, -1, -1, 0};
    return F4(I4(p.lo) & mask);
}

/// The centroid used to bin and split: the float box's midpoint, clamped to
/// the finite floats (a box reaching +-inf, in a scene beyond float range,
/// gets a finite centroid; NaN becomes FLT_MAX). Only decides sides, so
/// any consistent value is correct; the same function serves binning and
/// partitioning, so both put a primitive on the same side.
inline F4 centroid(const PrimRef& p) {
    F4 c = (lo_xyz(p) + p.hi) * 0.5f;
    const F4 big = {FLT_MAX, FLT_MAX, FLT_MAX, FLT_MAX};
    return vmax(vmin(c, big), -big);  // NaN: vmin gives big
}

/// A float box that grows; empty when lo > hi. Lane 3 is ignored.
struct Box4 {
    F4 lo = {INFINITY, INFINITY, INFINITY, INFINITY};
    F4 hi = {-INFINITY, -INFINITY, -INFINITY, -INFINITY};

    void expand(F4 l, F4 h) {
        lo = vmin(l, lo);
        hi = vmax(h, hi);
    }
    void expand(F4 p) { expand(p, p); }
    void expand(const Box4& b) { expand(b.lo, b.hi); }
    /// Surface area in double precision (float could overflow); 0 when empty.
    double area() const {
        if (lo[0] > hi[0]) return 0.0;
        double ex = double(hi[0]) - lo[0], ey = double(hi[1]) - lo[1], ez = double(hi[2]) - lo[2];
        return 2.0 * (ex * ey + ey * ez + ez * ex);
    }
    /// area() without a branch (a select instead), for the sweeps.
    double area_or_zero() const {
        double ex = double(hi[0]) - lo[0], ey = double(hi[1]) - lo[1], ez = double(hi[2]) - lo[2];
        const double a = 2.0 * (ex * ey + ey * ez + ez * ex);
        return lo[0] > hi[0] ? 0.0 : a;
    }
    int widest_axis() const {
        F4 e = hi - lo;
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (e[a] > e[axis]) axis = a;
        return axis;
    }
};

/// Where to split a node, or that it is a leaf; with the SAH, also the
/// children's boxes (the sweep's unions of bins), so no extra pass computes them.
struct SplitChoice {
    bool leaf = false;
    bool boxes_known = false;  ///< left/right and their centroid boxes are set
    int axis = 0;
    size_t mid = 0;  ///< the left child gets [begin, mid), the right [mid, end)
    Box4 left, right, left_centroids, right_centroids;
};

/// Maps centroids to bins: bin = floor((c - origin) * scale), clamped to
/// [0, kBins - 1], on the three axes at once.
struct Binner {
    F4 origin, scale;
    Binner(const Box4& centroids) {
        origin = centroids.lo;
        F4 extent = centroids.hi - centroids.lo;
        for (int a = 0; a < 4; ++a) scale[a] = a < 3 && extent[a] > 0 ? kBins / extent[a] : 0.0f;
    }
    /// (c - origin) * scale clamped to [0, kBins - 1] (NaN to 0).
    F4 position(F4 c) const {
        const F4 zero = {0, 0, 0, 0}, top = {kBins - 1, kBins - 1, kBins - 1, kBins - 1};
        return vmin(vmax((c - origin) * scale, zero), top);
    }
    I4 bins(F4 c) const { return __builtin_convertvector(position(c), I4); }
};

/// float_down and float_up (flat_bvh.h) with a select instead of a branch
/// on "did float() round the wrong way", which is a coin toss per
/// coordinate: the same results, 6 mispredictions fewer per primitive.
/// The step to the next float is next_float_down / next_float_up's with
/// selects for their special cases, as far as the step is ever taken: only
/// when float(x) lies beyond x, so never down from -inf, up from +inf or from
/// NaN; from +-0 to the smallest denormal of x's sign.
inline float round_down(double x) {
    const float f = float(x);
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    bits = f > 0 ? bits - 1 : f == 0 ? 0x80000001u : bits + 1;
    float d;
    std::memcpy(&d, &bits, sizeof d);
    return double(f) > x ? d : f;
}
inline float round_up(double x) {
    const float f = float(x);
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    bits = f > 0 ? bits + 1 : f == 0 ? 0x00000001u : bits - 1;
    float u;
    std::memcpy(&u, &bits, sizeof u);
    return double(f) < x ? u : f;
}

class Builder {
  public:
    Builder(std::vector<PrimRef> prims, int max_leaf, BvhSplit split, FlatBvh& out)
        : prims_(std::move(prims)), scratch_(std::min(prims_.size(), kOutOfPlaceBelow)), max_leaf_(size_t(max_leaf)), split_(split), out_(out) {}

    /// The boxes of prims_[begin, end) and of their centroids.
    void bounds(size_t begin, size_t end, Box4& box, Box4& centroids) const {
        box = Box4();
        centroids = Box4();
        for (size_t i = begin; i < end; ++i) {
            box.expand(prims_[i].lo, prims_[i].hi);
            centroids.expand(centroid(prims_[i]));
        }
    }

    /// Emits the subtree over prims_[begin, end), whose box and centroid box
    /// are given, at the end of out_.nodes and returns the index of its root.
    uint32_t build(size_t begin, size_t end, int depth, const Box4& box, const Box4& centroids) {
        const uint32_t index = uint32_t(out_.nodes.size());
        out_.nodes.emplace_back();
        out_.depth = std::max(out_.depth, depth);
        for (int a = 0; a < 3; ++a) {
            out_.nodes[index].bounds[a] = box.lo[a];
            out_.nodes[index].bounds[3 + a] = box.hi[a];
        }

        SplitChoice choice = choose_split(begin, end, depth, box, centroids);
        if (choice.leaf) {
            FlatBvhNode& node = out_.nodes[index];
            node.offset = uint32_t(out_.primitives.size());
            node.count = uint16_t(end - begin);
            for (size_t i = begin; i < end; ++i)
                out_.primitives.push_back(prims_[i].id());
            return index;
        }
        if (!choice.boxes_known) {
            bounds(begin, choice.mid, choice.left, choice.left_centroids);
            bounds(choice.mid, end, choice.right, choice.right_centroids);
        }
        // Depth-first: the left child is the next node; the right child's
        // index is known only once the left subtree is complete.
        build(begin, choice.mid, depth + 1, choice.left, choice.left_centroids);
        uint32_t right = build(choice.mid, end, depth + 1, choice.right, choice.right_centroids);
        out_.nodes[index].offset = right;
        out_.nodes[index].axis = uint8_t(choice.axis);
        return index;
    }

  private:
    SplitChoice choose_split(size_t begin, size_t end, int depth, const Box4& box, const Box4& centroids) {
        const size_t n = end - begin;
        SplitChoice choice;
        if (n == 1) {
            choice.leaf = true;
            return choice;
        }
        const int axis = centroids.widest_axis();
        choice.axis = axis;
        if (!(centroids.hi[axis] > centroids.lo[axis])) {
            // All centroids coincide: no plane separates them. Keep leaves
            // small anyway by halving the list (both halves share one box).
            choice.leaf = n <= max_leaf_;
            choice.mid = begin + n / 2;
            return choice;
        }
        if (depth >= kMedianDepth || split_ == BvhSplit::median) {
            if (n <= max_leaf_)
                choice.leaf = true;
            else
                choice.mid = median_split(begin, end, axis);
            return choice;
        }
        if (split_ == BvhSplit::middle) {
            if (n <= max_leaf_) {
                choice.leaf = true;
                return choice;
            }
            float pivot = centroids.lo[axis] + 0.5f * (centroids.hi[axis] - centroids.lo[axis]);
            auto mid = std::partition(prims_.begin() + long(begin), prims_.begin() + long(end),
                                      [&](const PrimRef& p) { return centroid(p)[axis] < pivot; });
            choice.mid = size_t(mid - prims_.begin());
            // The midpoint can round onto the largest centroid: then halve by count.
            if (choice.mid == begin || choice.mid == end)
                choice.mid = median_split(begin, end, axis);
            return choice;
        }
        if (n <= std::min(kForcedLeaf, max_leaf_)) {
            choice.leaf = true;
            return choice;
        }
        if (n < size_t(kSweepBelow) && box.area() > 0) return sweep_split(begin, end, box);
        return sah_split(begin, end, box, centroids);
    }

    /// sweep_split for two primitives (the most common small node): every
    /// axis offers the same one split, so the sweep's answer is axis 0's
    /// order and the same cost, found without sorting.
    SplitChoice pair_split(size_t begin, PrimRef* p, const F4* c, double parent_area) {
        SplitChoice choice;
        Box4 first, second;
        first.expand(p[0].lo, p[0].hi);
        second.expand(p[1].lo, p[1].hi);
        const double cost = kTraversalCost + kIntersectionCost * (first.area() + second.area()) / parent_area;
        if (2 <= max_leaf_ && kIntersectionCost * 2.0 <= cost) {
            choice.leaf = true;
            return choice;
        }
        const bool swap = c[1][0] < c[0][0];  // the sweep's order on axis 0 (ties keep positions)
        if (swap) std::swap(p[0], p[1]);
        choice.left = swap ? second : first;
        choice.right = swap ? first : second;
        choice.left_centroids.expand(c[swap ? 1 : 0]);
        choice.right_centroids.expand(c[swap ? 0 : 1]);
        choice.axis = 0;
        choice.mid = begin + 1;
        choice.boxes_known = true;
        return choice;
    }

    /// Exact object-split SAH for a small node: on each axis the primitives
    /// sorted by centroid and every one of the n - 1 splits of that order
    /// weighed (the sweep of Wald, Boulos and Shirley 2007). Cheaper than
    /// binning here (no 48 bins to clear and sweep per node; about half the
    /// nodes have at most four primitives) and never a worse split than the
    /// bins would find, which can only offer a subset of these splits.
    SplitChoice sweep_split(size_t begin, size_t end, const Box4& box) {
        const int n = int(end - begin);
        PrimRef* p = prims_.data() + begin;
        F4 c[kSweepBelow];
        for (int i = 0; i < n; ++i) c[i] = centroid(p[i]);
        const double parent_area = box.area();
        if (n == 2) return pair_split(begin, p, c, parent_area);
        double best_cost = INFINITY;
        int best_axis = 0, best_k = 0;
        // Sorted by centroid on each axis, ties by position, through each
        // one's rank (how many come before it): no branches, which an
        // insertion sort's mispredictions made the larger cost here. The
        // ranks on the three axes at once, one vector lane per axis: j
        // comes before i when c[j] < c[i], or c[j] == c[i] and j < i, that
        // is c[j] <= c[i] for j < i and c[j] < c[i] for j > i (centroids are
        // never NaN). A true comparison is all ones (-1), hence the minus.
        uint8_t order[3][kSweepBelow];
        for (int i = 0; i < n; ++i) {
            I4 rank = {0, 0, 0, 0};
            for (int j = 0; j < i; ++j) rank -= I4(c[j] <= c[i]);
            for (int j = i + 1; j < n; ++j) rank -= I4(c[j] < c[i]);
            for (int a = 0; a < 3; ++a) order[a][rank[a]] = uint8_t(i);
        }
        for (int a = 0; a < 3; ++a) {
            const uint8_t* o = order[a];
            double right_area[kSweepBelow];
            Box4 right;
            for (int k = n - 1; k > 0; --k) {
                right.expand(p[o[k]].lo, p[o[k]].hi);
                right_area[k] = right.area();
            }
            Box4 left;
            for (int k = 1; k < n; ++k) {  // left: o[0 .. k), right: o[k .. n)
                left.expand(p[o[k - 1]].lo, p[o[k - 1]].hi);
                double cost = kTraversalCost +
                              kIntersectionCost * (left.area() * blocks(uint32_t(k)) + right_area[k] * blocks(uint32_t(n - k))) / parent_area;
                const bool better = cost < best_cost;  // selects, not a branch
                best_cost = better ? cost : best_cost;
                best_axis = better ? a : best_axis;
                best_k = better ? k : best_k;
            }
        }
        SplitChoice choice;
        if (size_t(n) <= max_leaf_ && kIntersectionCost * double(n) <= best_cost) {
            choice.leaf = true;
            return choice;
        }
        // Reorder the primitives as the best axis sorted them.
        PrimRef sorted[kSweepBelow];
        for (int i = 0; i < n; ++i) sorted[i] = p[order[best_axis][i]];
        for (int i = 0; i < n; ++i) {
            p[i] = sorted[i];
            Box4& b = i < best_k ? choice.left : choice.right;
            b.expand(sorted[i].lo, sorted[i].hi);
            (i < best_k ? choice.left_centroids : choice.right_centroids).expand(c[order[best_axis][i]]);
        }
        choice.axis = best_axis;
        choice.mid = begin + size_t(best_k);
        choice.boxes_known = true;
        return choice;
    }

    size_t median_split(size_t begin, size_t end, int axis) {
        size_t mid = begin + (end - begin) / 2;
        std::nth_element(prims_.begin() + long(begin), prims_.begin() + long(mid), prims_.begin() + long(end),
                         [axis](const PrimRef& a, const PrimRef& b) { return centroid(a)[axis] < centroid(b)[axis]; });
        return mid;
    }

    /// Bins prims_[begin, end) into `bins` and `counts` (empty on entry)
    /// with two sets of bins, for even and odd primitives, merged at the
    /// end: neighbouring primitives usually fall into the same bins, and
    /// with one set each update would wait for the previous one's store.
    /// The same bins as one set (min, max and sums do not depend on order).
    void bin_two_sets(size_t begin, size_t end, const Binner& binner, Box4 (&bins)[3][kBins],
                      uint32_t (&counts)[3][kBins]) const {
        Box4 odd[3][kBins];
        uint32_t odd_counts[3][kBins] = {};
        size_t i = begin;
        for (; i + 1 < end; i += 2) {
            const PrimRef& p = prims_[i];
            const PrimRef& q = prims_[i + 1];
            const I4 b = binner.bins(centroid(p));
            const I4 d = binner.bins(centroid(q));
            for (int a = 0; a < 3; ++a) {
                bins[a][b[a]].expand(p.lo, p.hi);
                ++counts[a][b[a]];
                odd[a][d[a]].expand(q.lo, q.hi);
                ++odd_counts[a][d[a]];
            }
        }
        if (i < end) {
            const I4 b = binner.bins(centroid(prims_[i]));
            for (int a = 0; a < 3; ++a) {
                bins[a][b[a]].expand(prims_[i].lo, prims_[i].hi);
                ++counts[a][b[a]];
            }
        }
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < kBins; ++k) {
                bins[a][k].expand(odd[a][k]);
                counts[a][k] += odd_counts[a][k];
            }
    }

    /// Binned SAH (Wald 2007): one pass drops every centroid into one of
    /// kBins equal slices of the centroid bounds on each axis; sweeps over
    /// the bins then give the cost of all kBins - 1 planes per axis.
    SplitChoice sah_split(size_t begin, size_t end, const Box4& box, const Box4& centroids) {
        const size_t n = end - begin;
        Box4 bins[3][kBins];
        uint32_t counts[3][kBins] = {};
        const Binner binner(centroids);
        if (n >= kTwoBinSetsFrom) bin_two_sets(begin, end, binner, bins, counts);
        else
            for (size_t i = begin; i < end; ++i) {
                const I4 b = binner.bins(centroid(prims_[i]));
                for (int a = 0; a < 3; ++a) {
                    bins[a][b[a]].expand(prims_[i].lo, prims_[i].hi);
                    ++counts[a][b[a]];
                }
            }

        double parent_area = box.area();
        double best_cost = INFINITY;
        int best_axis = -1, best_plane = 0;
        for (int a = 0; a < 3; ++a) {
            if (binner.scale[a] == 0.0f) continue;
            // right_area[k], right_count[k]: everything in bins k .. kBins-1.
            // Both sweeps take every bin and every plane without a branch:
            // which bins of a small node are empty is a coin toss the branch
            // predictor loses (the sweep cost as much as binning the
            // primitives at 16 to 63 of them). An empty bin leaves the box
            // as it was, so the same bits as skipping it.
            double right_area[kBins];
            uint32_t right_count[kBins];
            Box4 right;
            uint32_t count = 0;
            for (int k = kBins - 1; k > 0; --k) {
                right.expand(bins[a][k]);
                count += counts[a][k];
                right_area[k] = right.area_or_zero();
                right_count[k] = count;
            }
            Box4 left;
            count = 0;
            for (int k = 1; k < kBins; ++k) {  // the plane between bins k-1 and k
                left.expand(bins[a][k - 1]);
                count += counts[a][k - 1];
                const double cost = kTraversalCost + kIntersectionCost *
                                                         (left.area_or_zero() * blocks(count) +
                                                          right_area[k] * blocks(right_count[k])) /
                                                         parent_area;
                // A plane with an empty side splits nothing. One just past an
                // empty bin splits as the plane before it did, at the same
                // cost, which `<` never prefers: no need to skip it.
                const bool better = (count > 0) & (right_count[k] > 0) & (cost < best_cost);
                best_cost = better ? cost : best_cost;
                best_axis = better ? a : best_axis;
                best_plane = better ? k : best_plane;
            }
        }

        SplitChoice choice;
        // A box of zero area (collinear primitives) gives the SAH nothing to
        // weigh; halve by count then.
        if (best_axis < 0 || !(parent_area > 0)) {
            const int axis = centroids.widest_axis();
            choice.leaf = n <= max_leaf_;
            choice.axis = axis;
            if (!choice.leaf) choice.mid = median_split(begin, end, axis);
            return choice;
        }
        if (n <= max_leaf_ && kIntersectionCost * double(n) <= best_cost) {
            choice.leaf = true;
            return choice;
        }
        // The children's boxes are the unions of their bins; their centroid
        // boxes are gathered while partitioning (Hoare's scheme: swap the
        // first right-side primitive from the front with the last left-side
        // one from the back).
        const int a = best_axis;
        for (int k = 0; k < kBins; ++k) (k < best_plane ? choice.left : choice.right).expand(bins[a][k]);
        PrimRef* lo = prims_.data() + begin;
        PrimRef* hi = prims_.data() + end;
        // The axis as a constant: its lane is read without a trip through
        // memory. Out of place while the node fits in L2 with its copy;
        // beyond that the extra memory traffic costs more than the
        // mispredictions it saves (measured: the 1M knot 6% slower, the
        // bunny 10% faster, out of place throughout).
        const bool small = n <= kOutOfPlaceBelow;
        switch (a) {
            case 0: lo = small ? partition<0>(lo, hi, binner, best_plane, choice) : hoare<0>(lo, hi, binner, best_plane, choice); break;
            case 1: lo = small ? partition<1>(lo, hi, binner, best_plane, choice) : hoare<1>(lo, hi, binner, best_plane, choice); break;
            default: lo = small ? partition<2>(lo, hi, binner, best_plane, choice) : hoare<2>(lo, hi, binner, best_plane, choice); break;
        }
        choice.axis = a;
        choice.mid = size_t(lo - prims_.data());
        choice.boxes_known = true;
        return choice;
    }

    /// Hoare's in-place partition of [lo, hi), as `partition` below.
    template <int A>
    static PrimRef* hoare(PrimRef* lo, PrimRef* hi, const Binner& binner, int plane, SplitChoice& choice) {
        const float limit = float(plane);
        auto side = [&](F4 c) { return binner.position(c)[A] < limit; };
        while (true) {
            F4 c;
            while (lo < hi && side(c = centroid(*lo))) {
                choice.left_centroids.expand(c);
                ++lo;
            }
            while (lo < hi && !side(c = centroid(*(hi - 1)))) {
                choice.right_centroids.expand(c);
                --hi;
            }
            if (lo == hi) return lo;
            std::swap(*lo, *(hi - 1));
        }
    }

    /// Partition of [lo, hi) by the bin on axis A (left: below `plane`),
    /// gathering both sides' centroid boxes; returns the first primitive of
    /// the right side. Out of place and without branches: each primitive is
    /// written to both ends of scratch_ (the left side grows from the front,
    /// the right from the back; the copy on the wrong side is overwritten
    /// later) and the side only moves the counts, because which side a
    /// primitive falls on is a coin toss the branch predictor loses about
    /// half the time in Hoare's in-place scheme.
    template <int A>
    PrimRef* partition(PrimRef* lo, PrimRef* hi, const Binner& binner, int plane, SplitChoice& choice) {
        // Binner::bins without the conversion: for x in [0, kBins - 1],
        // int(x) < plane exactly when x < plane.
        const float limit = float(plane);
        const size_t n = size_t(hi - lo);
        PrimRef* out = scratch_.data();
        size_t left = 0, right = n;  // out[0, left): left side; out[right, n): right side
        const F4 inf = {INFINITY, INFINITY, INFINITY, INFINITY};
        F4 llo = inf, lhi = -inf, rlo = inf, rhi = -inf;
        const F4 limits = {limit, limit, limit, limit};
        for (PrimRef* p = lo; p < hi; ++p) {
            const F4 c = centroid(*p);
            // The side as a mask in all four lanes, all ones on the left:
            // compared and broadcast in vector registers (through a general
            // register and back, it was the loop's longest chain).
            const I4 m = __builtin_shuffle(binner.position(c) < limits, I4{A, A, A, A});
            const size_t is_left = size_t(m[0] & 1);
            out[left] = *p;
            out[right - 1] = *p;
            left += is_left;
            right -= 1 - is_left;
            llo = vmin(F4((I4(c) & m) | (I4(inf) & ~m)), llo);
            lhi = vmax(F4((I4(c) & m) | (I4(-inf) & ~m)), lhi);
            rlo = vmin(F4((I4(c) & ~m) | (I4(inf) & m)), rlo);
            rhi = vmax(F4((I4(c) & ~m) | (I4(-inf) & m)), rhi);
        }
        choice.left_centroids.expand(llo, lhi);
        choice.right_centroids.expand(rlo, rhi);
        std::memcpy(static_cast<void*>(lo), out, n * sizeof(PrimRef));
        return lo + left;
    }

    std::vector<PrimRef> prims_;
    std::vector<PrimRef> scratch_;  ///< partition's output, as long as prims_
    size_t max_leaf_;
    BvhSplit split_;
    FlatBvh& out_;
};

}  // namespace

FlatBvh build_flat_bvh(const Scene& scene, const AcceleratorSettings& settings) {
    FlatBvh out;
    out.split = parse_bvh_split(settings.split);
    if (settings.max_leaf < 1 || settings.max_leaf > 255)
        throw InputError("--max-leaf: expected a whole number in [1, 255], got " +
                         std::to_string(settings.max_leaf));
    const uint32_t n = scene.primitive_count();
    if (n == 0) return out;

    // Reserved, not sized: sizing would first zero them all.
    std::vector<PrimRef> prims;
    prims.reserve(n);
    Box4 box, centroids;
    for (uint32_t i = 0; i < n; ++i) {
        BBox b;
        if (scene.is_sphere(i)) {
            b = padded_primitive_bounds(scene, i);
        } else {
            // padded_primitive_bounds inlined for triangles (the same
            // operations: x * 2^-32 is ldexp(x, -32), both exact or
            // correctly rounded), without copying the triangle's normals.
            const TriangleRecord& r = scene.triangles[i];
            b = BBox(scene.positions[r.v[0]], scene.positions[r.v[1]]);
            b.expand(scene.positions[r.v[2]]);
            double scale = std::max(max_component(abs(b.min)), max_component(abs(b.max)));
            Vec3 margin(scale * 0x1p-32);
            b = BBox(b.min - margin, b.max + margin);
        }
        float id;
        std::memcpy(&id, &i, sizeof id);
        const PrimRef& p = prims.emplace_back(
            PrimRef{F4{round_down(b.min.x), round_down(b.min.y), round_down(b.min.z), id},
                    F4{round_up(b.max.x), round_up(b.max.y), round_up(b.max.z), 0.0f}});
        box.expand(p.lo, p.hi);
        centroids.expand(centroid(p));
    }
    // At most 2n - 1 nodes: reserving them keeps emplace_back from copying.
    out.nodes.reserve(2 * size_t(n) - 1);
    out.primitives.reserve(n);
    Builder builder(std::move(prims), settings.max_leaf, out.split, out);
    builder.build(0, n, 0, box, centroids);
    // Not shrunk here: the wide BVHs collapse and drop these nodes at once
    // (a shrinking copy was 1 to 2% of their build); the binary one shrinks them.
    return out;
}

}  // namespace pt
