// Building the reference BVH (stages/flat_bvh.h): top-down, depth-first,
// one node at a time, with binned SAH, median or middle splits.
#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

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
// Below this depth every split is an object median (flat_bvh.h, "Robustness").
constexpr int kMedianDepth = 48;

// Boxes during the build have a fourth, unused lane, so that the compiler
// can grow them with 4-wide vector min/max instructions (binning is most of
// the build time).

/// One primitive during the build: its float box, its centroid, its id.
struct BuildPrimitive {
    alignas(16) float lo[4];  ///< bounds, rounded outward (lane 3 unused)
    alignas(16) float hi[4];
    float c[3];   ///< centroid (only decides the side of a split)
    uint32_t id;  ///< primitive id in the scene
};

/// A float box that grows; empty when lo > hi.
struct FloatBox {
    alignas(16) float lo[4] = {INFINITY, INFINITY, INFINITY, INFINITY};
    alignas(16) float hi[4] = {-INFINITY, -INFINITY, -INFINITY, -INFINITY};

    void expand(const float l[4], const float h[4]) {
        for (int a = 0; a < 4; ++a) {
            lo[a] = l[a] < lo[a] ? l[a] : lo[a];
            hi[a] = h[a] > hi[a] ? h[a] : hi[a];
        }
    }
    void expand(const FloatBox& b) { expand(b.lo, b.hi); }
    /// Surface area in double precision (float could overflow); 0 when empty.
    double area() const {
        if (lo[0] > hi[0]) return 0.0;
        double ex = double(hi[0]) - lo[0], ey = double(hi[1]) - lo[1], ez = double(hi[2]) - lo[2];
        return 2.0 * (ex * ey + ey * ez + ez * ex);
    }
};

/// Where to split a node, or that it is a leaf.
struct SplitChoice {
    bool leaf = false;
    int axis = 0;
    size_t mid = 0;  ///< the left child gets [begin, mid), the right [mid, end)
};

class Builder {
  public:
    Builder(std::vector<BuildPrimitive> prims, int max_leaf, BvhSplit split, FlatBvh& out)
        : prims_(std::move(prims)), max_leaf_(size_t(max_leaf)), split_(split), out_(out) {}

    /// Emits the subtree over prims_[begin, end) at the end of out_.nodes
    /// and returns the index of its root.
    uint32_t build(size_t begin, size_t end, int depth) {
        const uint32_t index = uint32_t(out_.nodes.size());
        out_.nodes.emplace_back();
        out_.depth = std::max(out_.depth, depth);

        FloatBox box, centroids;
        for (size_t i = begin; i < end; ++i) {
            box.expand(prims_[i].lo, prims_[i].hi);
            const float c[4] = {prims_[i].c[0], prims_[i].c[1], prims_[i].c[2], 0.0f};
            centroids.expand(c, c);
        }
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
                out_.primitives.push_back(prims_[i].id);
            return index;
        }
        // Depth-first: the left child is the next node; the right child's
        // index is known only once the left subtree is complete.
        build(begin, choice.mid, depth + 1);
        uint32_t right = build(choice.mid, end, depth + 1);
        out_.nodes[index].offset = right;
        out_.nodes[index].axis = uint8_t(choice.axis);
        return index;
    }

  private:
    SplitChoice choose_split(size_t begin, size_t end, int depth, const FloatBox& box,
                             const FloatBox& centroids) {
        const size_t n = end - begin;
        SplitChoice choice;
        if (n == 1) {
            choice.leaf = true;
            return choice;
        }
        int axis = 0;
        for (int a = 1; a < 3; ++a) {
            if (centroids.hi[a] - centroids.lo[a] > centroids.hi[axis] - centroids.lo[axis])
                axis = a;
        }
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
                                      [&](const BuildPrimitive& p) { return p.c[axis] < pivot; });
            choice.mid = size_t(mid - prims_.begin());
            // The midpoint can round onto the largest centroid: then halve by count.
            if (choice.mid == begin || choice.mid == end)
                choice.mid = median_split(begin, end, axis);
            return choice;
        }
        return sah_split(begin, end, box, centroids);
    }

    size_t median_split(size_t begin, size_t end, int axis) {
        size_t mid = begin + (end - begin) / 2;
        std::nth_element(prims_.begin() + long(begin), prims_.begin() + long(mid),
                         prims_.begin() + long(end),
                         [axis](const BuildPrimitive& a, const BuildPrimitive& b) {
                             return a.c[axis] < b.c[axis];
                         });
        return mid;
    }

    /// Binned SAH (Wald 2007): one pass drops every centroid into one of
    /// kBins equal slices of the centroid bounds on each axis; sweeps over
    /// the bins then give the cost of all kBins - 1 planes per axis.
    SplitChoice sah_split(size_t begin, size_t end, const FloatBox& box,
                          const FloatBox& centroids) {
        const size_t n = end - begin;
        struct Bin {
            FloatBox box;
            uint32_t count = 0;
        };
        std::array<std::array<Bin, kBins>, 3> bins{};
        float origin[3], scale[3];
        for (int a = 0; a < 3; ++a) {
            origin[a] = centroids.lo[a];
            float extent = centroids.hi[a] - centroids.lo[a];
            scale[a] = extent > 0 ? kBins / extent : 0.0f;
        }
        for (size_t i = begin; i < end; ++i) {
            const BuildPrimitive& p = prims_[i];
            for (int a = 0; a < 3; ++a) {
                Bin& bin = bins[a][bin_index(p.c[a], origin[a], scale[a])];
                bin.box.expand(p.lo, p.hi);
                ++bin.count;
            }
        }

        double parent_area = box.area();
        double best_cost = INFINITY;
        int best_axis = -1, best_plane = 0;
        for (int a = 0; a < 3; ++a) {
            if (scale[a] == 0.0f) continue;
            // right_area[k], right_count[k]: everything in bins k .. kBins-1.
            std::array<double, kBins> right_area{};
            std::array<uint32_t, kBins> right_count{};
            FloatBox right;
            uint32_t count = 0;
            double area = 0;
            for (int k = kBins - 1; k > 0; --k) {
                // An empty bin changes nothing (most bins of a small node are empty).
                if (bins[a][k].count > 0) {
                    right.expand(bins[a][k].box);
                    count += bins[a][k].count;
                    area = right.area();
                }
                right_area[k] = area;
                right_count[k] = count;
            }
            FloatBox left;
            count = 0;
            for (int k = 1; k < kBins; ++k) {  // the plane between bins k-1 and k
                // Past an empty bin the plane splits as the previous one did.
                if (bins[a][k - 1].count == 0) continue;
                left.expand(bins[a][k - 1].box);
                count += bins[a][k - 1].count;
                if (right_count[k] == 0) break;
                double cost =
                    kTraversalCost + kIntersectionCost *
                                         (left.area() * count + right_area[k] * right_count[k]) /
                                         parent_area;
                if (cost < best_cost) {
                    best_cost = cost;
                    best_axis = a;
                    best_plane = k;
                }
            }
        }

        SplitChoice choice;
        // A box of zero area (collinear primitives) gives the SAH nothing to
        // weigh; halve by count then.
        if (best_axis < 0 || !(parent_area > 0)) {
            int axis = 0;
            for (int a = 1; a < 3; ++a)
                if (centroids.hi[a] - centroids.lo[a] > centroids.hi[axis] - centroids.lo[axis])
                    axis = a;
            choice.leaf = n <= max_leaf_;
            choice.axis = axis;
            if (!choice.leaf) choice.mid = median_split(begin, end, axis);
            return choice;
        }
        if (n <= max_leaf_ && kIntersectionCost * double(n) <= best_cost) {
            choice.leaf = true;
            return choice;
        }
        const int a = best_axis;
        auto mid = std::partition(prims_.begin() + long(begin), prims_.begin() + long(end),
                                  [&](const BuildPrimitive& p) {
                                      return bin_index(p.c[a], origin[a], scale[a]) < best_plane;
                                  });
        choice.axis = a;
        choice.mid = size_t(mid - prims_.begin());
        return choice;
    }

    /// The bin of a centroid coordinate; NaN-safe and clamped to [0, kBins).
    static int bin_index(float c, float origin, float scale) {
        float x = (c - origin) * scale;
        // std::max(0, NaN) is 0, so a NaN lands in bin 0 instead of being
        // converted to int (undefined behaviour).
        x = std::min(float(kBins - 1), std::max(0.0f, x));
        return int(x);
    }

    std::vector<BuildPrimitive> prims_;
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

    std::vector<BuildPrimitive> prims(n);
    for (uint32_t i = 0; i < n; ++i) {
        BBox b = padded_primitive_bounds(scene, i);
        BuildPrimitive& p = prims[i];
        round_box_outward(b, p.lo, p.hi);
        p.lo[3] = p.hi[3] = 0.0f;
        Vec3 c = b.centroid();
        for (int a = 0; a < 3; ++a)
            p.c[a] = float(std::clamp(c[a], -double(FLT_MAX), double(FLT_MAX)));
        p.id = i;
    }
    out.nodes.reserve(n);
    out.primitives.reserve(n);
    Builder builder(std::move(prims), settings.max_leaf, out.split, out);
    builder.build(0, n, 0);
    out.nodes.shrink_to_fit();
    return out;
}

}  // namespace pt
